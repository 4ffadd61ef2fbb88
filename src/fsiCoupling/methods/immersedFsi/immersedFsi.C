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
    for (const fv::immersedMethod& m : methods_)
    {
        dt = min(dt, m.maxDeltaT(maxCo));
    }
    if (dt < runTime.deltaTValue())
    {
        runTime.setDeltaT(dt);
        Info<< "deltaT = " << dt << " (solid Courant number " << maxCo
            << ")" << endl;
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
