/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedForcing.H"
#include "fvMatrices.H"
#include "fvcGrad.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(immersedForcing, 0);

    addToRunTimeSelectionTable(option, immersedForcing, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::fv::immersedForcing::update()
{
    const Time& runTime = mesh_.time();
    if (updateIndex_ == runTime.timeIndex())
    {
        return;
    }
    updateIndex_ = runTime.timeIndex();

    immersedSolid& solid = coupling_.solid();
    const scalar dt = runTime.value() - solid.time();
    velocity0_ = solid.velocities();
    dt_ = dt;
    if (dt > 0)
    {
        solid.advance(dt);
    }
    coupling_.updatePairs();

    const immersedPairs& pairs = coupling_.pairs();
    coveredVelocity_ = coupling_.solidToFluid(solid.velocities());

    scalarField& chi = coverage_.primitiveFieldRef();
    chi = 0;
    UIndirectList<scalar>(chi, pairs.coveredCells()) = 1.0;
    coverage_.correctBoundaryConditions();

    Info<< type() << ' ' << name_ << ": solid at t = " << solid.time()
        << ", covered cells " << returnReduce(pairs.coveredCells().size(),
               sumOp<label>())
        << endl;
}


void Foam::fv::immersedForcing::fictitiousFluidForce(const volScalarField& p)
{
    immersedSolid& solid = coupling_.solid();
    const pointField& x = solid.points();
    const vectorField& v = solid.velocities();
    const List<solidTet>& elements = solid.elements();

    // Eq. 45: nodal pressures (every rank has every node)
    const scalarField ps(coupling_.fluidToSolid(p));

    vectorField& f = solid.externalForce();
    f.setSize(x.size());
    f = Zero;
    scalarField mass(x.size(), Zero);

    for (const solidTet& e : elements)
    {
        const vector d1(x[e[1]] - x[e[0]]);
        const vector d2(x[e[2]] - x[e[0]]);
        const vector d3(x[e[3]] - x[e[0]]);
        const tensor J(d1, d2, d3);     // rows
        const scalar Ve = det(J)/6;

        // Linear p in the element: J & grad p = (p1 - p0, p2 - p0, p3 - p0)
        const vector dp
        (
            ps[e[1]] - ps[e[0]], ps[e[2]] - ps[e[0]], ps[e[3]] - ps[e[0]]
        );
        const vector gradp(inv(J) & dp);

        for (const label n : e)
        {
            f[n] -= rhoFluid_*Ve/4*gradp;
            mass[n] += Ve/4;
        }
    }

    if (dt_ > 0 && velocity0_.size() == v.size())
    {
        f -= rhoFluid_*mass*(v - velocity0_)/dt_;
    }

    Info<< type() << ' ' << name_ << ": fictitious-fluid force on the"
        << " solid " << sum(f) << ", solid volume " << sum(mass) << endl;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::fv::immersedForcing::immersedForcing
(
    const word& name,
    const word& modelType,
    const dictionary& dict,
    const fvMesh& mesh
)
:
    option(name, modelType, dict, mesh),
    coupling_(mesh),
    coverage_
    (
        IOobject
        (
            "immersedCoverage",
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedScalar(dimless, Zero),
        "zeroGradient"
    ),
    coveredVelocity_(),
    updateIndex_(-1),
    rhoFluid_(0),
    velocity0_(),
    dt_(0),
    rowScale_
    (
        // OptimisationSwitches of the case's controlDict, then etc/
        mesh.time().controlDict().subOrEmptyDict("OptimisationSwitches")
       .getOrDefault<scalar>
        (
            "immersedForcingRowScale",
            debug::floatOptimisationSwitch("immersedForcingRowScale", 1e6)
        )
    )
{
    read(dict);

    // Coverage of the initial configuration
    coupling_.updatePairs();
    coveredVelocity_ = coupling_.solidToFluid(coupling_.solid().velocities());
    UIndirectList<scalar>
    (
        coverage_.primitiveFieldRef(), coupling_.pairs().coveredCells()
    ) = 1.0;
    coverage_.correctBoundaryConditions();
    updateIndex_ = mesh.time().timeIndex();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::fv::immersedForcing::constrain
(
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    update();
    unconstrained_.reset(new fvMatrix<vector>(eqn));

    const labelUList& cells = coupling_.pairs().coveredCells();
    eqn.setValues(cells, coveredVelocity_);

    // The covered rows are now decoupled (u = u_s); scaling their diagonal
    // and source together keeps u = u_s and makes 1/A small there, so the
    // projection's (1/A) grad p moves neither the covered cells nor the
    // flux of the faces between them (Brinkman limit, see the header)
    const scalar scale = rowScale_;
    scalarField& diag = eqn.diag();
    Field<vector>& source = eqn.source();
    for (const label celli : cells)
    {
        diag[celli] *= scale;
        source[celli] *= scale;
    }
}


Foam::vector Foam::fv::immersedForcing::fluidSource
(
    const volVectorField& U,
    const volScalarField& p
) const
{
    vector total(Zero);
    if (unconstrained_.valid())
    {
        const volVectorField residual(unconstrained_() & U);
        const volVectorField gradp(fvc::grad(p));
        const scalarField& V = mesh_.V();
        for (const label celli : coupling_.pairs().coveredCells())
        {
            total += rhoFluid_*V[celli]*(residual[celli] + gradp[celli]);
        }
    }
    reduce(total, sumOp<vector>());
    return total;
}


void Foam::fv::immersedForcing::correct(volVectorField& U)
{
    const word pName(coeffs_.getOrDefault<word>("p", "p"));
    const volScalarField& p = mesh_.lookupObject<volScalarField>(pName);
    fictitiousFluidForce(p);
    Info<< type() << ' ' << name_ << ": momentum source on the fluid "
        << fluidSource(U, p) << endl;
}


bool Foam::fv::immersedForcing::read(const dictionary& dict)
{
    if (option::read(dict))
    {
        fieldNames_.resize(1);
        fieldNames_.first() = coeffs_.getOrDefault<word>("U", "U");
        applied_.setSize(fieldNames_.size(), false);
        coeffs_.readEntry("rhoFluid", rhoFluid_);
        if (rhoFluid_ <= 0)
        {
            FatalIOErrorInFunction(coeffs_)
                << "rhoFluid " << rhoFluid_ << " is not positive"
                << exit(FatalIOError);
        }
        return true;
    }
    return false;
}


// ************************************************************************* //
