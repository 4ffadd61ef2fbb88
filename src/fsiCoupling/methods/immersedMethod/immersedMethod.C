/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedMethod.H"
#include "fvMatrices.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(immersedMethod, 0);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::fv::immersedMethod::immersedMethod
(
    const word& name,
    const word& modelType,
    const dictionary& dict,
    const fvMesh& mesh
)
:
    option(name, modelType, dict, mesh)
{}


// * * * * * * * * * * * * * * * Static Functions  * * * * * * * * * * * * * //

Foam::UPtrList<Foam::fv::immersedMethod>
Foam::fv::immersedMethod::all(optionList& options)
{
    UPtrList<immersedMethod> methods(options.size());
    label n = 0;
    forAll(options, i)
    {
        immersedMethod* m = dynamic_cast<immersedMethod*>(&options[i]);
        if (m)
        {
            methods.set(n++, m);
        }
    }
    methods.setSize(n);
    return methods;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::fv::immersedMethod::maxDeltaT(const scalar) const
{
    return GREAT;
}


Foam::string Foam::fv::immersedMethod::maxDeltaTLimit
(
    const scalar maxCo
) const
{
    return "the solid's Courant number " + Foam::name(maxCo);
}


void Foam::fv::immersedMethod::advanceSolid()
{}


void Foam::fv::immersedMethod::searchPairs()
{}


void Foam::fv::immersedMethod::setPressureReference(const label)
{}


void Foam::fv::immersedMethod::constrainFlux
(
    surfaceScalarField&,
    surfaceScalarField&
) const
{}


void Foam::fv::immersedMethod::constrainPressure
(
    fvScalarMatrix&,
    const volScalarField&
) const
{}


Foam::tmp<Foam::volVectorField>
Foam::fv::immersedMethod::pressureGradient(const volScalarField&) const
{
    return nullptr;
}


Foam::tmp<Foam::volVectorField>
Foam::fv::immersedMethod::correctPressure(volScalarField&) const
{
    return nullptr;
}


const Foam::volVectorField::Internal*
Foam::fv::immersedMethod::balancedForce() const
{
    return nullptr;
}


bool Foam::fv::immersedMethod::covers(const label) const
{
    return false;
}


// ************************************************************************* //
