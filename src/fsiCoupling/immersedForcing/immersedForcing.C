/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedForcing.H"
#include "fvMatrices.H"
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


bool Foam::fv::immersedForcing::read(const dictionary& dict)
{
    if (option::read(dict))
    {
        fieldNames_.resize(1);
        fieldNames_.first() = coeffs_.getOrDefault<word>("U", "U");
        applied_.setSize(fieldNames_.size(), false);
        return true;
    }
    return false;
}


// ************************************************************************* //
