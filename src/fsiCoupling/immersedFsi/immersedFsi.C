/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedFsi.H"
#include "immersedForcing.H"
#include "immersedElasticForce.H"
#include "fvOptions.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedFsi::immersedFsi(const fvMesh& mesh)
:
    mesh_(mesh),
    forcing_(),
    carried_()
{
    fv::optionList& opts = fv::options::New(mesh);
    forAll(opts, i)
    {
        fv::immersedForcing* f = dynamic_cast<fv::immersedForcing*>(&opts[i]);
        if (f)
        {
            forcing_.append(f);
        }
        fv::immersedElasticForce* e =
            dynamic_cast<fv::immersedElasticForce*>(&opts[i]);
        if (e)
        {
            carried_.append(e);
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedFsi::adjustDeltaT() const
{
    Time& runTime = const_cast<Time&>(mesh_.time());
    const dictionary& controlDict = runTime.controlDict();
    if (!active() || !controlDict.getOrDefault("adjustTimeStep", false))
    {
        return;
    }
    const scalar maxCo = controlDict.get<scalar>("maxCo");
    scalar dt = runTime.deltaTValue();
    for (const fv::immersedForcing* f : forcing_)
    {
        dt = min(dt, f->maxDeltaT(maxCo));
    }
    if (dt < runTime.deltaTValue())
    {
        runTime.setDeltaT(dt);
        Info<< "deltaT = " << dt << " (solid Courant number " << maxCo
            << ")" << endl;
    }
}


void Foam::immersedFsi::advanceSolid() const
{
    for (fv::immersedForcing* f : forcing_)
    {
        f->advanceSolid();
    }
}


void Foam::immersedFsi::searchPairs() const
{
    for (fv::immersedForcing* f : forcing_)
    {
        f->searchPairs();
    }
}


bool Foam::immersedFsi::updateForce() const
{
    bool converged = true;
    for (fv::immersedForcing* f : forcing_)
    {
        converged = f->updateForce() && converged;
    }
    for (fv::immersedElasticForce* e : carried_)
    {
        e->updateForce();
    }
    return converged;
}


void Foam::immersedFsi::write() const
{
    for (fv::immersedForcing* f : forcing_)
    {
        f->write();
    }
    for (fv::immersedElasticForce* e : carried_)
    {
        e->write();
    }
}


// ************************************************************************* //
