/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "carriedCouplingMap.H"
#include "fvm.H"
#include "fvc.H"
#include "fvMatrices.H"
#include "fixedValueFvPatchFields.H"
#include "zeroGradientFvPatchFields.H"
#include "clockTime.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::carriedCouplingMap::carriedCouplingMap
(
    const fvMesh& mesh,
    const word& owner
)
:
    mesh_(mesh),
    owner_(owner),
    ddtScheme_(),
    potential_(),
    solves_(0),
    applyTime_(4, 0.0)
{
    ITstream& ddt = mesh_.ddtScheme("ddt(U)");
    ddtScheme_ = word(ddt);
    ddt.rewind();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::surfaceScalarField> Foam::carriedCouplingMap::project
(
    const surfaceScalarField& phi,
    const scalar relTol
)
{
    if (!potential_.valid())
    {
        // the pressure's conditions, homogeneous: fixed where it is fixed
        const volScalarField& p = mesh_.lookupObject<volScalarField>("p");
        wordList types(p.boundaryField().size());
        forAll(types, patchi)
        {
            const word& patchType = mesh_.boundaryMesh()[patchi].type();
            if (polyPatch::constraintType(patchType))
            {
                types[patchi] = patchType;
            }
            else if (p.boundaryField()[patchi].fixesValue())
            {
                types[patchi] = fixedValueFvPatchScalarField::typeName;
            }
            else
            {
                types[patchi] = zeroGradientFvPatchScalarField::typeName;
            }
        }
        potential_.reset
        (
            new volScalarField
            (
                IOobject
                (
                    owner_ + ":couplingMapPotential",
                    mesh_.time().timeName(),
                    mesh_,
                    IOobject::NO_READ,
                    IOobject::NO_WRITE,
                    false
                ),
                mesh_,
                dimensionedScalar(phi.dimensions()/dimLength, Zero),
                types
            )
        );
        mesh_.setFluxRequired(potential_->name());
    }
    volScalarField& q = potential_.ref();
    q.primitiveFieldRef() = Zero;
    q.correctBoundaryConditions();

    fvScalarMatrix qEqn(fvm::laplacian(q) == fvc::div(phi));
    if (q.needReference())
    {
        qEqn.setReference(Pstream::master() ? 0 : -1, 0);
    }
    // the pressure's solver, to relTol of the right-hand side's own
    // residual (its tolerance made irrelevant)
    dictionary solverDict(mesh_.solverDict("p"));
    solverDict.set("relTol", relTol);
    solverDict.set("tolerance", 1e-30);
    // quietly: the map's users count its solves (solves())
    const int debug = solverPerformance::debug;
    solverPerformance::debug = 0;
    const solverPerformance perf = qEqn.solve(solverDict);
    solverPerformance::debug = debug;
    solves_ += perf.nIterations();
    return phi - qEqn.flux();
}


Foam::tmp<Foam::vectorField> Foam::carriedCouplingMap::respond
(
    const vectorField& F,
    const forceFluxMap& forceFlux,
    const velocityMap& velocity,
    const scalar relTol
)
{
    clockTime clock;
    const tmp<surfaceScalarField> flux(forceFlux(F));
    applyTime_[1] += clock.timeIncrement();
    const tmp<surfaceScalarField> projected(project(flux(), relTol));
    applyTime_[2] += clock.timeIncrement();
    tmp<vectorField> v(velocity(projected()));
    applyTime_[3] += clock.timeIncrement();
    return v;
}


Foam::tmp<Foam::vectorField> Foam::carriedCouplingMap::apply
(
    const vectorField& w,
    const stiffnessMap& stiffness,
    const forceFluxMap& forceFlux,
    const velocityMap& velocity,
    const scalar relTol
)
{
    clockTime clock;
    vectorField dF;
    string why;
    if (!stiffness(w, dF, why))
    {
        FatalErrorInFunction
            << "fvOption " << owner_ << ": the leaflets' stiffness for the"
            << " coupling's map at time " << mesh_.time().timeName()
            << ": " << why.c_str() << exit(FatalError);
    }
    applyTime_[0] += clock.timeIncrement();
    // dF = -K w: the map D K w is minus the velocity it gives
    return -respond(dF, forceFlux, velocity, relTol);
}


Foam::scalar Foam::carriedCouplingMap::orthogonalise
(
    const PtrList<vectorField>& Q,
    const label k,
    vectorField& v,
    Eigen::MatrixXd& H
)
{
    for (label pass = 0; pass < 2; ++pass)
    {
        for (label i = 0; i <= k; ++i)
        {
            const scalar h = sum(Q[i] & v);
            H(i, k) += h;
            v -= h*Q[i];
        }
    }
    return Foam::sqrt(sum(magSqr(v)));
}


// ************************************************************************* //
