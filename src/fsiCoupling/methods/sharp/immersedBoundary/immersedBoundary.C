/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedBoundary.H"
#include "emptyPolyPatch.H"
#include "fvMatrices.H"
#include "fvcSurfaceIntegrate.H"
#include "surfaceInterpolate.H"
#include "linear.H"
#include "syncTools.H"
#include "OFstream.H"
#include "IFstream.H"
#include "coupledFvPatch.H"
#include "processorPolyPatch.H"
#include "triSurfaceSearch.H"
#include "treeDataPrimitivePatch.H"
#include "registerSwitch.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(immersedBoundary, 0);
}

int Foam::immersedBoundary::processorExchange
(
    Foam::debug::optimisationSwitch("immersedProcessorExchange", 1)
);
registerOptSwitch
(
    "immersedProcessorExchange",
    int,
    Foam::immersedBoundary::processorExchange
);


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

//- Breadth-first fill over the fluid cells (a negative covered index)
//  through the cell-cell addressing of the internal faces
//  (primitiveMesh::cellCells): the cells reached, in queue order
class fluidFill
{
    const Foam::labelListList& cellCells_;
    const Foam::labelList& coveredIndex_;

public:

    //- Per cell: reached
    Foam::List<char> reached;

    //- The cells reached, in the order they were; head: the first whose
    //  neighbours are still to be visited; tail: the end
    Foam::labelList queue;
    Foam::label head;
    Foam::label tail;

    //- Construct for the cell-cell addressing and the covered index of
    //  nCells cells; nothing reached
    fluidFill
    (
        const Foam::labelListList& cellCells,
        const Foam::labelList& coveredIndex,
        const Foam::label nCells
    )
    :
        cellCells_(cellCells),
        coveredIndex_(coveredIndex),
        reached(nCells, char(0)),
        queue(nCells),
        head(0),
        tail(0)
    {}

    //- Reach celli when it is fluid and not reached yet
    void seed(const Foam::label celli)
    {
        if (!reached[celli] && coveredIndex_[celli] < 0)
        {
            reached[celli] = 1;
            queue[tail++] = celli;
        }
    }

    //- Reach the fluid cells connected to the queued ones
    void fill()
    {
        while (head < tail)
        {
            const Foam::label celli = queue[head++];
            for (const Foam::label nb : cellCells_[celli])
            {
                seed(nb);
            }
        }
    }
};


//- Fill, then seed the fluid cells across processor faces from the
//  reached cells of the other side and fill again, until no rank reaches
//  more. Collective (every rank, with or without processor faces)
void fillAcrossProcessors(const Foam::polyMesh& mesh, fluidFill& reach)
{
    using namespace Foam;

    const polyBoundaryMesh& pbm = mesh.boundaryMesh();
    const label nInternal = mesh.nInternalFaces();

    while (true)
    {
        reach.fill();
        if (!Pstream::parRun())
        {
            break;
        }
        // across processor faces (fluid on both sides)
        boolList nbrReached(mesh.nBoundaryFaces(), false);
        forAll(pbm, patchi)
        {
            if (pbm[patchi].coupled())
            {
                const labelUList& faceCells = pbm[patchi].faceCells();
                const label start = pbm[patchi].start() - nInternal;
                forAll(faceCells, i)
                {
                    nbrReached[start + i] = reach.reached[faceCells[i]];
                }
            }
        }
        syncTools::swapBoundaryFaceList(mesh, nbrReached);
        const label before = reach.tail;
        forAll(pbm, patchi)
        {
            if (!pbm[patchi].coupled())
            {
                continue;
            }
            const labelUList& faceCells = pbm[patchi].faceCells();
            forAll(faceCells, i)
            {
                if (nbrReached[pbm[patchi].start() + i - nInternal])
                {
                    reach.seed(faceCells[i]);
                }
            }
        }
        if (!returnReduce(reach.tail - before, sumOp<label>()))
        {
            break;
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedBoundary::immersedBoundary
(
    const fvMesh& mesh
)
:
    regIOobject
    (
        IOobject
        (
            typeName,
            mesh.time().constant(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            true
        )
    ),
    mesh_(mesh),
    coveredCells_(),
    coveredVelocity_(),
    coveredIndex_(mesh.nCells(), -1),
    nEnclosed_(0),
    refCells_(),
    enclosedFound_(false),
    region_(mesh.nCells(), -1),
    mark_(),
    owner_(),
    stamp_(0),
    nFills_(0),
    nLocalUpdates_(0),
    ramp_(false),
    ramps_(),
    updated_(false),
    pName_("p"),
    refCell_(Pstream::master() ? 0 : -1),
    nbrCovered_(mesh.nBoundaryFaces(), false),
    nbrVelocity_(mesh.nBoundaryFaces(), Zero),
    internalFaces_(),
    boundaryFaces_(),
    wallFraction_()
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedBoundary::setCoveredCells
(
    const labelUList& coveredCells,
    const vectorField& coveredVelocity,
    DynamicList<label>& newlyCovered,
    DynamicList<label>& newlyUncovered
)
{
    // The cells covered since the last update (the index is still the
    // last update's) and those uncovered since
    for (const label celli : coveredCells)
    {
        if (coveredIndex_[celli] < 0)
        {
            newlyCovered.append(celli);
        }
    }
    labelList oldCells;
    oldCells.transfer(coveredCells_);
    for (const label celli : oldCells)
    {
        coveredIndex_[celli] = -1;
    }
    coveredCells_ = coveredCells;
    coveredVelocity_ = coveredVelocity;
    forAll(coveredCells_, i)
    {
        coveredIndex_[coveredCells_[i]] = i;
    }
    for (const label celli : oldCells)
    {
        if (coveredIndex_[celli] < 0)
        {
            newlyUncovered.append(celli);
        }
    }
}


void Foam::immersedBoundary::exchangeNbrCovered()
{
    // Covered flag and solid velocity of the cells across coupled faces
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInternal = mesh_.nInternalFaces();
    nbrCovered_ = false;
    nbrVelocity_ = Zero;
    forAll(pbm, patchi)
    {
        if (!pbm[patchi].coupled())
        {
            continue;
        }
        const labelUList& faceCells = pbm[patchi].faceCells();
        const label start = pbm[patchi].start() - nInternal;
        forAll(faceCells, i)
        {
            const label ic = coveredIndex_[faceCells[i]];
            if (ic >= 0)
            {
                nbrCovered_[start + i] = true;
                nbrVelocity_[start + i] = coveredVelocity_[ic];
            }
        }
    }
    if (processorExchange)
    {
        syncTools::swapBoundaryFaceList(mesh_, nbrCovered_);
        syncTools::swapBoundaryFaceList(mesh_, nbrVelocity_);
    }
}


void Foam::immersedBoundary::findImmersedFaces()
{
    // Immersed faces: every face of a covered cell (internal, or coupled
    // boundary), and the coupled faces whose other side is covered
    const cellList& cells = mesh_.cells();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    DynamicList<label> internal(6*coveredCells_.size());
    DynamicList<label> boundary;

    for (const label celli : coveredCells_)
    {
        for (const label facei : cells[celli])
        {
            if (mesh_.isInternalFace(facei))
            {
                // once: from the owner, or the neighbour if the owner is
                // not covered
                const label o = mesh_.faceOwner()[facei];
                if (o == celli || !covered(o))
                {
                    internal.append(facei);
                }
            }
            else if (pbm[pbm.whichPatch(facei)].coupled())
            {
                boundary.append(facei);
            }
        }
    }
    forAll(pbm, patchi)
    {
        if (pbm[patchi].coupled())
        {
            const label start = pbm[patchi].start();
            const labelUList& faceCells = pbm[patchi].faceCells();
            forAll(faceCells, i)
            {
                if (!covered(faceCells[i]) && nbrCovered(start + i))
                {
                    boundary.append(start + i);
                }
            }
        }
    }

    internalFaces_.transfer(internal);
    boundaryFaces_.transfer(boundary);
    wallFraction_.setSize(nFaces());
    wallFraction_ = -1;
}


void Foam::immersedBoundary::update
(
    const labelUList& coveredCells,
    const vectorField& coveredVelocity
)
{
    // The cells covered since the last update and those uncovered since
    DynamicList<label> newlyCovered;
    DynamicList<label> newlyUncovered;
    setCoveredCells
    (
        coveredCells,
        coveredVelocity,
        newlyCovered,
        newlyUncovered
    );

    // The enclosed fluid regions: kept, updated where the covered cells
    // changed, or found afresh
    const bool sameCells = returnReduce
    (
        newlyCovered.empty() && newlyUncovered.empty(),
        andOp<bool>()
    );
    if
    (
        !enclosedFound_
     || (!sameCells && !updateEnclosedFluid(newlyCovered, newlyUncovered))
    )
    {
        findEnclosedFluid();
    }

    // Covered flag and solid velocity of the cells across coupled faces
    const boolList oldNbrCovered(ramp_ ? nbrCovered_ : boolList());
    exchangeNbrCovered();

    // Immersed faces
    findImmersedFaces();

    // (not at the first update: the initial covered cells were not
    // covered by a motion)
    if (ramp_ && updated_)
    {
        updateRamps(newlyCovered, oldNbrCovered);
    }
    updated_ = true;
}


void Foam::immersedBoundary::wallSegments
(
    DynamicList<label>& faces,
    DynamicList<label>& cells,
    DynamicList<point>& start,
    DynamicList<point>& end
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const volVectorField& C = mesh_.C();

    faces.clear();
    cells.clear();
    start.clear();
    end.clear();
    forAll(internalFaces_, i)
    {
        const label facei = internalFaces_[i];
        const bool oc = covered(own[facei]);
        if (oc != covered(nei[facei]))
        {
            const label c = oc ? own[facei] : nei[facei];
            faces.append(i);
            cells.append(coveredIndex_[c]);
            start.append(C[c]);
            end.append(C[oc ? nei[facei] : own[facei]]);
        }
    }

    // Cell centres across coupled faces
    pointField nbrC;
    syncTools::swapBoundaryCellList(mesh_, C.primitiveField(), nbrC);
    forAll(boundaryFaces_, j)
    {
        const label facei = boundaryFaces_[j];
        const label o = mesh_.faceOwner()[facei];
        if (covered(o) && !nbrCovered(facei))
        {
            faces.append(internalFaces_.size() + j);
            cells.append(coveredIndex_[o]);
            start.append(C[o]);
            end.append(nbrC[facei - mesh_.nInternalFaces()]);
        }
    }
}


void Foam::immersedBoundary::locateWall(const triSurface& surface)
{
    locateWall(triSurfaceSearch(surface));
}


void Foam::immersedBoundary::locateWall(const triSurfaceSearch& search)
{
    DynamicList<label> faces(nFaces());
    DynamicList<label> cells(nFaces());
    DynamicList<point> start(nFaces());
    DynamicList<point> end(nFaces());
    wallSegments(faces, cells, start, end);

    const pointField segStart(std::move(start));
    const pointField segEnd(std::move(end));
    List<pointIndexHit> hits;
    search.findLine(segStart, segEnd, hits);

    wallFraction_ = -1;
    forAll(hits, k)
    {
        if (hits[k].hit())
        {
            const scalar d = mag(segEnd[k] - segStart[k]);
            wallFraction_[faces[k]] =
                min(max(mag(hits[k].hitPoint() - segStart[k])/d, 0.0), 1.0);
        }
    }
}


void Foam::immersedBoundary::locateWall
(
    const UList<point>& points,
    const UList<labelledTri>& triangles,
    const CompactListList<label>& cellElements,
    const CompactListList<label>& elementTriangles
)
{
    DynamicList<label> faces(nFaces());
    DynamicList<label> cells(nFaces());
    DynamicList<point> start(nFaces());
    DynamicList<point> end(nFaces());
    wallSegments(faces, cells, start, end);

    if (cellElements.size() != coveredCells_.size())
    {
        FatalErrorInFunction
            << "elements listed for " << cellElements.size()
            << " covered cells, but " << coveredCells_.size()
            << " cells are covered: the lists must come from the same"
            << " search (touching coverage)" << exit(FatalError);
    }

    // The first crossing from the covered cell's centre, as
    // triSurfaceSearch::findLine (the same triangle test and tolerance)
    const scalar tol =
        indexedOctree<treeDataPrimitivePatch<triSurface>>::perturbTol();
    const labelList& cellOffsets = cellElements.offsets();
    const labelList& elements = cellElements.m();
    const labelList& triOffsets = elementTriangles.offsets();
    const labelList& tris = elementTriangles.m();

    wallFraction_ = -1;
    forAll(faces, k)
    {
        const point& a = start[k];
        const vector dir(end[k] - a);
        // (a triangle outside the segment's box is not crossed)
        const boundBox segBb(min(a, end[k]), max(a, end[k]));
        scalar lambda = GREAT;
        const label ic = cells[k];
        for (label i = cellOffsets[ic]; i < cellOffsets[ic + 1]; ++i)
        {
            const label e = elements[i];
            for (label j = triOffsets[e]; j < triOffsets[e + 1]; ++j)
            {
                const labelledTri& t = triangles[tris[j]];
                const point& p0 = points[t[0]];
                const point& p1 = points[t[1]];
                const point& p2 = points[t[2]];
                if
                (
                    !segBb.overlaps
                    (
                        boundBox(min(p0, min(p1, p2)), max(p0, max(p1, p2)))
                    )
                )
                {
                    continue;
                }
                const pointHit hit
                (
                    triPointRef(p0, p1, p2)
                   .intersection(a, dir, intersection::HALF_RAY, tol)
                );
                if (hit.hit() && hit.distance() <= 1)
                {
                    lambda = min(lambda, mag(hit.hitPoint() - a)/mag(dir));
                }
            }
        }
        if (lambda < GREAT)
        {
            wallFraction_[faces[k]] = min(max(lambda, 0.0), 1.0);
        }
    }
}


Foam::tmp<Foam::vectorField> Foam::immersedBoundary::ghostVelocity
(
    const volVectorField& U
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const label nInt = internalFaces_.size();
    // r = lambda/(1 - lambda) at most 2 (lambda <= 2/3): the explicit
    // extrapolation stays a contraction for the fluid cell's row
    const scalar rMax = 2;

    vectorField sum(coveredCells_.size(), Zero);
    labelList count(coveredCells_.size(), 0);

    auto add = [&](const label ic, const vector& uF, const scalar lambda)
    {
        const vector& us = coveredVelocity_[ic];
        const scalar r = min(lambda/max(1 - lambda, SMALL), rMax);
        sum[ic] += us + (us - uF)*r;
        ++count[ic];
    };

    forAll(internalFaces_, i)
    {
        if (wallFraction_[i] < 0)
        {
            continue;
        }
        const label facei = internalFaces_[i];
        const label io = coveredIndex_[own[facei]];
        const label F = io >= 0 ? nei[facei] : own[facei];
        add(io >= 0 ? io : coveredIndex_[nei[facei]], U[F], wallFraction_[i]);
    }
    if (Pstream::parRun())
    {
        vectorField nbrU;
        syncTools::swapBoundaryCellList(mesh_, U.primitiveField(), nbrU);
        forAll(boundaryFaces_, j)
        {
            if (wallFraction_[nInt + j] < 0)
            {
                continue;
            }
            const label facei = boundaryFaces_[j];
            add
            (
                coveredIndex_[mesh_.faceOwner()[facei]],
                nbrU[facei - mesh_.nInternalFaces()],
                wallFraction_[nInt + j]
            );
        }
    }

    tmp<vectorField> tu(new vectorField(coveredVelocity_));
    vectorField& u = tu.ref();
    forAll(u, i)
    {
        if (count[i])
        {
            u[i] = sum[i]/count[i];
        }
    }
    return tu;
}


void Foam::immersedBoundary::constrainCoupled
(
    fvMatrix<vector>& eqn,
    const vectorField& values
) const
{
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInternal = mesh_.nInternalFaces();
    scalarField& diag = eqn.diag();
    Field<vector>& source = eqn.source();

    // The covered side: the face's coefficient in the diagonal (as
    // fvMatrix::D() counts it), the value to the other side
    vectorField nbrValue(mesh_.nBoundaryFaces(), Zero);
    forAll(pbm, patchi)
    {
        if (!isA<processorPolyPatch>(pbm[patchi]))
        {
            continue;
        }
        const labelUList& faceCells = pbm[patchi].faceCells();
        Field<vector>& ic = eqn.internalCoeffs()[patchi];
        Field<vector>& bc = eqn.boundaryCoeffs()[patchi];
        const label start = pbm[patchi].start() - nInternal;
        forAll(faceCells, i)
        {
            const label ci = coveredIndex_[faceCells[i]];
            if (ci >= 0)
            {
                diag[faceCells[i]] += cmptAv(ic[i]);
                ic[i] = Zero;
                bc[i] = Zero;
                nbrValue[start + i] = values[ci];
            }
        }
    }
    syncTools::swapBoundaryFaceList(mesh_, nbrValue);

    // The fluid side: the covered cell's value in the source, as
    // setValues does for the neighbour of an internal face
    forAll(pbm, patchi)
    {
        if (!isA<processorPolyPatch>(pbm[patchi]))
        {
            continue;
        }
        const labelUList& faceCells = pbm[patchi].faceCells();
        Field<vector>& bc = eqn.boundaryCoeffs()[patchi];
        const label start = pbm[patchi].start() - nInternal;
        forAll(faceCells, i)
        {
            if (!covered(faceCells[i]) && nbrCovered_[start + i])
            {
                source[faceCells[i]] +=
                    cmptMultiply(bc[i], nbrValue[start + i]);
                bc[i] = Zero;
            }
        }
    }
}


void Foam::immersedBoundary::slip
(
    const volVectorField& U,
    scalar& sumSqr,
    label& count
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();

    boolList ghost(coveredCells_.size(), false);
    forAll(internalFaces_, i)
    {
        if (wallFraction_[i] >= 0)
        {
            const label facei = internalFaces_[i];
            const label io = coveredIndex_[own[facei]];
            ghost[io >= 0 ? io : coveredIndex_[nei[facei]]] = true;
        }
    }
    forAll(boundaryFaces_, j)
    {
        if (wallFraction_[internalFaces_.size() + j] >= 0)
        {
            ghost[coveredIndex_[mesh_.faceOwner()[boundaryFaces_[j]]]] = true;
        }
    }
    forAll(coveredCells_, i)
    {
        if (!ghost[i])
        {
            sumSqr += magSqr(U[coveredCells_[i]] - coveredVelocity_[i]);
            ++count;
        }
    }

    forAll(internalFaces_, i)
    {
        const scalar lambda = wallFraction_[i];
        if (lambda < 0)
        {
            continue;
        }
        const label facei = internalFaces_[i];
        const label io = coveredIndex_[own[facei]];
        const label Cc = io >= 0 ? own[facei] : nei[facei];
        const label F = io >= 0 ? nei[facei] : own[facei];
        const vector uWall(U[Cc] + lambda*(U[F] - U[Cc]));
        sumSqr += magSqr(uWall - coveredVelocity_[coveredIndex_[Cc]]);
        ++count;
    }

    // The wall points of the coupled faces, on their covered side (as
    // ghostVelocity: every rank takes part in the exchange)
    if (Pstream::parRun())
    {
        const label nInt = internalFaces_.size();
        vectorField nbrU;
        syncTools::swapBoundaryCellList(mesh_, U.primitiveField(), nbrU);
        forAll(boundaryFaces_, j)
        {
            const scalar lambda = wallFraction_[nInt + j];
            if (lambda < 0)
            {
                continue;
            }
            const label facei = boundaryFaces_[j];
            const label Cc = mesh_.faceOwner()[facei];
            const vector& uF = nbrU[facei - mesh_.nInternalFaces()];
            const vector uWall(U[Cc] + lambda*(uF - U[Cc]));
            sumSqr += magSqr(uWall - coveredVelocity_[coveredIndex_[Cc]]);
            ++count;
        }
    }
}


void Foam::immersedBoundary::findEnclosedFluid()
{
    // Fluid cells connected (through faces between fluid cells) to a cell
    // where the pressure is fixed: a boundary face whose p condition
    // fixes the value, or, with none in the domain, the reference cell
    // (the solver's, setPressureReference). Breadth-first fill over the
    // cell-cell addressing of the internal faces (primitiveMesh::cellCells),
    // repeated across processor faces until no rank changes.
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nCells = mesh_.nCells();
    ++nFills_;

    fluidFill reach(mesh_.cellCells(), coveredIndex_, nCells);

    const volScalarField* pPtr = mesh_.findObject<volScalarField>(pName_);
    bool anyFixed = false;
    if (pPtr)
    {
        forAll(pbm, patchi)
        {
            if
            (
                !pbm[patchi].coupled()
             && pPtr->boundaryField()[patchi].fixesValue()
            )
            {
                anyFixed = anyFixed || pbm[patchi].size();
                for (const label celli : pbm[patchi].faceCells())
                {
                    reach.seed(celli);
                }
            }
        }
    }
    reduce(anyFixed, orOp<bool>());
    enclosedFound_ = returnReduce(pPtr != nullptr, andOp<bool>());
    if (!anyFixed && refCell_ >= 0 && nCells)
    {
        reach.seed(min(refCell_, nCells - 1));
    }

    fillAcrossProcessors(mesh_, reach);

    // The fluid cells not reached form regions enclosed by the solid (and
    // walls) where the pressure is only known up to a constant: one cell
    // of each (this rank's part) gets a reference in constrainPressure
    refCells_.clear();
    const label nReached = reach.tail;
    region_ = -1;
    for (label i = 0; i < nReached; ++i)
    {
        region_[reach.queue[i]] = 0;
    }
    forAll(reach.reached, celli)
    {
        if (!reach.reached[celli] && coveredIndex_[celli] < 0)
        {
            const label first = reach.tail;
            refCells_.append(celli);
            reach.seed(celli);
            reach.fill();
            for (label i = first; i < reach.tail; ++i)
            {
                region_[reach.queue[i]] = refCells_.size();
            }
        }
    }
    nEnclosed_ = reach.tail - nReached;
}


Foam::label Foam::immersedBoundary::nextStamp()
{
    if (++stamp_ == labelMax)
    {
        mark_ = 0;
        stamp_ = 1;
    }
    return stamp_;
}


bool Foam::immersedBoundary::specialCell
(
    const label celli,
    const volScalarField* pPtr
) const
{
    // A cell whose group is not local (a coupled face) or that seeds the
    // fill (a face on a fixed-value pressure boundary)
    const cellList& cells = mesh_.cells();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    for (const label facei : cells[celli])
    {
        if (!mesh_.isInternalFace(facei))
        {
            const label patchi = pbm.whichPatch(facei);
            if
            (
                pbm[patchi].coupled()
             || (pPtr && pPtr->boundaryField()[patchi].fixesValue())
            )
            {
                return true;
            }
        }
    }
    return celli == refCell_ || refCells_.found(celli);
}


bool Foam::immersedBoundary::targetsConnected
(
    const labelUList& targets,
    DynamicList<label>& queue,
    labelList& parent
)
{
    const labelListList& cellCells = mesh_.cellCells();

    // fills from all targets at once through fluid cells, joining
    // the targets whose fills meet (union-find), until one set is
    // left or the budget is spent
    const label visited = nextStamp();
    parent.setSize(targets.size());
    queue.clear();
    forAll(targets, i)
    {
        parent[i] = i;
        mark_[targets[i]] = visited;
        owner_[targets[i]] = i;
        queue.append(targets[i]);
    }
    auto find = [&](label i)
    {
        while (parent[i] != i)
        {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    };
    label nSets = targets.size();
    const label budget = 50*targets.size() + 1000;
    for (label head = 0; head < queue.size() && nSets > 1; ++head)
    {
        if (queue.size() > budget)
        {
            break;
        }
        const label celli = queue[head];
        for (const label nb : cellCells[celli])
        {
            if (covered(nb))
            {
                continue;
            }
            if (mark_[nb] != visited)
            {
                mark_[nb] = visited;
                owner_[nb] = owner_[celli];
                queue.append(nb);
            }
            else
            {
                const label a = find(owner_[nb]);
                const label b = find(owner_[celli]);
                if (a != b)
                {
                    parent[a] = b;
                    --nSets;
                }
            }
        }
    }
    return nSets == 1;
}


void Foam::immersedBoundary::checkCoveredGroups
(
    const labelUList& newlyCovered,
    const volScalarField* pPtr,
    bool& ok,
    label& nEnclosedCovered
)
{
    const labelListList& cellCells = mesh_.cellCells();

    // (a) newly covered groups
    const label inA = nextStamp();
    for (const label celli : newlyCovered)
    {
        mark_[celli] = inA;
    }
    DynamicList<label> group;
    DynamicList<label> targets;
    DynamicList<label> queue;
    labelList parent;
    for (const label start : newlyCovered)
    {
        if (!ok)
        {
            break;
        }
        if (mark_[start] != inA)
        {
            continue;   // grouped already
        }
        // the group and its fluid neighbours
        const label grouped = nextStamp();
        group.clear();
        group.append(start);
        mark_[start] = grouped;
        targets.clear();
        const label isTarget = nextStamp();
        for (label i = 0; i < group.size() && ok; ++i)
        {
            const label celli = group[i];
            if (specialCell(celli, pPtr))
            {
                ok = false;
            }
            if (region_[celli] > 0)
            {
                ++nEnclosedCovered;
            }
            for (const label nb : cellCells[celli])
            {
                if (mark_[nb] == inA)
                {
                    mark_[nb] = grouped;
                    group.append(nb);
                }
                else if (!covered(nb) && mark_[nb] != isTarget)
                {
                    mark_[nb] = isTarget;
                    targets.append(nb);
                }
            }
        }
        if (!ok || targets.size() < 2)
        {
            continue;
        }
        ok = targetsConnected(targets, queue, parent);
    }
}


void Foam::immersedBoundary::checkUncoveredGroups
(
    const labelUList& newlyUncovered,
    const volScalarField* pPtr,
    bool& ok,
    DynamicList<label>& joined,
    DynamicList<label>& joinedRegion
)
{
    const labelListList& cellCells = mesh_.cellCells();

    // (b) newly uncovered groups: the region of the fluid they border
    const label inB = nextStamp();
    for (const label celli : newlyUncovered)
    {
        mark_[celli] = inB;
    }
    DynamicList<label> group;
    for (const label start : newlyUncovered)
    {
        if (!ok)
        {
            break;
        }
        if (mark_[start] != inB)
        {
            continue;
        }
        const label grouped = nextStamp();
        group.clear();
        group.append(start);
        mark_[start] = grouped;
        label r = -1;
        for (label i = 0; i < group.size() && ok; ++i)
        {
            const label celli = group[i];
            if (specialCell(celli, pPtr))
            {
                ok = false;
            }
            for (const label nb : cellCells[celli])
            {
                if (mark_[nb] == inB)
                {
                    mark_[nb] = grouped;
                    group.append(nb);
                }
                else if (!covered(nb) && mark_[nb] != grouped)
                {
                    // fluid before and now: its region is current
                    if (r < 0)
                    {
                        r = region_[nb];
                    }
                    else if (region_[nb] != r)
                    {
                        ok = false;     // regions merge
                    }
                }
            }
        }
        if (r < 0)
        {
            ok = false;                 // a new region
        }
        if (ok)
        {
            for (const label celli : group)
            {
                joined.append(celli);
                joinedRegion.append(r);
            }
        }
    }
}


bool Foam::immersedBoundary::updateEnclosedFluid
(
    const labelUList& newlyCovered,
    const labelUList& newlyUncovered
)
{
    // The regions of the last fill stay what they were when (a) every
    // connected group of newly covered cells leaves its fluid neighbours
    // connected to each other (then any path of fluid cells through the
    // group can go round it), none of them being a seed of the fill or a
    // reference cell; and (b) every connected group of newly uncovered
    // cells borders fluid of one region only (it joins that region).
    // Checked locally (within this rank, a bounded fill); anything else
    // (a group on a processor face, regions that merge or split) asks for
    // the whole fill. Same result as findEnclosedFluid (test
    // fsiCoupling.enclosedUpdate).
    const volScalarField* pPtr = mesh_.findObject<volScalarField>(pName_);

    bool ok = (pPtr != nullptr) && enclosedFound_;
    if (mark_.size() != mesh_.nCells())
    {
        mark_.setSize(mesh_.nCells(), 0);
        owner_.setSize(mesh_.nCells(), -1);
        stamp_ = 0;
    }

    // (a) newly covered groups
    label nEnclosedCovered = 0;
    checkCoveredGroups(newlyCovered, pPtr, ok, nEnclosedCovered);

    // (b) newly uncovered groups: the region of the fluid they border
    DynamicList<label> joined;
    DynamicList<label> joinedRegion;
    checkUncoveredGroups(newlyUncovered, pPtr, ok, joined, joinedRegion);

    if (!returnReduce(ok, andOp<bool>()))
    {
        return false;
    }
    for (const label celli : newlyCovered)
    {
        region_[celli] = -1;
    }
    label nEnclosedJoined = 0;
    forAll(joined, i)
    {
        region_[joined[i]] = joinedRegion[i];
        nEnclosedJoined += (joinedRegion[i] > 0);
    }
    nEnclosed_ += nEnclosedJoined - nEnclosedCovered;
    ++nLocalUpdates_;
    return true;
}


Foam::vector Foam::immersedBoundary::solidVelocity(const label facei) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const label nInternal = mesh_.nInternalFaces();

    // The solid flux u_s . S_f of an immersed face (the mean of the two
    // covered cells' u_s between two of them): its u_s
    if (facei < nInternal)
    {
        const label io = coveredIndex_[own[facei]];
        const label in = coveredIndex_[nei[facei]];
        if (io >= 0 && in >= 0)
        {
            return vector(0.5*(coveredVelocity_[io] + coveredVelocity_[in]));
        }
        return vector(coveredVelocity_[io >= 0 ? io : in]);
    }
    const label io = coveredIndex_[mesh_.faceOwner()[facei]];
    const bool nc = nbrCovered(facei);
    const vector& un = nbrVelocity_[facei - nInternal];
    if (io >= 0 && nc)
    {
        return vector(0.5*(coveredVelocity_[io] + un));
    }
    return vector(io >= 0 ? coveredVelocity_[io] : un);
}


void Foam::immersedBoundary::constrainFlux(surfaceScalarField& phi) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const surfaceVectorField& Sf = mesh_.Sf();
    const surfaceScalarField& magSf = mesh_.magSf();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();

    // The solid's volume change seen by the fluid: the net solid flux out
    // of the covered cells through their faces to fluid cells, Q over
    // their area A (all ranks: a processor face counted on its covered
    // side). The fluid takes the solid as volume-preserving: each such
    // face's solid flux loses Q |S_f|/A (outward). A compressible solid's
    // squeeze (nu < 0.5) would otherwise be a mass source that the
    // incompressible fluid can only absorb by accelerating the whole
    // column to the outlet within one step: a pressure that grows as
    // 1/dt^2 and squeezes the solid further (the coupling diverged on
    // the Turek-Hron flag, nu_s = 0.4, whatever its density).
    scalar Q = 0;
    scalar A = 0;
    for (const label facei : internalFaces_)
    {
        const bool co = covered(own[facei]);
        if (co != covered(nei[facei]))
        {
            const scalar phis = solidVelocity(facei) & Sf[facei];
            Q += co ? phis : -phis;
            A += magSf[facei];
        }
    }
    for (const label facei : boundaryFaces_)
    {
        const label patchi = pbm.whichPatch(facei);
        const label i = facei - pbm[patchi].start();
        if (covered(mesh_.faceOwner()[facei]) && !nbrCovered(facei))
        {
            Q += solidVelocity(facei) & Sf.boundaryField()[patchi][i];
            A += magSf.boundaryField()[patchi][i];
        }
    }
    reduce(Q, sumOp<scalar>());
    reduce(A, sumOp<scalar>());
    const scalar q = A > VSMALL ? Q/A : 0;

    scalarField& phiI = phi.primitiveFieldRef();
    for (const label facei : internalFaces_)
    {
        phiI[facei] = solidVelocity(facei) & Sf[facei];
        const bool co = covered(own[facei]);
        if (co != covered(nei[facei]))
        {
            phiI[facei] -= (co ? q : -q)*magSf[facei];
            if (ramp_)
            {
                phiI[facei] = rampedFlux(facei, phiI[facei]);
            }
        }
    }

    auto& phiB = phi.boundaryFieldRef();
    for (const label facei : boundaryFaces_)
    {
        const label patchi = pbm.whichPatch(facei);
        const label i = facei - pbm[patchi].start();
        phiB[patchi][i] = solidVelocity(facei) & Sf.boundaryField()[patchi][i];
        const bool co = covered(mesh_.faceOwner()[facei]);
        if (co != nbrCovered(facei))
        {
            phiB[patchi][i] -= (co ? q : -q)*magSf.boundaryField()[patchi][i];
            if (ramp_)
            {
                phiB[patchi][i] = rampedFlux(facei, phiB[patchi][i]);
            }
        }
    }
}


void Foam::immersedBoundary::keepRamp
(
    const label facei,
    const scalar t,
    Map<ramp>& running
) const
{
    const auto iter = ramps_.cfind(facei);
    if (iter.found() && t - iter.val().start < iter.val().tau)
    {
        running.insert(facei, iter.val());
    }
}


void Foam::immersedBoundary::startRamp
(
    const label facei,
    const scalar frozen,
    const vector& us,
    const scalar d,
    const scalar t,
    const scalar dt,
    Map<ramp>& running
)
{
    const scalar u = mag(us);
    if (u > VSMALL)
    {
        // (started at the last step: its first weight is 1 - dt/tau)
        running.set(facei, ramp{t - dt, d/u, frozen});
    }
}


void Foam::immersedBoundary::reportRamps
(
    const scalar t,
    const scalar dt
) const
{
    // (DebugSwitches { immersedBoundary 1; } in controlDict)
    if (debug && ramps_.size())
    {
        scalar tauMin = GREAT, tauMax = 0, frozenMax = 0;
        label nFresh = 0;
        forAllConstIters(ramps_, iter)
        {
            const ramp& r = iter.val();
            tauMin = min(tauMin, r.tau);
            tauMax = max(tauMax, r.tau);
            frozenMax = max(frozenMax, mag(r.frozen));
            if (r.start > t - 1.5*dt)
            {
                ++nFresh;
            }
        }
        Pout<< "immersedBoundary ramps at t = " << t << ": " << ramps_.size()
            << " running (" << nFresh << " new), tau/dt "
            << tauMin/dt << " to " << tauMax/dt << ", max |frozen flux| "
            << frozenMax << endl;
    }
}


void Foam::immersedBoundary::updateRamps
(
    const labelUList& newlyCovered,
    const boolList& oldNbrCovered
)
{
    // A face between a covered and a fluid cell whose covered cell was
    // fluid at the last update: its flux goes from the one it had (phi,
    // the last step's, in this rank's orientation) to the solid's over
    // the time the solid takes to move from the covered cell's centre to
    // the fluid cell's, tau = |x_F - x_C|/|u_s|
    const scalar t = mesh_.time().value();
    const scalar dt = mesh_.time().deltaTValue();
    const surfaceScalarField* phiPtr =
        mesh_.findObject<surfaceScalarField>("phi");
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const vectorField& C = mesh_.cellCentres();
    const label nInternal = mesh_.nInternalFaces();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();

    // the ramps still running on faces still between covered and fluid
    // (keepRamp), and those that start (startRamp)
    Map<ramp> running(2*ramps_.size());

    labelHashSet fresh(newlyCovered);
    for (const label facei : internalFaces_)
    {
        const label o = own[facei];
        const label n = nei[facei];
        if (covered(o) == covered(n))
        {
            continue;
        }
        const label c = covered(o) ? o : n;
        if (fresh.found(c) && phiPtr)
        {
            startRamp
            (
                facei,
                (*phiPtr)[facei],
                coveredVelocity_[coveredIndex_[c]],
                mag(C[n] - C[o]),
                t,
                dt,
                running
            );
        }
        else
        {
            keepRamp(facei, t, running);
        }
    }
    {
        // (collective: every rank, with or without immersed coupled faces)
        pointField nbrC;
        syncTools::swapBoundaryCellList(mesh_, C, nbrC);
        for (const label facei : boundaryFaces_)
        {
            const label o = mesh_.faceOwner()[facei];
            const label bf = facei - nInternal;
            if (covered(o) == nbrCovered_[bf])
            {
                continue;
            }
            const bool newly =
                covered(o) ? fresh.found(o) : !oldNbrCovered[bf];
            if (newly && phiPtr)
            {
                const label patchi = pbm.whichPatch(facei);
                startRamp
                (
                    facei,
                    phiPtr->boundaryField()[patchi]
                        [facei - pbm[patchi].start()],
                    covered(o)
                  ? coveredVelocity_[coveredIndex_[o]]
                  : nbrVelocity_[bf],
                    mag(nbrC[bf] - C[o]),
                    t,
                    dt,
                    running
                );
            }
            else
            {
                keepRamp(facei, t, running);
            }
        }
    }
    ramps_.transfer(running);

    reportRamps(t, dt);
}


Foam::tmp<Foam::scalarField> Foam::immersedBoundary::immersedArea() const
{
    auto tA = tmp<scalarField>::New(coveredCells_.size(), Zero);
    scalarField& A = tA.ref();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const scalarField& magSf = mesh_.magSf();
    for (const label facei : internalFaces_)
    {
        const label c = covered(own[facei]) ? own[facei] : nei[facei];
        A[coveredIndex_[c]] += magSf[facei];
    }
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    for (const label facei : boundaryFaces_)
    {
        const label o = mesh_.faceOwner()[facei];
        if (covered(o))
        {
            const label patchi = pbm.whichPatch(facei);
            A[coveredIndex_[o]] +=
                mesh_.magSf().boundaryField()[patchi]
                [facei - pbm[patchi].start()];
        }
    }
    return tA;
}


void Foam::immersedBoundary::writeRamps(const fileName& file) const
{
    mkDir(file.path());
    OFstream os(file);
    os.precision(17);
    const labelList faces(ramps_.sortedToc());
    scalarList start(faces.size()), tau(faces.size()), frozen(faces.size());
    forAll(faces, i)
    {
        const ramp& r = ramps_[faces[i]];
        start[i] = r.start;
        tau[i] = r.tau;
        frozen[i] = r.frozen;
    }
    os  << "// immersedBoundary covering ramps (isfem restart state)" << nl;
    os.writeEntry("faces", faces);
    os.writeEntry("start", start);
    os.writeEntry("tau", tau);
    os.writeEntry("frozen", frozen);
    if (!os.good())
    {
        FatalErrorInFunction
            << "Cannot write " << file << exit(FatalError);
    }
}


void Foam::immersedBoundary::readRamps(const fileName& file)
{
    if (!isFile(file))
    {
        return;
    }
    IFstream is(file);
    const dictionary dict(is);
    const labelList faces(dict.get<labelList>("faces"));
    const scalarList start(dict.get<scalarList>("start"));
    const scalarList tau(dict.get<scalarList>("tau"));
    const scalarList frozen(dict.get<scalarList>("frozen"));
    if
    (
        start.size() != faces.size()
     || tau.size() != faces.size()
     || frozen.size() != faces.size()
    )
    {
        FatalIOErrorInFunction(dict)
            << "The lists of " << file << " differ in length: the file is"
            << " damaged; remove it (the ramps then restart) or restart"
            << " from an earlier time" << exit(FatalIOError);
    }
    ramps_.clear();
    forAll(faces, i)
    {
        if (faces[i] < 0 || faces[i] >= mesh_.nFaces())
        {
            FatalIOErrorInFunction(dict)
                << "Face " << faces[i] << " of " << file << " is not a face"
                << " of the mesh (" << mesh_.nFaces() << " faces): the"
                << " file belongs to another mesh or decomposition"
                << exit(FatalIOError);
        }
        ramps_.insert(faces[i], ramp{start[i], tau[i], frozen[i]});
    }
    updated_ = true;
}


Foam::scalar Foam::immersedBoundary::rampedFlux
(
    const label facei,
    const scalar solidFlux
) const
{
    const auto iter = ramps_.cfind(facei);
    if (!iter.found())
    {
        return solidFlux;
    }
    const ramp& r = iter.val();
    const scalar w =
        max(1 - (mesh_.time().value() - r.start)/r.tau, scalar(0));
    return w*r.frozen + (1 - w)*solidFlux;
}


void Foam::immersedBoundary::constrainLaplacian
(
    surfaceScalarField& rAUf
) const
{
    scalarField& rI = rAUf.primitiveFieldRef();
    for (const label facei : internalFaces_)
    {
        rI[facei] = 0;
    }
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    auto& rB = rAUf.boundaryFieldRef();
    for (const label facei : boundaryFaces_)
    {
        const label patchi = pbm.whichPatch(facei);
        rB[patchi][facei - pbm[patchi].start()] = 0;
    }
}


void Foam::immersedBoundary::constrainPressure
(
    fvScalarMatrix& pEqn,
    const volScalarField& p
) const
{
    // With the coefficients of all their faces zero (constrainLaplacian)
    // the covered cells are decoupled; each row becomes D p = D p_old.
    // D is small (1e-6 of the mean diagonal, same sign): a multigrid
    // agglomerate that joins a covered cell and fluid cells (agglomeration
    // by face areas) then keeps the fluid cells' coarse operator; a large D
    // there acts as a spurious fixed value on the coarse levels (GAMG
    // stalled at 1000 iterations with D = the mean diagonal).
    // Fluid regions enclosed by the solid (findEnclosedFluid) have no
    // fixed pressure: pure Neumann blocks, singular (a single enclosed
    // cell is a zero row); GAMG diverged on them. One cell of each gets a
    // reference to its current value, as fvMatrix::setReference does
    scalarField& diag = pEqn.diag();
    scalarField& source = pEqn.source();
    const scalar D = 1e-6*gAverage(diag);
    for (const label celli : coveredCells_)
    {
        diag[celli] = D;
        source[celli] = D*p[celli];
    }
    for (const label celli : refCells_)
    {
        source[celli] += diag[celli]*p[celli];
        diag[celli] += diag[celli];
        if (diag[celli] == 0)
        {
            diag[celli] = D;
            source[celli] = D*p[celli];
        }
    }
}


void Foam::immersedBoundary::wallCellMatrices
(
    Map<label>& wallCell,
    DynamicList<label>& wallCells,
    DynamicList<tensor>& M
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const vectorField& Sf = mesh_.faceAreas();
    const vectorField& Cf = mesh_.faceCentres();
    const vectorField& C = mesh_.cellCentres();
    const scalarField& V = mesh_.cellVolumes();

    // M per fluid cell beside the wall: with the wall values
    // p_F + (x_f - x_F).g on its immersed faces, its Gauss gradient
    // satisfies g = g0 + M g, M = (1/V) sum_imm S_f (x_f - x_F)^T, g0 the
    // Gauss gradient with p_F there (zero gradient at the wall)
    wallCell.clear();
    wallCell.resize(2*internalFaces_.size());
    auto addFace = [&](const label F, const vector& S, const point& xf)
    {
        auto iter = wallCell.cfind(F);
        label k;
        if (iter.found())
        {
            k = iter.val();
        }
        else
        {
            k = wallCells.size();
            wallCell.insert(F, k);
            wallCells.append(F);
            M.append(Zero);
        }
        M[k] += (S*(xf - C[F]))/V[F];
    };
    for (const label facei : internalFaces_)
    {
        const label o = own[facei];
        const label n = nei[facei];
        const bool oc = covered(o);
        if (oc != covered(n))
        {
            // S_f points out of the owner
            if (oc)
            {
                addFace(n, -Sf[facei], Cf[facei]);
            }
            else
            {
                addFace(o, Sf[facei], Cf[facei]);
            }
        }
    }
    for (const label facei : boundaryFaces_)
    {
        const label o = mesh_.faceOwner()[facei];
        if (!covered(o))
        {
            addFace(o, Sf[facei], Cf[facei]);
        }
    }
}


void Foam::immersedBoundary::wallCellGradients
(
    const volScalarField& p,
    const scalarField& pNbr,
    const labelUList& wallCells,
    const UList<tensor>& M,
    vectorField& gradient
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const vectorField& Sf = mesh_.faceAreas();
    const scalarField& V = mesh_.cellVolumes();
    const surfaceScalarField& weights = mesh_.weights();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const cellList& cells = mesh_.cells();
    const label nInternal = mesh_.nInternalFaces();

    // g0 of each wall cell: face values as linearInterpolate's, p_F on its
    // immersed faces; then g = (I - M)^-1 g0. Where I - M is near singular
    // (the immersed faces surround the cell on opposite sides: no
    // information across; det < 0.1, e.g. a cell between the two layers
    // of a leaflet) the zero-gradient values are kept (g = g0).
    gradient.setSize(wallCells.size());
    forAll(wallCells, k)
    {
        const label F = wallCells[k];
        vector g0(Zero);
        for (const label facei : cells[F])
        {
            if (facei < nInternal)
            {
                const label o = own[facei];
                const label n = nei[facei];
                const scalar pf =
                    covered(o == F ? n : o)
                  ? p[F]
                  : weights[facei]*p[o] + (1 - weights[facei])*p[n];
                g0 += (o == F ? Sf[facei] : -Sf[facei])*pf;
                continue;
            }
            const label patchi = pbm.whichPatch(facei);
            if (isA<emptyPolyPatch>(pbm[patchi]))
            {
                continue;
            }
            const label i = facei - pbm[patchi].start();
            scalar pf;
            if (!pbm[patchi].coupled())
            {
                pf = p.boundaryField()[patchi][i];
            }
            else if (nbrCovered(facei))
            {
                pf = p[F];
            }
            else
            {
                const scalar w = weights.boundaryField()[patchi][i];
                pf = w*p[F] + (1 - w)*pNbr[facei - nInternal];
            }
            g0 += Sf[facei]*pf;
        }
        g0 /= V[F];
        const tensor A(I - M[k]);
        gradient[k] = mag(det(A)) > 0.1 ? (inv(A) & g0) : g0;
    }
}


void Foam::immersedBoundary::wallValues
(
    const volScalarField& p,
    scalarField& internalWall,
    scalarField& boundaryWall,
    Map<label>& wallCell,
    vectorField& gradient
) const
{
    // Only the fluid cells beside the wall and their faces are visited (no
    // field over all cells or faces)
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const vectorField& Cf = mesh_.faceCentres();
    const vectorField& C = mesh_.cellCentres();
    const label nInternal = mesh_.nInternalFaces();

    // M per fluid cell beside the wall (wallCellMatrices)
    DynamicList<label> wallCells(internalFaces_.size());
    DynamicList<tensor> M(internalFaces_.size());
    wallCellMatrices(wallCell, wallCells, M);

    // p across the coupled faces (all ranks take part)
    scalarField pNbr;
    syncTools::swapBoundaryCellList(mesh_, p.primitiveField(), pNbr);

    // g of each wall cell (wallCellGradients)
    wallCellGradients(p, pNbr, wallCells, M, gradient);

    // The wall values with those gradients
    internalWall.setSize(internalFaces_.size());
    internalWall = 0;
    forAll(internalFaces_, j)
    {
        const label facei = internalFaces_[j];
        const label o = own[facei];
        const label n = nei[facei];
        const bool oc = covered(o);
        if (oc != covered(n))
        {
            const label F = oc ? n : o;
            internalWall[j] =
                p[F] + ((Cf[facei] - C[F]) & gradient[wallCell[F]]);
        }
    }
    boundaryWall.setSize(boundaryFaces_.size());
    boundaryWall = 0;
    scalarField nbrWall;
    if (boundaryFaces_.size() || Pstream::parRun())
    {
        nbrWall.setSize(mesh_.nBoundaryFaces(), Zero);
    }
    forAll(boundaryFaces_, j)
    {
        const label facei = boundaryFaces_[j];
        const label o = mesh_.faceOwner()[facei];
        if (!covered(o))
        {
            boundaryWall[j] =
                p[o] + ((Cf[facei] - C[o]) & gradient[wallCell[o]]);
            nbrWall[facei - nInternal] = boundaryWall[j];
        }
    }

    // Coupled faces with the covered cell on this side: the wall value of
    // the fluid side, from the other rank
    if (boundaryFaces_.size() || Pstream::parRun())
    {
        syncTools::swapBoundaryFaceList(mesh_, nbrWall);
        forAll(boundaryFaces_, j)
        {
            const label facei = boundaryFaces_[j];
            if (covered(mesh_.faceOwner()[facei]) && !nbrCovered(facei))
            {
                boundaryWall[j] = nbrWall[facei - nInternal];
            }
        }
    }
}


Foam::tmp<Foam::surfaceScalarField> Foam::immersedBoundary::wallFaceValues
(
    const volScalarField& p
) const
{
    scalarField internalWall;
    scalarField boundaryWall;
    Map<label> wallCell;
    vectorField gradient;
    wallValues(p, internalWall, boundaryWall, wallCell, gradient);

    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();

    tmp<surfaceScalarField> tpf(linearInterpolate(p));
    surfaceScalarField& pf = tpf.ref();
    scalarField& pfI = pf.primitiveFieldRef();
    auto& pfB = pf.boundaryFieldRef();
    forAll(internalFaces_, j)
    {
        const label facei = internalFaces_[j];
        if (covered(own[facei]) != covered(nei[facei]))
        {
            pfI[facei] = internalWall[j];
        }
    }
    forAll(boundaryFaces_, j)
    {
        const label facei = boundaryFaces_[j];
        if (covered(mesh_.faceOwner()[facei]) != nbrCovered(facei))
        {
            const label patchi = pbm.whichPatch(facei);
            pfB[patchi][facei - pbm[patchi].start()] = boundaryWall[j];
        }
    }
    return tpf;
}


Foam::tmp<Foam::volVectorField> Foam::immersedBoundary::gaussGrad
(
    const surfaceScalarField& pf,
    const word& name
) const
{
    tmp<volVectorField> tg
    (
        new volVectorField
        (
            IOobject
            (
                "immersedGrad(" + name + ')',
                pf.instance(),
                mesh_,
                IOobject::NO_READ,
                IOobject::NO_WRITE,
                false
            ),
            fvc::surfaceIntegrate(mesh_.Sf()*pf),
            "zeroGradient"
        )
    );
    tg.ref().correctBoundaryConditions();
    return tg;
}


Foam::tmp<Foam::volVectorField> Foam::immersedBoundary::grad
(
    const volScalarField& p
) const
{
    return gaussGrad(wallFaceValues(p)(), p.name());
}


Foam::tmp<Foam::volVectorField> Foam::immersedBoundary::correctPressure
(
    volScalarField& p
) const
{
    // the gradient first: the covered cells' values set below do not
    // enter the fluid cells' wall values
    const tmp<surfaceScalarField> tpf(wallFaceValues(p));
    const surfaceScalarField& pf = tpf();
    tmp<volVectorField> tgrad(gaussGrad(pf, p.name()));
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();

    scalarField sum(coveredCells_.size(), Zero);
    labelList count(coveredCells_.size(), 0);
    for (const label facei : internalFaces_)
    {
        const label io = coveredIndex_[own[facei]];
        const label in = coveredIndex_[nei[facei]];
        if ((io >= 0) != (in >= 0))
        {
            const label i = io >= 0 ? io : in;
            sum[i] += pf[facei];
            ++count[i];
        }
    }
    for (const label facei : boundaryFaces_)
    {
        const label io = coveredIndex_[mesh_.faceOwner()[facei]];
        if (io >= 0 && !nbrCovered(facei))
        {
            const label patchi = pbm.whichPatch(facei);
            sum[io] += pf.boundaryField()[patchi][facei - pbm[patchi].start()];
            ++count[io];
        }
    }
    scalarField& pI = p.primitiveFieldRef();
    forAll(coveredCells_, i)
    {
        if (count[i])
        {
            pI[coveredCells_[i]] = sum[i]/count[i];
        }
    }
    p.correctBoundaryConditions();
    return tgrad;
}


void Foam::immersedBoundary::internalTraction
(
    const volScalarField& p,
    const volVectorField& U,
    const volScalarField& nu,
    const scalar rhoFluid,
    const scalarField& internalWall,
    const Map<label>& wallCell,
    const vectorField& gradp,
    vectorField& t,
    vector& coveredGradP
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const vectorField& Sf = mesh_.faceAreas();
    const surfaceScalarField& delta = mesh_.nonOrthDeltaCoeffs();
    const vectorField& Cc = mesh_.cellCentres();

    forAll(internalFaces_, facej)
    {
        const label facei = internalFaces_[facej];
        const label o = own[facei];
        const label n = nei[facei];
        const label io = coveredIndex_[o];
        const label in = coveredIndex_[n];
        if ((io >= 0) == (in >= 0))
        {
            continue;
        }
        // S from the covered cell C to the fluid cell F
        const label C = io >= 0 ? o : n;
        const label F = io >= 0 ? n : o;
        const vector S(io >= 0 ? Sf[facei] : -Sf[facei]);
        // pressure at the wall point, else at the face
        const scalar lambda = wallFraction_[facej];
        const scalar pw =
            lambda < 0
          ? internalWall[facej]
          : p[F]
          + ((Cc[C] + lambda*(Cc[F] - Cc[C]) - Cc[F]) & gradp[wallCell[F]]);
        t[io >= 0 ? io : in] +=
            rhoFluid
           *(
              - pw*S
              + nu[F]*mag(S)*delta[facei]*(U[F] - U[C])
            );
        coveredGradP += internalWall[facej]*S;
    }
}


void Foam::immersedBoundary::coupledTraction
(
    const volScalarField& p,
    const volVectorField& U,
    const volScalarField& nu,
    const scalar rhoFluid,
    const scalarField& boundaryWall,
    const Map<label>& wallCell,
    const vectorField& gradp,
    vectorField& t,
    vector& coveredGradP
) const
{
    const vectorField& Sf = mesh_.faceAreas();
    const surfaceScalarField& delta = mesh_.nonOrthDeltaCoeffs();
    const vectorField& Cc = mesh_.cellCentres();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInternal = mesh_.nInternalFaces();

    // U and nu across the coupled faces, and for the wall point the fluid
    // cell's p, centre and wall gradient g_F (collective)
    vectorField Unbr;
    scalarField nuNbr;
    syncTools::swapBoundaryCellList(mesh_, U.primitiveField(), Unbr);
    syncTools::swapBoundaryCellList(mesh_, nu.primitiveField(), nuNbr);
    scalarField pNbr;
    pointField Cnbr;
    syncTools::swapBoundaryCellList(mesh_, p.primitiveField(), pNbr);
    syncTools::swapBoundaryCellList(mesh_, Cc, Cnbr);
    vectorField gradpNbr(mesh_.nBoundaryFaces(), Zero);
    for (const label facei : boundaryFaces_)
    {
        const label o = mesh_.faceOwner()[facei];
        if (!covered(o))
        {
            gradpNbr[facei - nInternal] = gradp[wallCell[o]];
        }
    }
    syncTools::swapBoundaryFaceList(mesh_, gradpNbr);
    forAll(boundaryFaces_, j)
    {
        const label facei = boundaryFaces_[j];
        const label o = mesh_.faceOwner()[facei];
        const label io = coveredIndex_[o];
        if (io < 0 || nbrCovered(facei))
        {
            continue;
        }
        const label patchi = pbm.whichPatch(facei);
        const label i = facei - pbm[patchi].start();
        const label b = facei - nInternal;
        const vector& S = Sf[facei];
        // pressure at the wall point, else at the face: as on an internal
        // face, from the fluid cell across
        const scalar lambda = wallFraction_[internalFaces_.size() + j];
        const scalar pw =
            lambda < 0
          ? boundaryWall[j]
          : pNbr[b]
          + ((Cc[o] + lambda*(Cnbr[b] - Cc[o]) - Cnbr[b]) & gradpNbr[b]);
        t[io] +=
            rhoFluid
           *(
              - pw*S
              + nuNbr[b]*mag(S)*delta.boundaryField()[patchi][i]
               *(Unbr[b] - U[o])
            );
        coveredGradP += boundaryWall[j]*S;
    }
}


Foam::tmp<Foam::vectorField> Foam::immersedBoundary::traction
(
    const volScalarField& p,
    const volVectorField& U,
    const volScalarField& nu,
    const scalar rhoFluid,
    vector& coveredGradP
) const
{
    tmp<vectorField> tt(new vectorField(coveredCells_.size(), Zero));
    vectorField& t = tt.ref();
    coveredGradP = Zero;

    scalarField internalWall;
    scalarField boundaryWall;
    Map<label> wallCell;
    vectorField gradp;
    wallValues(p, internalWall, boundaryWall, wallCell, gradp);

    internalTraction
    (
        p, U, nu, rhoFluid, internalWall, wallCell, gradp, t, coveredGradP
    );

    // Coupled faces: U and nu across them, and for the wall point the
    // fluid cell's p, centre and wall gradient g_F (all ranks take part;
    // none where no rank has such a face, as in a serial run)
    if (!returnReduce(boundaryFaces_.size(), sumOp<label>()))
    {
        return tt;
    }
    coupledTraction
    (
        p, U, nu, rhoFluid, boundaryWall, wallCell, gradp, t, coveredGradP
    );

    return tt;
}


// ************************************************************************* //
