/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedElasticForce.H"
#include "deformableSolid.H"
#include "fvMatrices.H"
#include "readEnumEntry.H"
#include "checkRemovedEntries.H"
#include "clockTime.H"
#include "zeroGradientFvPatchFields.H"
#include "OFstream.H"
#include "wallPolyPatch.H"
#include "fixedValueFvPatchFields.H"
#include "IFstream.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(immersedElasticForce, 0);
    addToRunTimeSelectionTable(option, immersedElasticForce, dictionary);
}
}

const Foam::Enum<Foam::fv::immersedElasticForce::pointSet>
Foam::fv::immersedElasticForce::pointSetNames
({
    { pointSet::nodes, "nodes" },
    { pointSet::elements, "elements" },
});


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::tmp<Foam::pointField>
Foam::fv::immersedElasticForce::transferPoints() const
{
    const pointField& x = solidPtr_->points();
    if (!elementPoints_)
    {
        return tmp<pointField>(new pointField(x));
    }
    const List<solidTet>& tets = solidPtr_->elements();
    tmp<pointField> tq(new pointField(x.size() + tets.size()));
    pointField& q = tq.ref();
    SubList<point>(q, x.size()) = x;
    forAll(tets, e)
    {
        const solidTet& t = tets[e];
        q[x.size() + e] = 0.25*(x[t[0]] + x[t[1]] + x[t[2]] + x[t[3]]);
    }
    return tq;
}


bool Foam::fv::immersedElasticForce::ownSample(const label a) const
{
    // a node held in every component (a tether, or a support whose force
    // goes to the wall) keeps its own sample alone: its force does not
    // reach the fluid through its elements' centroids
    return cmptSum(free_[a]) == 0 || nodeElements_[a].empty();
}


Foam::tmp<Foam::vectorField> Foam::fv::immersedElasticForce::toNodes
(
    const vectorField& uq
) const
{
    const label n = solidPtr_->nPoints();
    if (!elementPoints_)
    {
        return tmp<vectorField>(new vectorField(uq));
    }
    // v_a = (u_a + sum_{e ni a} V_e u_e / sum_{e ni a} V_e)/2: the lumped
    // L2 projection onto the solid's linear elements of the fluid velocity
    // sampled at the nodes and the centroids (the quadrature weight of each
    // element split V_e/8 to each vertex, V_e/2 to the centroid;
    // interaction points denser than the nodes, as in Griffith & Luo, Int
    // J Numer Meth Biomed Eng 33(12) e2888, 2017, so that fewer of the
    // fluid cells the solid passes through are left unsampled)
    tmp<vectorField> tv(new vectorField(n, Zero));
    vectorField& v = tv.ref();
    forAll(v, a)
    {
        if (ownSample(a))
        {
            v[a] = uq[a];
            continue;
        }
        vector mean(Zero);
        for (const label e : nodeElements_[a])
        {
            mean += elementVolume_[e]*uq[n + e];
        }
        v[a] = 0.5*uq[a] + 0.5*mean/nodeElementVolume_[a];
    }
    return tv;
}


Foam::tmp<Foam::vectorField> Foam::fv::immersedElasticForce::fromNodes
(
    const vectorField& F
) const
{
    if (!elementPoints_)
    {
        return tmp<vectorField>(new vectorField(F));
    }
    // the transpose of toNodes()
    const label n = solidPtr_->nPoints();
    tmp<vectorField> tFq(new vectorField(n + solidPtr_->nElements(), Zero));
    vectorField& Fq = tFq.ref();
    forAll(F, a)
    {
        if (ownSample(a))
        {
            Fq[a] += F[a];
            continue;
        }
        Fq[a] += 0.5*F[a];
        const vector Fe = 0.5*F[a]/nodeElementVolume_[a];
        for (const label e : nodeElements_[a])
        {
            Fq[n + e] += elementVolume_[e]*Fe;
        }
    }
    return tFq;
}


bool Foam::fv::immersedElasticForce::keepsStencil(const label i) const
{
    // a tether does not move: its stencil is the first one
    return stencilsBuilt_ && i < solidPtr_->nPoints() && tethered_[i];
}


Foam::labelList Foam::fv::immersedElasticForce::locate(const pointField& x)
{
    const label nNodes = solidPtr_->nPoints();

    // the local cell of every free transfer point and the lowest rank
    // holding it (immersedPointLocator). A tether keeps its first stencil;
    // a held node that is not a tether gets no stencil (rank -1);
    // centroids are free
    boolList active(x.size(), true);
    forAll(x, i)
    {
        active[i] =
            !keepsStencil(i)
         && !(i < nNodes && cmptSum(free_[i]) == 0 && !tethered_[i]);
    }
    labelList cells;
    labelList rank(locator_->locate(x, cells, active));
    forAll(x, i)
    {
        if (keepsStencil(i))
        {
            rank[i] = tetherRank_[i];
        }
        else
        {
            transfer_.setCell(i, cells[i]);
        }
    }
    return rank;
}


void Foam::fv::immersedElasticForce::placeOutside
(
    const pointField& x,
    labelList& rank
)
{
    // a free node outside the fluid (beside the faceted root wall, which
    // cuts inside the true wall where it is concave): its nearest cell's
    // stencil, the weights clamped to that cell's nearest tet, so that it
    // follows the fluid beside it (and the wall contact pushes it back);
    // the rank with the nearest cell centre takes it
    const label n = x.size();
    const label nNodes = solidPtr_->nPoints();
    outside_ = 0;
    scalarField nearest(n, GREAT);
    labelList nearestCell(n, -1);
    forAll(x, i)
    {
        if (rank[i] == Pstream::nProcs())
        {
            if (i < nNodes && !tethered_[i])
            {
                ++outside_;
            }
            if (mesh_.nCells())
            {
                const label c = locator_->search().findNearestCell
                (
                    x[i],
                    locator_->hint(i),
                    true
                );
                nearestCell[i] = c;
                nearest[i] = mag(mesh_.cellCentres()[c] - x[i]);
            }
        }
    }
    if (!returnReduce(min(nearest) < GREAT, orOp<bool>()))
    {
        return;
    }
    scalarField best(nearest);
    Pstream::listCombineGather(best, minEqOp<scalar>());
    Pstream::listCombineScatter(best);
    labelList owner(n, Pstream::nProcs());
    forAll(x, i)
    {
        if (nearestCell[i] >= 0 && nearest[i] <= best[i])
        {
            owner[i] = Pstream::myProcNo();
        }
    }
    Pstream::listCombineGather(owner, minEqOp<label>());
    Pstream::listCombineScatter(owner);
    forAll(x, i)
    {
        if (rank[i] == Pstream::nProcs())
        {
            rank[i] = owner[i];
            if (owner[i] == Pstream::myProcNo())
            {
                transfer_.setCell(i, nearestCell[i]);
                locator_->setHint(i, nearestCell[i]);
            }
        }
    }
}


void Foam::fv::immersedElasticForce::updateStencils()
{
    const tmp<pointField> tx(transferPoints());
    const pointField& x = tx();
    labelList rank(locate(x));
    placeOutside(x, rank);
    forAll(x, i)
    {
        if (rank[i] != Pstream::myProcNo())
        {
            transfer_.setCell(i, -1);
        }
        else if (!keepsStencil(i))
        {
            transfer_.setWeights(i, x[i]);
        }
    }
    if (!stencilsBuilt_)
    {
        tetherRank_ = rank;
        stencilsBuilt_ = true;
    }
}


void Foam::fv::immersedElasticForce::spread
(
    const vectorField& F,
    vectorField& s
) const
{
    transfer_.spread(fromNodes(F), rhoFluid_, s);
}


Foam::tmp<Foam::vectorField> Foam::fv::immersedElasticForce::gather
(
    const vectorField& u
) const
{
    return toNodes(transfer_.gather(u));
}


void Foam::fv::immersedElasticForce::setTetherMobility()
{
    // D_i = sum_c w_ic W_c/(rho V_c), W_c = sum_j w_jc over the tethered
    // nodes: the row sums of the tethers' mobility W M^-1 W^T (the fluid
    // velocity a unit force on every tether gives at each), an upper
    // bound of its largest eigenvalue (Gershgorin), so that the feedback
    // below is stable for relaxation <= 1
    vectorField unit(solidPtr_->nPoints(), Zero);
    forAll(unit, i)
    {
        if (tethered_[i])
        {
            unit[i] = vector::one;
        }
    }
    vectorField s;
    spread(unit, s);
    const vectorField D(gather(s));
    tetherMobility_.setSize(D.size());
    forAll(D, i)
    {
        tetherMobility_[i] = tethered_[i] ? D[i].x() : 0;
    }
}


bool Foam::fv::immersedElasticForce::implicitTethers() const
{
    return implicitForce_.valid() && implicitForce_->implicitTethers();
}


bool Foam::fv::immersedElasticForce::spreadForce
(
    const vectorField& v,
    const bool advanceDrift,
    string& why
)
{
    const scalar dt = mesh_.time().deltaTValue();
    clockTime clock;
    vectorField& F = nodeForce_;
    const scalar beta = stepDamping_ > 0 ? stepDamping_*dt : baseDamping_;
    if (implicitForce_.valid())
    {
        // the look-ahead force: of x + (theta dt + beta) v, the
        // configuration the nodes reach at the step's end (theta 1) or
        // middle (1/2) at their present velocity (correctImplicit() adds
        // the change of that velocity)
        solid_->setStiffnessDamping(implicitForce_->theta()*dt + beta);
    }
    else if (stepDamping_ > 0)
    {
        // the force of x + beta v, beta a fraction of the step
        // (carriedStableStep.H: under backward, b >= 1/2 keeps every mode
        // from growing)
        solid_->setStiffnessDamping(beta);
    }
    if (!solid_->interactionForce(dt, F, why))
    {
        return false;
    }
    solidTime_ += clock.timeIncrement();

    // The tethers: a node held still (the attachment, sewn to the root)
    // holds the fluid at rest where it is. The fluid at it would otherwise
    // not see the leaflet there (its force goes to the support) and flow
    // through the attachment band. Feedback on the fluid's velocity v at
    // the node and its drift xi (the target points of immersed boundary
    // methods; Peskin, Acta Numerica 11:479, 2002, Sect. 6):
    //     F_i = -(alpha v_i + beta xi_i/dt)/(dt D_i),  xi_i += dt v_i
    // The drift's term is a spring of stiffness tetherStiffness/(dt^2 D_i): at a
    // change of step the drift is scaled by (dt/dt_old)^2, so the force
    // it holds carries over (unscaled, a step cut by 4 would multiply it
    // by 16). On a restart the first update's step is the one the drift
    // was written with (uniform/time's deltaT), so nothing is scaled.
    // In the implicit force's solve instead (carriedImplicitForce.H) a
    // damper and a spring per unit time, -(v/t_v + xi/t_x^2)/D_i at the
    // step's end: the look-ahead of v and xi + dt v here (the drift
    // rescaled only where the rates' scale changes, so that the spring's
    // force carries over: carriedImplicitForce::tetherRates).
    // kept for a step refused below (nothing changed then)
    const vectorField drift0(tetherDrift_);
    const scalar rateScale0 = tetherRateScale_;
    const scalar driftStep0 = tetherDriftStep_;
    const bool implicitTethers = this->implicitTethers();
    scalar dampingRate = 0, springRate = 0;
    if (implicitTethers)
    {
        const scalar scale =
            implicitForce_->tetherRates(dt, dampingRate, springRate);
        if (tetherRateScale_ > 0 && scale != tetherRateScale_)
        {
            tetherDrift_ *= tetherRateScale_/scale;
        }
        tetherRateScale_ = scale;
    }
    else if (tetherDriftStep_ > 0 && dt != tetherDriftStep_)
    {
        tetherDrift_ *= sqr(dt/tetherDriftStep_);
    }
    tetherDriftStep_ = dt;
    tetherForce_ = Zero;
    forAll(F, i)
    {
        if (tethered_[i] && tetherMobility_[i] > 0)
        {
            if (advanceDrift)
            {
                tetherDrift_[i] += dt*v[i];
            }
            const vector Ft =
                implicitTethers
              ? vector
                (
                   -(
                        dampingRate*v[i]
                      + springRate*(tetherDrift_[i] + dt*v[i])
                    )/tetherMobility_[i]
                )
              : vector
                (
                   -(tetherRelaxation_*v[i] + tetherStiffness_*tetherDrift_[i]/dt)
                   /(dt*tetherMobility_[i])
                );
            F[i] += Ft;
            tetherForce_ += Ft;
        }
    }

    vectorField& s = force_.field();
    const vectorField Fq(fromNodes(F));
    transfer_.spread(Fq, rhoFluid_, s);

    const scalarField& V = mesh_.V();

    // A blown-up solid: its force would move the fluid of a cell by
    // dt^2 |s| (s the force per unit mass) more than maxCellMoves of the
    // cell's length, V^(1/3), in one step. The flow moves its fluid less
    // than a cell a step (its Courant number) and the tethers' force
    // stops the fluid at a node within a step (its velocity at most): a
    // hundred cells is out of reach of either. Handed to the fluid, such a
    // force ends in the pressure solver's floating-point trap.
    scalar moves = 0;
    forAll(s, celli)
    {
        moves = max(moves, sqr(dt)*mag(s[celli])/Foam::cbrt(V[celli]));
    }
    reduce(moves, maxOp<scalar>());
    if (!(moves <= maxCellMoves_))
    {
        tetherDrift_ = drift0;
        tetherRateScale_ = rateScale0;
        tetherDriftStep_ = driftStep0;
        why =
            "its force would move the fluid of a cell "
          + Foam::name(moves) + " of the cell's lengths in one step (above "
          + Foam::name(maxCellMoves_) + "): the solid has blown up";
        return false;
    }

    vector total(Zero);
    forAll(Fq, i)
    {
        if (transfer_.cell(i) >= 0)
        {
            total += Fq[i];
        }
    }
    fluidForce_ = Zero;
    forAll(s, celli)
    {
        fluidForce_ += rhoFluid_*V[celli]*s[celli];
    }
    reduce(fluidForce_, sumOp<vector>());
    reduce(total, sumOp<vector>());
    wallForce_ = total - fluidForce_;
    forceTime_ += clock.timeIncrement();
    return true;
}


void Foam::fv::immersedElasticForce::failed(const string& why) const
{
    FatalErrorInFunction
        << "fvOption " << name_ << ": the immersed solid failed at time "
        << mesh_.time().timeName() << ": " << why.c_str()
        << "; the last written time is kept. Reduce maxDeltaT in"
        << " system/controlDict (the leaflets' stiffness limits the"
        << " step of this coupling)" << exit(FatalError);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::fv::immersedElasticForce::immersedElasticForce
(
    const word& name,
    const word& modelType,
    const dictionary& dict,
    const fvMesh& mesh
)
:
    immersedMethod(name, modelType, dict, mesh),
    solidPtr_(immersedSolid::New(mesh.time())),
    solid_(dynamic_cast<immersedSolids::deformable*>(solidPtr_.get())),
    rhoFluid_(0),
    free_(),
    elementPoints_(false),
    nodeElements_(),
    nodeElementVolume_(),
    elementVolume_(),
    transfer_(mesh),
    locator_(),
    smallCell_(0.2),
    wallCondition_(cellTetTransfer::wallCondition::free),
    wallPoints_(0),
    force_
    (
        IOobject
        (
            "immersedBalancedForce",
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        mesh,
        dimensionedVector(dimAcceleration, Zero)
    ),
    tethered_(),
    tetherDrift_(),
    tetherDriftStep_(0),
    tetherRateScale_(0),
    lastVelocity_(),
    tetherRank_(),
    stencilsBuilt_(false),
    tetherMobility_(),
    tetherRelaxation_(0.5),
    tetherStiffness_(0.1),
    tetherForce_(Zero),
    nodeForce_(),
    fluidForce_(Zero),
    wallForce_(Zero),
    outside_(0),
    reconstruction_(),
    couplingMap_(mesh, name),
    stableStep_(mesh, couplingMap_, name, dictionary::null),
    estimateStep_(false),
    implicitForce_(),
    baseDamping_(0),
    stepDamping_(0),
    refusals_(0),
    stepRetries_(0),
    retries_(0),
    updateIndex_(mesh.time().timeIndex()),
    probes_(solidPtr_()),
    solidTime_(0),
    searchTime_(0),
    forceTime_(0),
    stepTime_(0),
    implicitTime_(0)
{
    read(dict);

    checkSolid();
    baseDamping_ = solid_->stiffnessDamping();

    const label n = solidPtr_->nPoints();
    free_ = solidPtr_->freeComponents();
    const label nq = n + (elementPoints_ ? solidPtr_->nElements() : 0);
    transfer_.setSize(nq);
    if (elementPoints_)
    {
        setElementPoints();
    }

    readState(solidPtr_->stateDir());
    if (tetherRelaxation_ > 0 || tetherStiffness_ > 0)
    {
        forAll(free_, i)
        {
            tethered_[i] = (cmptSum(free_[i]) == 0);
        }
    }
    transfer_.setPointData(smallCell_);
    // the sharp method's walk limit (immersedPairs' maxWalk default)
    locator_.reset(new immersedPointLocator(mesh, 100));
    updateStencils();
    setTetherMobility();
    // after the tethers' mobility, which is taken with the wall points
    // free: its row sums, one number per tether for the same unit force in
    // every component, take a single component of the result, and with
    // the walls' normal components removed (slip) that component can come
    // out near zero at a tether by the wall, its inverse the tethers' gain
    // (their force grew tenfold a step from the start)
    checkWallPoints();
    wallPoints_ = transfer_.setWallPoints(wallCondition_);
    // the force of the start time: on a restart with the tethers' state,
    // as the interrupted run had it for this step
    string why;
    if (!spreadForce(lastVelocity_, false, why))
    {
        failed(why);
    }

    report();
    if
    (
        estimateStep_
     && !stableStep_.readState(solidPtr_->stateDir(), solidPtr_->nPoints())
    )
    {
        estimateStableStep();
    }

    // the solid's output at the start time
    solidPtr_->write(true);
}


void Foam::fv::immersedElasticForce::checkSolid() const
{
    if (!solid_)
    {
        FatalIOErrorInFunction(solidPtr_->dict())
            << "fvOption " << name_ << " (type " << typeName << ") moves a"
            << " deformable solid with the fluid; " << solidPtr_->dict().name()
            << " has type " << solidPtr_->type() << ": set type deformable,"
            << " or use fvOption type immersedForcing for a rigid solid"
            << exit(FatalIOError);
    }

    // the fluid carries the solid's mass: as dense as the fluid, or the
    // interaction force would need the inertia -(rho_s - rho_f) dv/dt
    const scalar rhoSolid =
        solidPtr_->dict().subDict("material").get<scalar>("rho");
    if (mag(rhoSolid - rhoFluid_) > 1e-6*rhoFluid_)
    {
        FatalIOErrorInFunction(solidPtr_->dict())
            << "fvOption " << name_ << " (type " << typeName << "): the"
            << " fluid carries the solid's mass, so the solid must be as"
            << " dense as the fluid: material rho " << rhoSolid << " in "
            << solidPtr_->dict().name() << " against rhoFluid " << rhoFluid_
            << " in the fvOption. Set them equal (blood and leaflets:"
            << " 1000), or use type immersedForcing for a denser solid"
            << exit(FatalIOError);
    }
}


void Foam::fv::immersedElasticForce::checkWallPoints() const
{
    if
    (
        wallCondition_ != cellTetTransfer::wallCondition::noSlip
     || !mesh_.foundObject<volVectorField>(fieldNames_[0])
    )
    {
        return;
    }
    // the wall points carry zero, the value of a wall at rest: a moving
    // wall's velocity, or a wall the fluid slips along, would be lost
    const volVectorField& U =
        mesh_.lookupObject<volVectorField>(fieldNames_[0]);
    for (const fvPatchVectorField& Up : U.boundaryField())
    {
        if (!isA<wallPolyPatch>(Up.patch().patch()))
        {
            continue;
        }
        const scalar magU =
            returnReduce(Up.size() ? max(mag(Up)) : scalar(0), maxOp<scalar>());
        // (calculated fixes its value too, but nothing holds it)
        if (!isA<fixedValueFvPatchVectorField>(Up) || magU > 0)
        {
            FatalIOErrorInFunction(coeffs_)
                << "fvOption " << name_ << ": wallPoints noSlip holds the"
                << " wall points at rest, but wall patch "
                << Up.patch().name() << " has " << U.name() << " of type "
                << Up.type() << " (largest value " << magU << " m/s). Give"
                << " it noSlip (or a fixedValue of zero), or set wallPoints"
                << " slip or free" << exit(FatalIOError);
        }
    }
}


void Foam::fv::immersedElasticForce::setElementPoints()
{
    const label n = solidPtr_->nPoints();
    // the elements' reference volumes and the nodes' elements
    const List<solidTet>& tets = solidPtr_->elements();
    const pointField& X = solidPtr_->points0();
    elementVolume_.setSize(tets.size());
    List<DynamicList<label>> around(n);
    forAll(tets, e)
    {
        const solidTet& t = tets[e];
        elementVolume_[e] = mag
        (
            ((X[t[1]] - X[t[0]]) ^ (X[t[2]] - X[t[0]])) & (X[t[3]] - X[t[0]])
        )/6;
        for (const label a : t)
        {
            around[a].append(e);
        }
    }
    nodeElements_.setSize(n);
    nodeElementVolume_.setSize(n, 0);
    forAll(around, a)
    {
        nodeElements_[a].transfer(around[a]);
        for (const label e : nodeElements_[a])
        {
            nodeElementVolume_[a] += elementVolume_[e];
        }
    }
}


void Foam::fv::immersedElasticForce::readState(const fileName& stateDir)
{
    const label n = solidPtr_->nPoints();
    // A restart: the solid's state of the start time
    solidPtr_->restart(type() + ' ' + name_);

    tethered_.setSize(n, false);
    tetherDrift_.setSize(n, Zero);
    lastVelocity_.setSize(n, Zero);
    // the tethers' state of a restart: their drift and the velocity of
    // the last update (their feedback)
    for (const word file : {"tetherDrift", "tetherVelocity"})
    {
        if (!isFile(stateDir/file))
        {
            continue;
        }
        IFstream is(stateDir/file);
        vectorField values(is);
        if (values.size() != n)
        {
            FatalIOErrorInFunction(is)
                << "fvOption " << name_ << ": " << is.name() << " holds "
                << values.size() << " vectors for a solid of " << n
                << " nodes: the restart state does not belong to this"
                << " solid (remove " << stateDir << " to start the solid"
                << " from its mesh)" << exit(FatalIOError);
        }
        (file == "tetherDrift" ? tetherDrift_ : lastVelocity_) = values;
    }
}


Foam::tmp<Foam::surfaceScalarField>
Foam::fv::immersedElasticForce::forceFlux(const vectorField& F) const
{
    if (!reconstruction_.valid())
    {
        reconstruction_.reset(new balancedForceFlux(mesh_));
    }
    volVectorField f
    (
        IOobject
        (
            name_ + ":nodeForce",
            mesh_.time().timeName(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            false
        ),
        mesh_,
        dimensionedVector(dimAcceleration/dimTime, Zero),
        zeroGradientFvPatchVectorField::typeName
    );
    spread(F, f.primitiveFieldRef());
    f.correctBoundaryConditions();
    return reconstruction_->flux(f);
}


Foam::carriedCouplingMap::stiffnessMap
Foam::fv::immersedElasticForce::stiffnessMap() const
{
    return [this](const vectorField& w, vectorField& dF, string& why)
    {
        return solid_->stiffnessAction(w, dF, why);
    };
}


Foam::carriedCouplingMap::forceFluxMap
Foam::fv::immersedElasticForce::forceFluxMap() const
{
    return [this](const vectorField& F) { return forceFlux(F); };
}


Foam::carriedCouplingMap::velocityMap
Foam::fv::immersedElasticForce::velocityMap() const
{
    if (!reconstruction_.valid())
    {
        reconstruction_.reset(new balancedForceFlux(mesh_));
    }
    return [this](const surfaceScalarField& phi)
    {
        return gather(reconstruction_->reconstruct(phi)().primitiveField());
    };
}


void Foam::fv::immersedElasticForce::correctImplicit(vectorField& v)
{
    if (lastVelocity_.size() != v.size())
    {
        return;
    }
    clockTime clock;
    const scalar dt = mesh_.time().deltaTValue();
    const scalar beta = stepDamping_ > 0 ? stepDamping_*dt : baseDamping_;
    // the fluid's velocity change per unit acceleration over the step:
    // rAU with the momentum's diagonal taken as its inertia alone (dt
    // under Euler, 2 dt/3 under backward: 3 u^{n+1}/(2 dt))
    const scalar a = implicitForce_->response(dt);

    // The force F(x^n + (theta dt + beta) v^{n+1}) (theta 1: of the
    // step's end) is the look-ahead force handed to the fluid,
    // F(x^n + (theta dt + beta) v^n), less (theta dt + beta) K dv,
    // dv = v^{n+1} - v^n: the fluid's response to it,
    // a (theta dt + beta) D K dv (D K the map of carriedCouplingMap),
    // taken with the velocity change the look-ahead force gave, r:
    //     (I + a (theta dt + beta) D K) dv = r
    const scalar lookAhead = implicitForce_->theta()*dt + beta;
    // the tethers in the solve (carriedImplicitForce.H): their velocity
    // change too, with the damping (1/t_v + dt/t_x^2)/D_i
    vectorField mask(free_);
    scalarField tetherDamping(v.size(), 0);
    if (implicitTethers())
    {
        scalar dampingRate = 0, springRate = 0;
        implicitForce_->tetherRates(dt, dampingRate, springRate);
        const scalar rate = dampingRate + dt*springRate;
        forAll(v, i)
        {
            if (tethered_[i] && tetherMobility_[i] > 0)
            {
                tetherDamping[i] = rate/tetherMobility_[i];
                mask[i] = vector::one;
            }
        }
    }
    const vectorField r(cmptMultiply(v - lastVelocity_, mask));
    vectorField dv;
    const label iterations = implicitForce_->solve
    (
        r,
        free_,
        a,
        lookAhead,
        tetherDamping,
        stiffnessMap(),
        forceFluxMap(),
        velocityMap(),
        dv
    );
    const vectorField dF
    (
        implicitForce_->force
        (
            dv, free_, lookAhead, tetherDamping, stiffnessMap()
        )
    );

    // the fluid corrected by the force's change, projected (one more
    // Poisson solve, by the pressure's solver to correctionTolerance of
    // the correction's own divergence: the corrected flux's divergence
    // error a small part of the correction's, itself a small part of the
    // flow; on the coarse valve Q_inlet and Q_outlet then agree to 3e-6
    // of the closed valve's flow, and the step costs 10-20 % less than
    // with the final pressure solver's absolute 1e-8): flux, cells (the
    // reconstruction) and pressure
    surfaceScalarField& phi =
        mesh_.lookupObjectRef<surfaceScalarField>("phi");
    volVectorField& U = mesh_.lookupObjectRef<volVectorField>(fieldNames_[0]);
    volScalarField& p = mesh_.lookupObjectRef<volScalarField>("p");
    const tmp<surfaceScalarField> dphi
    (
        couplingMap_.project
        (
            forceFlux(dF), implicitForce_->correctionTolerance()
        )
    );
    // (the map's fields carry nominal dimensions: values only)
    phi.primitiveFieldRef() += a*dphi().primitiveField();
    forAll(phi.boundaryField(), patchi)
    {
        phi.boundaryFieldRef()[patchi] += a*dphi().boundaryField()[patchi];
    }
    U.primitiveFieldRef() +=
        a*reconstruction_->reconstruct(dphi())().primitiveField();
    U.correctBoundaryConditions();
    p.primitiveFieldRef() += couplingMap_.potential().primitiveField();
    p.correctBoundaryConditions();

    v = nodeVelocity(U);
    implicitTime_ += clock.timeIncrement();
    Info<< type() << ' ' << name_ << ": implicit force: " << iterations
        << " iterations, residual " << implicitForce_->residual() << "; |r| "
        << max(mag(r)) << ", |dv| " << max(mag(dv)) << ", |v - v^n - dv| "
        << max(mag(cmptMultiply(v - lastVelocity_ - dv, mask)))
        << " m/s; force change at the nodes " << sum(dF) << " N; "
        << implicitTime_ << " s so far (map: stiffness, flux,"
        << " projection, velocity " << couplingMap_.applyTime() << " s)"
        << endl;
}


void Foam::fv::immersedElasticForce::estimateStableStep(const bool fresh)
{
    clockTime clock;
    stableStep_.estimate
    (
        fresh,
        free_,
        stiffnessMap(),
        forceFluxMap(),
        velocityMap()
    );
    stepTime_ += clock.timeIncrement();
    const label peak = stableStep_.modePeak();
    stableStep_.report(Info, solid_->stiffnessDamping());
    if (peak >= 0)
    {
        Info<< "; mode largest at node " << peak << " ("
            << solidPtr_->points()[peak] << ")";
    }
    Info<< "; " << stepTime_ << " s so far" << endl;
}


void Foam::fv::immersedElasticForce::report() const
{
    const label n = solidPtr_->nPoints();
    label fixedNodes = 0;
    forAll(free_, i)
    {
        if (cmptSum(free_[i]) == 0)
        {
            ++fixedNodes;
        }
    }
    Info<< type() << ' ' << name_ << ": " << n << " nodes ("
        << fixedNodes << " held), " << solidPtr_->nElements()
        << " elements; transfer points: "
        << (elementPoints_ ? "nodes and element centroids" : "nodes")
        << "; " << outside_ << " free nodes outside the fluid mesh"
        << " (taken in their nearest cell); " << transfer_.nSmallCells() << " cells"
        << " smaller than " << smallCell_ << " of the cells around them"
        << " take their centre's value from their points; "
        << (
               wallCondition_ == cellTetTransfer::wallCondition::free
             ? string("wall points free")
             : Foam::name(wallPoints_) + " wall points "
             + (
                   wallCondition_ == cellTetTransfer::wallCondition::slip
                 ? "with no normal velocity (slip)"
                 : "at rest (noSlip)"
               )
           ).c_str()
        << "; force on the fluid "
        << fluidForce_ << " N, on the walls " << wallForce_ << " N" << nl
        << endl;
}


Foam::fv::immersedElasticForce::~immersedElasticForce()
{}


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

// The time step again from its start t0 at the length dt. Time::setDeltaT
// leaves the length Time::operator++ saves for the next step's deltaT0
// (TimeState::deltaTSave_) at the refused length: the next step's
// backward time derivative would take the refused length for the old
// step's (a step halved and the next as long: 7/6 of a steady
// acceleration). Reached through a class derived from TimeState, the
// only access to it.
struct stepRepeat
:
    public Foam::TimeState
{
    static void set(Foam::Time& runTime, const Foam::scalar dt)
    {
        runTime.*(&stepRepeat::deltaTSave_) = dt;
    }
};

void repeatStep
(
    Foam::Time& runTime,
    const Foam::scalar t0,
    const Foam::scalar dt
)
{
    runTime.setDeltaT(dt, false);
    runTime.setTime(t0 + dt, runTime.timeIndex());
    stepRepeat::set(runTime, dt);
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::vectorField> Foam::fv::immersedElasticForce::nodeVelocity
(
    const volVectorField& U
) const
{
    // the reconstruction of the face flux the projection left, the velocity
    // whose face balance holds the force (balancedForce)
    if (!reconstruction_.valid())
    {
        reconstruction_.reset(new balancedForceFlux(mesh_));
    }
    const surfaceScalarField& phi =
        mesh_.lookupObject<surfaceScalarField>("phi");
    return gather(reconstruction_->reconstruct(phi)().primitiveField());
}


bool Foam::fv::immersedElasticForce::refuseStep(const vectorField& v)
{
    Time& runTime = const_cast<Time&>(mesh_.time());
    const scalar growth = stableStep_.refuseGrowth();
    if
    (
        !estimateStep_
     || !(growth > 0)
     || refusals_ > 0   // the step again at the bound just estimated
     || !runTime.controlDict().getOrDefault("adjustTimeStep", false)
    )
    {
        return false;
    }
    // the nodes are the same on every rank (v summed over the ranks)
    const scalar vNew = max(mag(v));
    const scalar vOld = max(mag(lastVelocity_));
    if (!(vOld > 0) || !(vNew > growth*vOld))
    {
        return false;
    }
    // the fastest node sped up by more than 'growth' in one step: a fresh
    // estimate at the step's start (the solid has not moved yet)
    Info<< type() << ' ' << name_ << ": the fastest node " << vNew
        << " m/s after " << vOld << " m/s; the stable step estimated again"
        << endl;
    estimateStableStep(true);
    const scalar dt = runTime.deltaTValue();
    const scalar beta = solid_->stiffnessDamping();
    if (dt <= stableStep_.stableDeltaT(beta))
    {
        // within the bound: the flow's own acceleration (the next step
        // takes the fraction of the new estimate)
        return false;
    }
    const scalar dtMax = stableStep_.maxDeltaT(beta);
    ++refusals_;
    const scalar t0 = runTime.value() - dt;
    repeatStep(runTime, t0, dtMax);
    Info<< type() << ' ' << name_ << ": step refused (deltaT " << dt
        << " s above the stable step " << stableStep_.stableDeltaT(beta)
        << " s): repeated from " << t0 << " s with deltaT " << dtMax
        << " s (" << stableStep_.fraction() << " of it)" << endl;
    return true;
}


void Foam::fv::immersedElasticForce::repeatShorter
(
    const vectorField& vLast,
    const string& why
)
{
    Time& runTime = const_cast<Time&>(mesh_.time());
    const scalar dt = runTime.deltaTValue();
    const scalar t0 = runTime.value() - dt;
    solid_->restoreState();
    lastVelocity_ = vLast;
    ++retries_;
    repeatStep(runTime, t0, 0.5*dt);
    updateStencils();
    // the look-ahead force of the step's start at the shorter step
    string whyStart;
    if (!spreadForce(lastVelocity_, false, whyStart))
    {
        failed(whyStart);
    }
    Info<< type() << ' ' << name_ << ": step refused (" << why.c_str()
        << "): repeated from " << t0 << " s with deltaT " << 0.5*dt
        << " s (" << retries_ << " of at most " << stepRetries_
        << " halvings)" << endl;
}


Foam::scalar Foam::fv::immersedElasticForce::maxDeltaT(const scalar) const
{
    return
        estimateStep_
      ? stableStep_.maxDeltaT(solid_->stiffnessDamping())
      : GREAT;
}


Foam::string Foam::fv::immersedElasticForce::maxDeltaTLimit
(
    const scalar
) const
{
    return
        Foam::name(stableStep_.fraction())
      + " of the carried solid's stable step (omega "
      + Foam::name(stableStep_.omega()) + " 1/s)";
}


bool Foam::fv::immersedElasticForce::updateForce()
{
    const Time& runTime = mesh_.time();
    if (updateIndex_ == runTime.timeIndex())
    {
        return true;
    }
    const scalar dt = runTime.deltaTValue();

    // x^{n+1} = x^n + dt v(u^{n+1}) (Zhang et al. 2004, Eq. 12)
    clockTime clock;
    const volVectorField& U =
        mesh_.lookupObject<volVectorField>(fieldNames_[0]);
    vectorField v(nodeVelocity(U));
    forceTime_ += clock.timeIncrement();
    if (refuseStep(v))
    {
        // the fluid's step again, shorter (the solid has not moved)
        return false;
    }
    refusals_ = 0;
    if (implicitForce_.valid())
    {
        correctImplicit(v);
        clock.timeIncrement();  // counted in implicitTime_, not the solid's
    }
    // a step whose end inverts an element is repeated, shorter, from its
    // start (the solid's state kept for it)
    const bool retry =
        retries_ < stepRetries_
     && runTime.controlDict().getOrDefault("adjustTimeStep", false);
    if (retry)
    {
        solid_->storeState();
    }
    string why;
    if (!solid_->tryMoveWith(v, dt, why))
    {
        failed(why);
    }
    solidTime_ += clock.timeIncrement();

    updateStencils();
    searchTime_ += clock.timeIncrement();

    const vectorField vLast(retry ? lastVelocity_ : vectorField());
    lastVelocity_ = v;
    if (!spreadForce(v, true, why))   // adds to solidTime_ and forceTime_
    {
        if (!retry)
        {
            failed
            (
                retries_
              ? why + " (the step repeated " + Foam::name(retries_)
              + " times at half its length)"
              : why
            );
        }
        repeatShorter(vLast, why);
        return false;
    }
    retries_ = 0;
    updateIndex_ = runTime.timeIndex();

    if (estimateStep_ && stableStep_.due())
    {
        estimateStableStep();
    }

    scalar vMax = 0;
    label iMax = -1;
    forAll(v, i)
    {
        if (mag(v[i]) > vMax)
        {
            vMax = mag(v[i]);
            iMax = i;
        }
    }
    Info<< type() << ' ' << name_ << ": force on the fluid " << fluidForce_
        << " N (tethers " << tetherForce_ << " N), on the walls "
        << wallForce_ << " N; fastest node "
        << vMax << " m/s";
    if (iMax >= 0)
    {
        Info<< " (node " << iMax << " at " << solidPtr_->points()[iMax]
            << ")";
    }
    if (outside_)
    {
        Info<< "; " << outside_ << " free nodes outside the fluid mesh";
    }
    Info<< nl << "    time: solid " << solidTime_ << " s, search "
        << searchTime_ << " s, force " << forceTime_ << " s" << endl;

    return true;
}


void Foam::fv::immersedElasticForce::write()
{
    const Time& runTime = mesh_.time();
    probes_.write(solidPtr_(), runTime);
    if (!runTime.writeTime())
    {
        return;
    }
    const fileName dir(solidPtr_->stateDir());
    solidPtr_->writeState(dir);
    // the tethers' state (drift and the last update's velocity) goes with
    // the solid's
    for (const word file : {"tetherDrift", "tetherVelocity"})
    {
        OFstream os(dir/file);
        os.precision(17);
        os << (file == "tetherDrift" ? tetherDrift_ : lastVelocity_);
        if (!os.good())
        {
            FatalErrorInFunction
                << "Cannot write " << os.name() << exit(FatalError);
        }
    }
    if (estimateStep_)
    {
        stableStep_.writeState(dir);
    }
    solidPtr_->write();
}


void Foam::fv::immersedElasticForce::addSup
(
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    eqn += force_;
}


bool Foam::fv::immersedElasticForce::read(const dictionary& dict)
{
    if (!option::read(dict))
    {
        return false;
    }
    if (!coeffs_.readIfPresent("fields", fieldNames_))
    {
        fieldNames_ = wordList(1, word("U"));
    }
    applied_.setSize(fieldNames_.size(), false);
    checkRemovedEntries
    (
        coeffs_,
        {
            {"balancedForce", "the force is always balanced by the face"
                " pressure (remove the entry)"},
            {"nodeVelocity", "the nodes always move with the face flux's"
                " reconstruction (remove the entry)"},
            {"deviatoricOnly", "the whole stress of the leaflets enters"
                " (remove the entry)"},
            {"noSlipPoints", "the held nodes hold the fluid through"
                " tetherRelaxation and tetherStiffness (remove the entry)"},
            {"wallSlip", "replaced by wallPoints free, slip or noSlip"
                " (wallSlip yes is wallPoints slip)"}
        },
        "fvOption " + name_
    );
    rhoFluid_ = coeffs_.get<scalar>("rhoFluid");
    if (!(rhoFluid_ > 0))
    {
        FatalIOErrorInFunction(coeffs_)
            << "fvOption " << name_ << ": rhoFluid " << rhoFluid_
            << " must be positive (the fluid's density in kg/m^3)"
            << exit(FatalIOError);
    }
    const bool elements =
        readEnumEntry
        (
            pointSetNames,
            "transferPoints",
            coeffs_,
            pointSet::nodes,
            "fvOption " + name_
        ) == pointSet::elements;
    if (transfer_.size() && elements != elementPoints_)
    {
        FatalIOErrorInFunction(coeffs_)
            << "fvOption " << name_ << ": transferPoints cannot change"
            << " during a run (restart the solver)" << exit(FatalIOError);
    }
    elementPoints_ = elements;
    const cellTetTransfer::wallCondition wall =
        readEnumEntry
        (
            cellTetTransfer::wallConditionNames,
            "wallPoints",
            coeffs_,
            cellTetTransfer::wallCondition::free,
            "fvOption " + name_
        );
    if (transfer_.size() && wall != wallCondition_)
    {
        FatalIOErrorInFunction(coeffs_)
            << "fvOption " << name_ << ": wallPoints cannot change during a"
            << " run (restart the solver)" << exit(FatalIOError);
    }
    wallCondition_ = wall;
    smallCell_ = coeffs_.getOrDefault<scalar>("smallCell", 0.2);
    tetherRelaxation_ = coeffs_.getOrDefault<scalar>("tetherRelaxation", 0.5);
    tetherStiffness_ = coeffs_.getOrDefault<scalar>("tetherStiffness", 0.1);
    estimateStep_ = coeffs_.found("stableStep");
    stableStep_.read(coeffs_);
    if (!coeffs_.found("implicitForce"))
    {
        implicitForce_.clear();
    }
    else
    {
        if (implicitForce_.valid())
        {
            implicitForce_->read(coeffs_);
        }
        else
        {
            implicitForce_.reset
            (
                new carriedImplicitForce(couplingMap_, name_, coeffs_)
            );
        }
        if (estimateStep_)
        {
            FatalIOErrorInFunction(coeffs_)
                << "fvOption " << name_ << ": stableStep estimates the"
                << " explicit force's stable step, which implicitForce does"
                << " not have: remove one of them (with implicitForce the"
                << " step is the flow's: adjustTimeStep and maxCo in"
                << " system/controlDict)" << exit(FatalIOError);
        }
    }
    stepRetries_ = coeffs_.getOrDefault<label>("stepRetries", 0);
    if (stepRetries_ < 0 || stepRetries_ > 20)
    {
        FatalIOErrorInFunction(coeffs_)
            << "fvOption " << name_ << ": stepRetries " << stepRetries_
            << " must be in [0, 20] (the halvings of a step whose end"
            << " inverts an element; 0: stop at once)" << exit(FatalIOError);
    }
    stepDamping_ = coeffs_.getOrDefault<scalar>("stepDamping", 0);
    if (stepDamping_ < 0 || stepDamping_ > 1)
    {
        FatalIOErrorInFunction(coeffs_)
            << "fvOption " << name_ << ": stepDamping " << stepDamping_
            << " must be in [0, 1] (the leaflets' stiffness damping as a"
            << " fraction of the step; 0.75 under the backward scheme, 0:"
            << " the solid's stiffnessDamping)" << exit(FatalIOError);
    }
    if
    (
        tetherRelaxation_ < 0 || tetherRelaxation_ > 1
     || tetherStiffness_ < 0 || tetherStiffness_ > 0.25
    )
    {
        FatalIOErrorInFunction(coeffs_)
            << "fvOption " << name_ << ": tetherRelaxation "
            << tetherRelaxation_ << " must be in [0, 1] and tetherStiffness "
            << tetherStiffness_ << " in [0, 0.25] (0 and 0: no tethers)"
            << exit(FatalIOError);
    }
    return true;
}


// ************************************************************************* //
