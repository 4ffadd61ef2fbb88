/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedFsi.H"
#include "fvOptions.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedFsi::immersedFsi(const fvMesh& mesh)
:
    mesh_(mesh),
    methods_(fv::immersedMethod::all(fv::options::New(mesh)))
{}


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
    const fv::immersedMethod* limit = nullptr;
    for (const fv::immersedMethod& m : methods_)
    {
        const scalar dtm = m.maxDeltaT(maxCo);
        if (dtm < dt)
        {
            dt = dtm;
            limit = &m;
        }
    }
    if (limit)
    {
        runTime.setDeltaT(dt);
        Info<< "deltaT = " << dt << " (fvOption " << limit->name() << ": "
            << limit->maxDeltaTLimit(maxCo).c_str() << ")" << endl;
    }
}


void Foam::immersedFsi::advanceSolid()
{
    for (fv::immersedMethod& m : methods_)
    {
        m.advanceSolid();
    }
}


void Foam::immersedFsi::searchPairs()
{
    for (fv::immersedMethod& m : methods_)
    {
        m.searchPairs();
    }
}


bool Foam::immersedFsi::updateForce()
{
    bool converged = true;
    for (fv::immersedMethod& m : methods_)
    {
        converged = m.updateForce() && converged;
    }
    return converged;
}


void Foam::immersedFsi::write()
{
    for (fv::immersedMethod& m : methods_)
    {
        m.write();
    }
}


// ************************************************************************* //
