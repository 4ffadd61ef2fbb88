/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedForcing.H"
#include "readEnumEntry.H"
#include "checkRemovedEntries.H"
#include "scalarMatrices.H"
#include "fvMatrices.H"
#include "singlePhaseTransportModel.H"
#include "clockValue.H"
#include "syncTools.H"
#include "OSspecific.H"
#include "IFstream.H"
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

const Foam::Enum<Foam::fv::immersedForcing::wallType>
Foam::fv::immersedForcing::wallTypeNames
({
    { wallType::ghost, "ghost" },
    { wallType::staircase, "staircase" },
    { wallType::interpolation, "interpolation" },
});


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::fv::immersedForcing::update()
{
    advanceSolid();
    searchPairs();
}


void Foam::fv::immersedForcing::retryHalved
(
    const scalar dt,
    string& why
)
{
    const Time& runTime = mesh_.time();
    immersedSolid& solid = coupling_.solid();
    // A coupling iteration's update broke the solid (an inverted
    // element: Turek-Hron FSI2 at 1.47 s, residual 0.09 updated from
    // the columns of the last steps, before the remainder's
    // relaxation in updateForce()): back along the update from the
    // last iterate x_k, halving it until the solid advances, the
    // columns dropped. Still failing at 1/1024 of it, the solid has
    // blown up: stop (the last written time is kept).
    WarningInFunction
        << "Coupling iteration " << scheme_->iteration() + 1 << " at t = "
        << runTime.value() << ": the solid failed under the updated"
        << " force (" << why.c_str() << "); the update is halved"
        << " until it advances and the quasi-Newton columns are"
        << " dropped" << endl;
    scheme_->dropHistory();
    const vectorField x(scheme_->lastIterate());
    const vectorField update(guess_ - x);
    scalar factor = 1;
    bool advanced = false;
    for (label j = 0; j < 10 && !advanced; ++j)
    {
        factor /= 2;
        solid.restoreState();
        guess_ = x + factor*update;
        solid.externalForce() = guess_;
        advanced = solid.tryAdvance(dt, why);
        Info<< type() << ' ' << name_ << ": update times " << factor
            << (advanced ? ": the solid advanced" : ": failed") << endl;
    }
    if (!advanced)
    {
        FatalErrorInFunction
            << "The immersed solid failed at time " << solid.time()
            << " in coupling iteration " << scheme_->iteration() + 1
            << ", also with the update cut to " << factor << ": "
            << why.c_str() << exit(FatalError);
    }
}


void Foam::fv::immersedForcing::reportFastestNode() const
{
    const immersedSolid& solid = coupling_.solid();
    const vectorField& v = solid.velocities();
    label imax = 0;
    forAll(v, i)
    {
        if (magSqr(v[i]) > magSqr(v[imax]))
        {
            imax = i;
        }
    }
    Info<< "immersedForcing: solid max |v| " << (v.size() ? mag(v[imax]) : 0)
        << " at node " << imax << " X "
        << (v.size() ? solid.points0()[imax] : Zero)
        << ", |F| there " << mag(solid.externalForce()[imax])
        << ", max |F| " << max(mag(solid.externalForce()))
        << endl;
}


void Foam::fv::immersedForcing::advanceSolid()
{
    const Time& runTime = mesh_.time();
    immersedSolid& solid = coupling_.solid();
    if (advanceIndex_ == runTime.timeIndex() && !redo_)
    {
        return;
    }
    if (redo_)
    {
        // the next coupling iteration of this step: from the step's start
        // with the relaxed force
        redo_ = false;
        scheme_->nextIteration();
        solid.restoreState();
        solid.externalForce() = guess_;
    }
    else
    {
        endOfStep();
        writeDiagnostics();
        advanceIndex_ = runTime.timeIndex();
        stepIndex_ = runTime.timeIndex();
        searchTime0_ = coupling_.searchTime();
        transferTime0_ = coupling_.transferTime();
        forceTime_ = 0;
        wallTime_ = 0;
        advanceTime_ = 0;
        scheme_->startStep();
        velocities0_ = solid.velocities();
        if (scheme_->iterates())
        {
            solid.storeState();
            guess_ = solid.externalForce();
            storeFluid();
        }
    }
    searchIndex_ = -1;

    const scalar dt = runTime.value() - solid.time();
    stepDeltaT_ = dt;
    const clockValue start(true);
    string why;
    if (dt > 0 && !solid.tryAdvance(dt, why))
    {
        if (scheme_->iteration() == 0)
        {
            FatalErrorInFunction
                << "The immersed solid failed at time " << solid.time()
                << ": " << why.c_str() << exit(FatalError);
        }
        retryHalved(dt, why);
    }
    advanceTime_ += double(start.elapsed());
    if (debug)
    {
        reportFastestNode();
    }
}


void Foam::fv::immersedForcing::searchPairs()
{
    const Time& runTime = mesh_.time();
    if (searchIndex_ == runTime.timeIndex())
    {
        return;
    }
    advanceSolid();
    searchIndex_ = runTime.timeIndex();

    const immersedSolid& solid = coupling_.solid();
    // The pairs and covered cells of the step's first coupling iteration
    // hold for its later ones (the solid's velocities are interpolated
    // again, by the same weights): re-searched, a cell covered in one
    // iteration and not in the next changes the fluid's equations, and
    // the fixed point the iterations look for stops being smooth (the
    // IQN-ILS residual stalled at 0.4-0.9 on the soft flap; with the
    // pairs held it falls below 1e-3 in 5 to 11 iterations on the
    // Turek-Hron flag).
    if (scheme_->iteration() == 0)
    {
        coupling_.updatePairs();
    }

    const immersedPairs& pairs = coupling_.pairs();
    coveredVelocity_ = coupling_.solidToFluid(solid.velocities());

    // the immersed faces and the wall location count as search time
    const clockValue wallStart(true);
    const bool writeFraction = mesh_.time().writeTime();
    const surfaceSearch search(*this, writeFraction);
    updateBoundary(search);
    if (debug)
    {
        Info<< "immersedForcing: immersed faces " << wallStart.elapsed()
            << " s, pairs " << coupling_.searchTime() - searchTime0_ << " s"
            << endl;
    }
    const clockValue locateStart(true);
    locateWall(search);
    if (debug)
    {
        Info<< "immersedForcing: wall location " << locateStart.elapsed()
            << " s" << endl;
    }
    // (summed over the step's coupling iterations, as the solid's advances
    // and the force: the cut cells are found in the first)
    wallTime_ += double(wallStart.elapsed());

    scalarField& chi = coverage_.primitiveFieldRef();
    chi = 0;
    UIndirectList<scalar>(chi, boundary_.coveredCells()) = 1.0;
    coverage_.correctBoundaryConditions();

    if (writeFraction)
    {
        updateSolidFraction(search());
    }

    Info<< type() << ' ' << name_ << ": solid at t = " << solid.time()
        << ", covered cells " << returnReduce(pairs.coveredCells().size(),
               sumOp<label>())
        << (interpolatedWall() ? ", of them cut cells " : "")
        << (
               interpolatedWall()
             ? Foam::name(returnReduce(cutCellList_.size(), sumOp<label>()))
             : word::null
           )
        << ", fluid cells enclosed by the solid " << returnReduce
           (boundary_.nEnclosed(), sumOp<label>())
        << " in " << returnReduce(boundary_.nEnclosedRegions(), sumOp<label>())
        << " regions (pressure level fixed there)"
        << endl;
}


Foam::scalar Foam::fv::immersedForcing::maxDeltaT(const scalar maxCo) const
{
    const immersedSolid& solid = coupling_.solid();
    const labelList& cells = coupling_.pairs().nodeCells();
    const vectorField& v = solid.velocities();
    const scalarField& V = mesh_.V();

    // cell size: the cube root of the volume, or in a 2D case the root of
    // the area (volume over the depth of the empty direction)
    const Vector<label>& solD = mesh_.solutionD();
    const vector span(mesh_.bounds().span());
    scalar depth = 1;
    label nD = 0;
    for (direction d = 0; d < vector::nComponents; ++d)
    {
        if (solD[d] == -1)
        {
            depth *= span[d];
        }
        else
        {
            ++nD;
        }
    }
    scalar dt = GREAT;
    forAll(cells, i)
    {
        const label celli = cells[i];
        const scalar u = mag(v[i]);
        if (celli >= 0 && u > VSMALL)
        {
            const scalar h = Foam::pow(V[celli]/depth, 1.0/max(nD, 1));
            dt = min(dt, maxCo*h/u);
        }
    }
    return returnReduce(dt, minOp<scalar>());
}


void Foam::fv::immersedForcing::write()
{
    const Time& runTime = mesh_.time();
    // once per step, after its last coupling iteration
    probes_.write(coupling_.solid(), runTime);
    if (!runTime.writeTime())
    {
        return;
    }
    const fileName dir(coupling_.solid().stateDir());
    coupling_.solid().writeState(dir);
    boundary_.writeRamps(dir/"coverRamps");
    scheme_->writeState(dir);
    coupling_.solid().write();
}


void Foam::fv::immersedForcing::splitCutCells
(
    const labelList& covered,
    const scalarField& fraction
)
{
    // A covered cell with some fluid in it (more than kappaMin of its
    // volume) beside a covered cell with at most kappaMin fluid is a cut
    // cell: the solid is thick there (a thin solid, with no cell it
    // fills, keeps its staircase and stays tight). Whether its centre is
    // inside or outside does not decide: the blockage of a cut cell
    // follows the surface from a fluid fraction of kappaMin to 1, and a
    // cell changes status only at the ends of that range or where its
    // last full neighbour stops being full. (The first cut
    // cells, centre outside only, changed status where the surface
    // crossed a centre, half full: on the Turek-Hron flag the round-off
    // of a centre on the surface made one corner of its tail cut and the
    // other covered, lift +54 %, and the deformable flag's tail drifted.)
    // The split is made in a step's first coupling iteration and held in
    // its later ones, as the pairs are (searchPairs), with the fractions
    // (above).
    const scalar kappaMin = 0.02;
    // per cell: 0 not covered, 1 covered and full (fluid fraction at
    // most kappaMin), 2 covered with some fluid; the neighbours'
    // across processor faces too (swapBoundaryCellList), so that the
    // split of a decomposed run is the serial one
    labelList state(mesh_.nCells(), 0);
    forAll(covered, i)
    {
        state[covered[i]] = fraction[i] <= kappaMin ? 1 : 2;
    }
    isCut_.setSize(covered.size());
    isCut_ = false;
    {
        labelList nbrState;
        syncTools::swapBoundaryCellList(mesh_, state, nbrState);
        forAll(covered, i)
        {
            isCut_[i] =
                state[covered[i]] == 2
             && neighbourHas(covered[i], state, nbrState, 1);
        }
    }
    // and layer after layer: a covered cell with some fluid beside a
    // cut cell, until none is left. Where a sloped surface enters a
    // new row of cells, the cell it first touches (nearly all fluid)
    // lies beside a cell the surface has not yet filled, and covered
    // whole it puts the wall
    // on its faces: on the deformable Turek-Hron flag (N = 44) one
    // cell at the tail's upper edge was covered and uncovered every
    // other step once u_y(A) reached 0.2 h, and the lift on the flag
    // alternated by +-0.5 N/m (with a second layer only, 25 Nov 2026);
    // on the flapping FSI2 flag (N = 24, interpolated cut cells) such
    // cells beyond the second layer, 2 to 6 of them beside fluid cells
    // at a time, carried the drag's spikes (up to +150 N/m in a step,
    // as their faces' staircase pressure came and went). A thin solid
    // fills no cell, so it keeps its staircase.
    // (every rank makes the same passes: the loop ends only on the
    // reduced flag, after a pass that grew no rank's cells)
    labelList layer(mesh_.nCells(), 0);
    while (true)
    {
        forAll(covered, i)
        {
            layer[covered[i]] = isCut_[i] ? 1 : 0;
        }
        labelList nbrLayer;
        syncTools::swapBoundaryCellList(mesh_, layer, nbrLayer);
        bool grown = false;
        forAll(covered, i)
        {
            if
            (
                !isCut_[i] && state[covered[i]] == 2
             && neighbourHas(covered[i], layer, nbrLayer, 1)
            )
            {
                isCut_[i] = true;
                grown = true;
            }
        }
        if (!returnReduce(grown, orOp<bool>()))
        {
            break;
        }
    }
}


void Foam::fv::immersedForcing::updateBoundary(const surfaceSearch& search)
{
    const immersedPairs& pairs = coupling_.pairs();
    const labelList& covered = pairs.coveredCells();
    if (!interpolatedWall())
    {
        boundary_.update(covered, coveredVelocity_);
        coveredPairIndex_ = identity(covered.size());
        return;
    }

    // The cut-cell geometry of the covered cells, unless the last one
    // holds (cutCellsCurrent): the volume fractions of the cut cells are
    // those of the step's first coupling iteration, held in its later
    // ones with the split (a surface search per iteration was
    // most of the coupling's cost on refined meshes: 0.42 s per step at
    // Turek-Hron N = 36, -refine 2, 3,072 covered cells), and the
    // penalty's fixed point stays smooth in the force; a surface at rest
    // keeps its cut cells (the rigid CFD1 flag: 0.054 s per step)
    const bool newSplit =
        scheme_->iteration() == 0 || isCut_.size() != covered.size();
    const bool newGeometry = !cutCellsCurrent(search.points());
    if (newGeometry)
    {
        cutCells_.update(search(), covered);
        cutSurfacePoints_ = search.points();
        coveredFraction_ = cutCells_.fraction();
    }
    const scalarField& fraction = coveredFraction_;

    if (newSplit)
    {
        splitCutCells(covered, coveredFraction_);
    }
    const boolList& isCut = isCut_;

    DynamicList<label> sCells, sIndex, xCells, xIndex;
    DynamicList<vector> sVelocity;
    forAll(covered, i)
    {
        if (isCut[i])
        {
            xCells.append(covered[i]);
            xIndex.append(i);
        }
        else
        {
            sCells.append(covered[i]);
            sIndex.append(i);
            sVelocity.append(coveredVelocity_[i]);
        }
    }
    boundary_.update(sCells, vectorField(sVelocity));
    coveredPairIndex_.transfer(sIndex);
    cutCellList_.transfer(xCells);
    cutPairIndex_.transfer(xIndex);

    // the cut cells: whole fluid cells (no cut faces) whose centre, if
    // inside, is held by the penalty of constrain, and the forcing cells
    // of the interpolation
    cutVelocity_.setSize(cutCellList_.size());
    cutFraction_.setSize(cutCellList_.size());
    forAll(cutCellList_, j)
    {
        cutVelocity_[j] = coveredVelocity_[cutPairIndex_[j]];
        cutFraction_[j] = fraction[cutPairIndex_[j]];
    }
    updateWallInterpolation(newGeometry, search);
    if (debug)
    {
        Info<< "immersedForcing: " << cutCellList_.size()
            << " cut cells, solid volume "
            << sum((1 - cutFraction_)*scalarField(mesh_.V(), cutCellList_))
            << endl;
    }
}


void Foam::fv::immersedForcing::updateWallInterpolation
(
    const bool newGeometry,
    const surfaceSearch& search
)
{
    // Fadlun et al. (2000): the cells whose centre is inside hold u_s,
    // those outside within a cell's width of the surface are forced
    // toward the interpolation between the wall and their outer
    // neighbour (immersedWallInterpolation)
    cutInside_.setSize(cutCellList_.size());
    forAll(cutCellList_, j)
    {
        cutInside_[j] = cutCells_.centreDistance(cutCellList_[j]) <= 0;
    }
    if (newGeometry || !wallInterpolationCurrent_)
    {
        wallInterpolationCurrent_ = true;
        DynamicList<label> candidates(2*cutCellList_.size());
        forAll(cutCellList_, j)
        {
            if (!cutInside_[j])
            {
                candidates.append(cutCellList_[j]);
            }
        }
        const labelList& covered = coupling_.pairs().coveredCells();
        labelList isCovered(mesh_.nCells(), 0);
        UIndirectList<label>(isCovered, covered) = 1;
        boolList added(mesh_.nCells(), false);
        const labelUList& own = mesh_.faceOwner();
        const labelUList& nei = mesh_.faceNeighbour();
        // a cell beside a covered cell on another rank (processor faces)
        {
            labelList nbrCovered;
            syncTools::swapBoundaryCellList(mesh_, isCovered, nbrCovered);
            forAll(nbrCovered, bFacei)
            {
                const label celli = own[mesh_.nInternalFaces() + bFacei];
                if (nbrCovered[bFacei] && !isCovered[celli] && !added[celli])
                {
                    added[celli] = true;
                    candidates.append(celli);
                }
            }
        }
        for (const label celli : covered)
        {
            for (const label facei : mesh_.cells()[celli])
            {
                if (!mesh_.isInternalFace(facei))
                {
                    continue;
                }
                const label other =
                    own[facei] == celli ? nei[facei] : own[facei];
                if (!isCovered[other] && !added[other])
                {
                    added[other] = true;
                    candidates.append(other);
                }
            }
        }
        wallInterpolation_.update(search(), surfacePoints_, candidates);
        if (debug)
        {
            Info<< "immersedForcing: " << wallInterpolation_.cells().size()
                << " forcing cells of " << candidates.size()
                << " candidates, "
                << std::count(cutInside_.begin(), cutInside_.end(), true)
                << " cut cells held" << endl;
        }
    }
    wallInterpolation_.setVelocity(coupling_.solid().velocities());
}


bool Foam::fv::immersedForcing::neighbourHas
(
    const label celli,
    const labelUList& cellValue,
    const labelUList& boundaryValue,
    const label value
) const
{
    const labelUList& own = mesh_.faceOwner();
    const labelUList& nei = mesh_.faceNeighbour();
    const polyBoundaryMesh& patches = mesh_.boundaryMesh();
    for (const label facei : mesh_.cells()[celli])
    {
        if (mesh_.isInternalFace(facei))
        {
            const label other = own[facei] == celli ? nei[facei] : own[facei];
            if (cellValue[other] == value)
            {
                return true;
            }
        }
        else if
        (
            patches[patches.whichPatch(facei)].coupled()
         && boundaryValue[facei - mesh_.nInternalFaces()] == value
        )
        {
            return true;
        }
    }
    return false;
}


void Foam::fv::immersedForcing::updateSolidFraction
(
    const triSurfaceSearch& search
)
{
    // the covered cells and their face neighbours (a cell the solid
    // touches is one of them with either coverage)
    labelHashSet cells(boundary_.coveredCells());
    const labelListList& cellCells = mesh_.cellCells();
    for (const label celli : boundary_.coveredCells())
    {
        cells.insert(cellCells[celli]);
    }
    const labelList cellList(cells.sortedToc());
    fractionCells_.update(search, cellList);

    scalarField& f = solidFraction_.primitiveFieldRef();
    f = 0;
    forAll(cellList, i)
    {
        f[cellList[i]] = 1 - fractionCells_.fraction()[i];
    }
    solidFraction_.correctBoundaryConditions();
}


void Foam::fv::immersedForcing::locateWall(const surfaceSearch& search)
{
    if (!ghostWall())
    {
        return;
    }
    if (search.valid())
    {
        boundary_.locateWall(search());
        return;
    }
    const immersedPairs& pairs = coupling_.pairs();
    boundary_.locateWall
    (
        search.points(),
        surfaceTriangles_,
        pairs.nearElements(),
        elementTriangles_
    );
}


bool Foam::fv::immersedForcing::cutCellsCurrent
(
    const pointField& points
) const
{
    const labelList& covered = coupling_.pairs().coveredCells();
    if (scheme_->iteration() > 0 && isCut_.size() == covered.size())
    {
        return true;    // coveredFraction_ of the step's first iteration
    }
    // (the solid fraction of a write time updates cutCells_ over more
    // cells: then they are not the covered cells)
    return cutCells_.cells() == covered && points == cutSurfacePoints_;
}


bool Foam::fv::immersedForcing::needsOctree
(
    const bool solidFraction,
    const pointField& points
) const
{
    // cut cells (unless current) with their forcing cells, the solid
    // fraction, and the wall location of centre coverage search the whole
    // surface; the wall location of touching coverage tests each covered
    // cell's own elements (no octree: the covered cells of the projection
    // must be the pairs')
    return
        (interpolatedWall() && (!cutCellsCurrent(points) || !wallInterpolationCurrent_))
     || solidFraction
     || (
            ghostWall()
         && coupling_.pairs().coverage()
         != immersedPairs::coverageType::touching
        );
}


Foam::fv::immersedForcing::surfaceSearch::surfaceSearch
(
    const immersedForcing& forcing,
    const bool solidFraction
)
:
    points_
    (
        UIndirectList<point>
        (
            forcing.coupling_.solid().points(),
            forcing.surfacePoints_
        )
    )
{
    if (forcing.needsOctree(solidFraction, points_))
    {
        surface_.reset(new triSurface(forcing.surfaceTriangles_, points_));
        search_.reset(new triSurfaceSearch(*surface_));
    }
}


const Foam::triSurfaceSearch&
Foam::fv::immersedForcing::surfaceSearch::operator()() const
{
    if (!search_.valid())
    {
        FatalErrorInFunction
            << "the solid's surface octree was not built for this update"
            << abort(FatalError);
    }
    return *search_;
}


void Foam::fv::immersedForcing::fluidForce
(
    const volScalarField& p,
    const volVectorField& U
)
{
    immersedSolid& solid = coupling_.solid();

    const singlePhaseTransportModel& transport =
        mesh_.lookupObject<singlePhaseTransportModel>("transportProperties");
    const tmp<volScalarField> tnu(transport.nu());

    // Traction on the staircase surface of the covered cells (pressure
    // and viscous, Eqs. 44/48 boundary terms), per covered cell
    vectorField t
    (
        boundary_.traction(p, U, tnu(), rhoFluid_, coveredGradP_)
    );
    // To the solid nodes (held for the solid's next step)
    if (interpolatedWall())
    {
        // to the pairs' covered cells, with the cut cells' force: the
        // reaction of the penalty (constrain) that holds a cut cell whose
        // centre is inside to u_s against the fluid (pressure and shear on
        // the solid inside the cell; Brinkman penalty force, Angot,
        // Bruneau & Fabrie 1999), less the inertia of the fictitious
        // fluid in the cell's solid part: the cell's momentum row holds
        // its whole volume, and the penalty also accelerates the fluid
        // standing in for the solid part, rho (1 - kappa) V du_s/dt,
        // which the solid, with its own mass, must not feel again (the
        // internal-fluid term of the hydrodynamic force on a particle,
        // Uhlmann 2005, J Comput Phys 209: F = -rho int f dV + rho d/dt
        // int_solid u dV)
        vectorField tp(coupling_.pairs().coveredCells().size(), Zero);
        UIndirectList<vector>(tp, coveredPairIndex_) = t;
        const vectorField us0
        (
            stepDeltaT_ > 0 && velocities0_.size() == solid.nPoints()
          ? coupling_.solidToFluid(velocities0_)
          : tmp<vectorField>(coveredVelocity_)
        );
        const scalar rDt = stepDeltaT_ > 0 ? 1/stepDeltaT_ : 0;
        vectorField fictitiousInertia(cutCellList_.size());
        forAll(cutCellList_, j)
        {
            const label celli = cutCellList_[j];
            const label i = cutPairIndex_[j];
            const scalar K = j < cutPenalty_.size() ? cutPenalty_[j] : 0;
            tp[i] = rhoFluid_*K*(U[celli] - cutVelocity_[j]);
            // (a cell whose centre is outside is a fluid cell, with no
            // fictitious fluid)
            fictitiousInertia[j] =
                !cutInside_[j]
              ? Zero
              : rhoFluid_*(1 - cutFraction_[j])*mesh_.V()[celli]
               *(cutVelocity_[j] - us0[i])*rDt;
        }
        // the wall force the fluid feels back (fluidSource), then the
        // solid's correction by the fictitious fluid's inertia (not a
        // force on the fluid: |force + source| in the diagnostics shows
        // it)
        cutForce_ = Zero;
        for (const label i : cutPairIndex_)
        {
            cutForce_ += tp[i];
        }
        forAll(fictitiousInertia, j)
        {
            tp[cutPairIndex_[j]] += fictitiousInertia[j];
        }
        t.transfer(tp);
    }
    vectorField& f = solid.externalForce();
    f = coupling_.spreadToSolid(t);
    if (interpolatedWall())
    {
        // the forcing cells' penalty reaction, to the nodes of their
        // nearest surface points (the fluid feels it back: cutForce_)
        vectorField fw(f.size(), Zero);
        cutForce_ += wallInterpolation_.addForce(U, rhoFluid_, fw);
        reduce(fw, sumOp<vectorField>());
        f += fw;
    }
    force_ = sum(f);
}



void Foam::fv::immersedForcing::writeDiagnostics()
{
    if (stepIndex_ < 0)
    {
        return;
    }
    const Time& runTime = mesh_.time();
    const immersedPairs& pairs = coupling_.pairs();

    const label nCovered =
        returnReduce(boundary_.coveredCells().size(), sumOp<label>());
    const label nFaces = returnReduce(boundary_.nFaces(), sumOp<label>());
    const label nSteps = returnReduce(pairs.nSteps(), sumOp<label>());
    const label nWalks = returnReduce(pairs.nWalks(), sumOp<label>());
    const label nFallback =
        returnReduce(pairs.nFallback() + pairs.nLeft(), sumOp<label>());
    const scalar magF = mag(force_);
    const scalar magS = mag(source_);
    const scalar imbalance =
        mag(force_ + source_)/max(max(magF, magS), VSMALL);

    if (Pstream::master())
    {
        if (!diagnostics_.valid())
        {
            const fileName dir
            (
                (Pstream::parRun() ? runTime.path()/".." : runTime.path())
               /"postProcessing"/name_/runTime.timeName(runTime.startTime().value())
            );
            mkDir(dir);
            diagnostics_.reset(new OFstream(dir/"immersedForcing.dat"));
            diagnostics_()
                << "# immersedForcing " << name_ << " (fsiCoupling): per time"
                << " step" << nl
                << "# force: of the fluid on the solid [N]; source: momentum"
                << " source the fluid received in the covered cells [N]"
                << nl
                << "# imbalance = |force + source|/max(|force|, |source|)"
                << nl
                << "# slip = RMS |u - u_s| over covered cells / max |u_s|"
                << " (RMS |u - u_s| [m/s] when the solid is at rest)" << nl
                << "# walk = mean neighbour steps per solid node;"
                << " fallback = octree searches" << nl
                << "# times [s]: solid advance, pair search (F-S, S-F and"
                << " the wall location), transfers, force and source (all"
                << " coupling iterations)" << nl
                << "# iterations: coupling iterations of the step;"
                << " residual: the last one's force residual" << nl
                << "# time Fx Fy Fz Sx Sy Sz imbalance slip coveredCells"
                << " immersedFaces walk fallback tAdvance tSearch"
                << " tTransfer tForce iterations residual" << endl;
        }
        OFstream& os = diagnostics_();
        os.precision(8);
        os  << solidTime_ << ' '
            << force_.x() << ' ' << force_.y() << ' ' << force_.z() << ' '
            << source_.x() << ' ' << source_.y() << ' ' << source_.z() << ' '
            << imbalance << ' ' << slip_ << ' '
            << nCovered << ' ' << nFaces << ' '
            << scalar(nSteps)/max(nWalks, 1) << ' ' << nFallback << ' '
            << advanceTime_ << ' '
            << coupling_.searchTime() - searchTime0_ + wallTime_ << ' '
            << coupling_.transferTime() - transferTime0_ << ' '
            << forceTime_ << ' ' << scheme_->iteration() + 1 << ' '
            << scheme_->residual()
            << endl;
    }
    stepIndex_ = -1;
}


void Foam::fv::immersedForcing::readSolidState()
{
    coupling_.solid().restart(type() + ' ' + name_);
    velocities0_ = coupling_.solid().velocities();
}


void Foam::fv::immersedForcing::initialCoverage()
{
    coupling_.updatePairs();
    coveredVelocity_ = coupling_.solidToFluid(coupling_.solid().velocities());
    {
        const surfaceSearch search(*this, false);
        updateBoundary(search);
        locateWall(search);
    }
    UIndirectList<scalar>
    (
        coverage_.primitiveFieldRef(), boundary_.coveredCells()
    ) = 1.0;
    coverage_.correctBoundaryConditions();
    advanceIndex_ = mesh_.time().timeIndex();
    searchIndex_ = mesh_.time().timeIndex();
}


Foam::IOobject Foam::fv::immersedForcing::writtenField
(
    const word& name,
    const fvMesh& mesh
)
{
    return IOobject
    (
        name,
        mesh.time().timeName(),
        mesh,
        IOobject::NO_READ,
        IOobject::AUTO_WRITE
    );
}


void Foam::fv::immersedForcing::checkSingle(const dictionary& dict) const
{
    if
    (
        mesh_.findObject<immersedBoundary>(immersedBoundary::typeName)
     != &boundary_
    )
    {
        FatalIOErrorInFunction(dict)
            << "fvOption " << name_ << ": a second immersedForcing option on"
            << " mesh " << mesh_.name() << "; one immersed solid per mesh is"
            << " supported: put all solid parts in one constant/"
            << "solidProperties mesh" << exit(FatalIOError);
    }
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
    immersedMethod(name, modelType, dict, mesh),
    coupling_(mesh),
    coverage_
    (
        writtenField("immersedCoverage", mesh),
        mesh,
        dimensionedScalar(dimless, Zero),
        "zeroGradient"
    ),
    solidFraction_
    (
        writtenField("immersedSolidFraction", mesh),
        mesh,
        dimensionedScalar(dimless, Zero),
        "zeroGradient"
    ),
    advanceIndex_(-1),
    searchIndex_(-1),
    stepDeltaT_(0),
    redo_(false),
    probes_(coupling_.solid()),
    rhoFluid_(0),
    boundary_(mesh),
    force_(Zero),
    wall_(wallType::ghost),
    cutCells_(mesh),
    fractionCells_(mesh),
    wallInterpolation_(mesh),
    wallInterpolationCurrent_(false),
    cutForce_(Zero),
    source_(Zero),
    slip_(0),
    solidTime_(0),
    advanceTime_(0),
    forceTime_(0),
    wallTime_(0),
    searchTime0_(0),
    transferTime0_(0),
    stepIndex_(-1),
    stepSolved_(false),
    coveredGradP_(Zero),
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
    checkSingle(dict);

    // The solid's surface, element by element (the wall location)
    coupling_.solid().surface
    (
        surfaceTriangles_, surfacePoints_, elementTriangles_
    );

    // A restart: the solid's state of the start time, then the coverage
    // of its configuration, the running covering ramps and the coupling
    // scheme's state
    const fileName stateDir(coupling_.solid().stateDir());
    readSolidState();
    initialCoverage();
    boundary_.readRamps(stateDir/"coverRamps");
    scheme_->readState(stateDir, coupling_.solid().nPoints());

    Info<< type() << ' ' << name_ << ": coupling scheme " << scheme_->type()
        << endl;

    // the solid's output at the start time
    coupling_.solid().write(true);
}


// * * * * * * * * * * * * * * * * Destructor  * * * * * * * * * * * * * * //

Foam::fv::immersedForcing::~immersedForcing()
{
    // (the fields may be gone: fv::options are destroyed with the mesh)
    const word pName(coeffs_.getOrDefault<word>("p", "p"));
    if
    (
        mesh_.foundObject<volScalarField>(pName)
     && mesh_.foundObject<volVectorField>(fieldNames_.first())
    )
    {
        endOfStep();
    }
    writeDiagnostics();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::fv::immersedForcing::constrain
(
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    update();
    unconstrained_.keep(eqn, boundary_.coveredCells());

    // u_s in the covered cells, the ghost cells' value extrapolated through
    // the wall (immersedBoundary::ghostVelocity). (coveredVelocity_ is in
    // the pairs' order: with cut cells the covered cells of the projection
    // are a part of them.) Their processor faces first get what setValues
    // gives their internal faces, on both sides (constrainCoupled): else
    // the fluid cell across stays coupled to the covered cell's solution,
    // which the pressure gradient moves off the value
    const labelUList& cells = boundary_.coveredCells();
    const vectorField values
    (
        ghostWall()
      ? boundary_.ghostVelocity(eqn.psi())
      : tmp<vectorField>
        (
            new vectorField
            (
                UIndirectList<vector>(coveredVelocity_, coveredPairIndex_)
            )
        )
    );
    boundary_.constrainCoupled(eqn, values);
    eqn.setValues(cells, values);

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

    // Cut cells (Fadlun et al. 2000): a cut cell whose centre is inside
    // is held at u_s (the wall beyond its centre) by the penalty K (u_s -
    // u), K = (1 - kappaMin)/kappaMin A, implicit: the row (A u = H)
    // becomes (A + K) u = H + K u_s, u = H/(A + K) + K u_s/(A + K), and
    // the projection moves the cell by grad p/(A + K) (Steps II and III);
    // one whose centre is outside is a forcing cell of wallInterpolation_
    if (interpolatedWall())
    {
        // A: the row's whole diagonal, as the solver and A() see it, with
        // the boundary faces' internal coefficients (fvMatrix::D): on a
        // processor boundary the faces to the other rank's cells are
        // there, not in diag(), and without them the penalty of a cut
        // cell beside it differed from the serial run's (DFG cylinder, 10
        // cells across, processor boundary through it: F_x 5e-4 off)
        const scalarField A(eqn.D());
        const scalar kappaMin = 0.02;
        const scalar KmaxByA = (1 - kappaMin)/kappaMin;
        cutPenalty_.setSize(cutCellList_.size());
        forAll(cutCellList_, j)
        {
            const label celli = cutCellList_[j];
            const scalar K = cutInside_[j] ? KmaxByA*A[celli] : 0;
            cutPenalty_[j] = K;
            diag[celli] += K;
            source[celli] += K*cutVelocity_[j];
        }
        wallInterpolation_.constrain(eqn, A, KmaxByA);
    }
}


Foam::vector Foam::fv::immersedForcing::fluidSource
(
    const volVectorField& U
) const
{
    vector total(Zero);
    if (!unconstrained_.empty())
    {
        total = rhoFluid_*(unconstrained_.residualSum(U) + coveredGradP_);
    }
    if (interpolatedWall())
    {
        // the cut cells' wall force, whose reaction the fluid receives
        // through the closed part of their faces and the wall shear
        total -= cutForce_;
    }
    reduce(total, sumOp<vector>());
    return total;
}


void Foam::fv::immersedForcing::correct(volVectorField&)
{
    // A projection pass has run: the force, source and slip of the step
    // are evaluated once, from its final U and p, by the solver's explicit
    // end of the step (updateForce), else when the next step starts
    stepSolved_ = true;
    solidTime_ = mesh_.time().value();   // the step's time, for its line
}


void Foam::fv::immersedForcing::setPressureReference(const label celli)
{
    boundary_.setPressureReference(celli);
}


void Foam::fv::immersedForcing::constrainFlux
(
    surfaceScalarField& phiHbyA,
    surfaceScalarField& rAUf
) const
{
    boundary_.constrainFlux(phiHbyA);
    boundary_.constrainLaplacian(rAUf);
}


void Foam::fv::immersedForcing::constrainPressure
(
    fvScalarMatrix& pEqn,
    const volScalarField& p
) const
{
    boundary_.constrainPressure(pEqn, p);
}


Foam::tmp<Foam::volVectorField>
Foam::fv::immersedForcing::pressureGradient(const volScalarField& p) const
{
    return boundary_.grad(p);
}


Foam::tmp<Foam::volVectorField>
Foam::fv::immersedForcing::correctPressure(volScalarField& p) const
{
    return boundary_.correctPressure(p);
}


bool Foam::fv::immersedForcing::updateForce()
{
    endOfStep();
    if (!scheme_->iterates())
    {
        return true;
    }
    // the force the fluid gave back against the one handed to the solid
    // (couplingScheme): done, or the next iteration from the step's start
    immersedSolid& solid = coupling_.solid();
    if
    (
        scheme_->update
        (
            solid.externalForce(),
            solid.freeComponents(),
            guess_
        )
    )
    {
        // the scheme's first force for the next step, held by the solid
        // (and written with its state for a restart)
        solid.externalForce() = guess_;
        return true;
    }
    redo_ = true;
    restoreFluid();
    return false;
}


void Foam::fv::immersedForcing::storeFluid()
{
    // The fluid's iterates at the step's start: every coupling iteration
    // solves the step from them (restoreFluid), so that the force the
    // fluid gives back is a function of the force handed to the solid
    // alone. Carried over from the last iteration (the wall's ghost
    // velocities and the convecting flux are taken from the current
    // iterate), they made the fixed-point map one with memory: the same
    // force handed to the solid twice gave back forces 1.2 % apart on the
    // Turek-Hron flag, and IQN-ILS stalled at that level.
    const word UName(coeffs_.getOrDefault<word>("U", "U"));
    const word pName(coeffs_.getOrDefault<word>("p", "p"));
    const word phiName(coeffs_.getOrDefault<word>("phi", "phi"));
    U0_.reset
    (
        new volVectorField("U0", mesh_.lookupObject<volVectorField>(UName))
    );
    p0_.reset
    (
        new volScalarField("p0", mesh_.lookupObject<volScalarField>(pName))
    );
    phi0_.reset
    (
        new surfaceScalarField
        (
            "phi0",
            mesh_.lookupObject<surfaceScalarField>(phiName)
        )
    );
}


void Foam::fv::immersedForcing::restoreFluid()
{
    if (!U0_.valid())
    {
        return;
    }
    mesh_.lookupObjectRef<volVectorField>
    (
        coeffs_.getOrDefault<word>("U", "U")
    ) == U0_();
    mesh_.lookupObjectRef<volScalarField>
    (
        coeffs_.getOrDefault<word>("p", "p")
    ) == p0_();
    mesh_.lookupObjectRef<surfaceScalarField>
    (
        coeffs_.getOrDefault<word>("phi", "phi")
    ) == phi0_();
}


void Foam::fv::immersedForcing::endOfStep()
{
    if (!stepSolved_)
    {
        return;
    }
    stepSolved_ = false;
    const word pName(coeffs_.getOrDefault<word>("p", "p"));
    const volScalarField& p = mesh_.lookupObject<volScalarField>(pName);
    const volVectorField& U =
        mesh_.lookupObject<volVectorField>(fieldNames_.first());
    const clockValue start(true);
    fluidForce(p, U);
    source_ = fluidSource(U);
    forceTime_ += double(start.elapsed());

    // Slip: covered cells and wall points (immersedBoundary::slip)
    scalar sum2 = 0;
    label n = 0;
    boundary_.slip(U, sum2, n);
    scalar maxUs = 0;
    for (const vector& us : coveredVelocity_)
    {
        maxUs = max(maxUs, mag(us));
    }
    reduce(sum2, sumOp<scalar>());
    reduce(n, sumOp<label>());
    reduce(maxUs, maxOp<scalar>());
    slip_ = Foam::sqrt(sum2/max(n, 1))/(maxUs > SMALL ? maxUs : 1);

    Info<< type() << ' ' << name_ << ": force on the solid " << force_
        << ", momentum source on the fluid " << source_ << endl;
}


bool Foam::fv::immersedForcing::read(const dictionary& dict)
{
    if (option::read(dict))
    {
        fieldNames_.resize(1);
        fieldNames_.first() = coeffs_.getOrDefault<word>("U", "U");
        applied_.setSize(fieldNames_.size(), false);
        checkRemovedEntries
        (
            coeffs_,
            {
                {"addedMassLength", "a solid about as dense as the fluid"
                    " takes couplingIterations (remove the entry)"},
                {"coupling", "the coupling is chosen by couplingScheme"
                    " (explicit or IQNILS; remove the entry)"},
                {"cutCells", "the wall model is chosen by wall: cutCells"
                    " interpolation is wall interpolation, cutCells no the"
                    " default wall ghost"}
            },
            "fvOption " + name_
        );
        coeffs_.readEntry("rhoFluid", rhoFluid_);
        boundary_.setPressureName(coeffs_.getOrDefault<word>("p", "p"));
        wall_ =
            readEnumEntry
            (
                wallTypeNames,
                "wall",
                coeffs_,
                wallType::ghost,
                "fvOption " + name_
            );
        // the coupling scheme: made again when its type changes (a
        // run-time modified dictionary), else its entries read again
        if
        (
            !scheme_.valid()
         || scheme_->type() != couplingScheme::selectedType(coeffs_)
        )
        {
            scheme_ = couplingScheme::New
            (
                coeffs_,
                string(type() + ' ' + name_),
                mesh_.time()
            );
        }
        else
        {
            scheme_->read(coeffs_);
        }
        boundary_.setCoverRamp
        (
            !interpolatedWall() && coeffs_.getOrDefault<bool>("coverRamp", true)
        );
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
