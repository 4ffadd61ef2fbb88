/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedPairs.H"
#include "Random.H"
#include "PstreamReduceOps.H"
#include "Tuple2.H"
#include "processorPolyPatch.H"
#include "treeDataCell.H"
#include "treeDataFace.H"
#include "polyMeshTetDecomposition.H"
#include "clockValue.H"


// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(immersedPairs, 0);
}

const Foam::Enum<Foam::immersedPairs::coverageType>
Foam::immersedPairs::coverageTypeNames
({
    { coverageType::centre, "centre" },
    { coverageType::touching, "touching" },
});


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedPairs::immersedPairs
(
    const polyMesh& mesh,
    const dictionary& dict
)
:
    mesh_(mesh),
    locator_(mesh, dict.getOrDefault<label>("maxWalk", 100)),
    centreTree_(),
    cellBoxTree_(),
    coverage_
    (
        coverageTypeNames.getOrDefault("coverage", dict, coverageType::centre)
    ),

    boundaryTolerance_(dict.getOrDefault<scalar>("boundaryTolerance", 0.25)),
    maxBoundaryDistance_(0),
    nodeCell_(),
    nOnBoundary_(0),
    maxOutside_(0),
    candidates_(),
    candidateGap_(),
    candidateCentreGap_(),
    candidateX_(),
    lastX_(),
    margin_(0),
    nCandidateUpdates_(0),
    nPairTests_(0),
    nPairsSkipped_(0),
    cellBb_(),
    nearCoupled_(),
    visitedBy_(),
    fillCells_(),
    stamp_(0),
    slot_(),
    nearElements_(),
    nearPairs_()
{
    if (!(boundaryTolerance_ >= 0 && boundaryTolerance_ <= 1))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'boundaryTolerance' " << boundaryTolerance_ << " in "
            << dict.name() << " must lie in [0, 1] (a fraction of a cell's"
            << " size: how far outside the fluid mesh a solid node may lie)"
            << exit(FatalIOError);
    }
    maxBoundaryDistance_ = boundaryTolerance_*Foam::cbrt
    (
        returnReduce
        (
            mesh_.nCells() ? max(mesh_.cellVolumes()) : 0.0,
            maxOp<scalar>()
        )
    ) + ROOTVSMALL;

    // a quarter of the smallest cell's size
    if (mesh_.nCells())
    {
        margin_ = 0.25*Foam::cbrt(min(mesh_.cellVolumes()));
    }
    // Octree of the cell centres, built once (the fluid mesh never moves)
    const pointField& C = mesh_.cellCentres();
    Random rndGen(1234);
    treeBoundBox bb(C.size() ? treeBoundBox(C) : treeBoundBox(mesh_.points()));
    bb = bb.extend(rndGen, 1e-4);
    bb.min() -= point::uniform(ROOTVSMALL);
    bb.max() += point::uniform(ROOTVSMALL);
    centreTree_.reset
    (
        new indexedOctree<treeDataPoint>(treeDataPoint(C), bb, 10, 10.0, 3.0)
    );
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::immersedPairs::tetWeights Foam::immersedPairs::barycentric
(
    const point& p,
    const point& a,
    const point& b,
    const point& c,
    const point& d
)
{
    const vector ab(b - a), ac(c - a), ad(d - a), ap(p - a);
    const scalar V = (ab ^ ac) & ad;
    tetWeights w;
    w[1] = ((ap ^ ac) & ad)/V;
    w[2] = ((ab ^ ap) & ad)/V;
    w[3] = ((ab ^ ac) & ap)/V;
    w[0] = 1 - w[1] - w[2] - w[3];
    return w;
}


void Foam::immersedPairs::placeOnBoundary
(
    const pointField& x,
    labelList& owner,
    labelList& cells
)
{
    // Nodes on the fluid domain's boundary (a leaflet's attachment on the
    // root wall) can lie just outside the faceted boundary of the fluid mesh
    // (a wall facet's chord, a solid face's edge through the wall): within
    // boundaryTolerance_ of the cube root of its cell's volume of a boundary
    // face (not coupled), such a node takes the cell of its nearest one. The
    // nearest over all ranks wins, the lowest rank on a tie. (owner is the
    // same on every rank: nothing to do, and no communication, when every
    // node is in a cell.)
    nOnBoundary_ = 0;
    maxOutside_ = 0;
    const label none = Pstream::nProcs();
    if (!owner.found(none))
    {
        return;
    }
    const label n = x.size();
    const indexedOctree<treeDataFace>& bTree =
        locator_.search().boundaryTree();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    scalarField dist(n, GREAT);
    labelList nearCell(n, -1);
    forAll(owner, i)
    {
        if (owner[i] != none)
        {
            continue;
        }
        const pointIndexHit h =
            bTree.findNearest(x[i], sqr(maxBoundaryDistance_));
        if (!h.hit())
        {
            continue;
        }
        const label facei = bTree.shapes().faceLabels()[h.index()];
        if (pbm[pbm.whichPatch(facei)].coupled())
        {
            continue;
        }
        const label celli = mesh_.faceOwner()[facei];
        const scalar d = mag(h.hitPoint() - x[i]);
        if (d <= boundaryTolerance_*cbrt(mesh_.cellVolumes()[celli]))
        {
            dist[i] = d;
            nearCell[i] = celli;
        }
    }
    scalarField minDist(dist);
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(minDist, minEqOp<scalar>());
        Pstream::listCombineScatter(minDist);
    }
    labelList nearOwner(n, labelMax);
    forAll(dist, i)
    {
        if (nearCell[i] >= 0 && dist[i] == minDist[i])
        {
            nearOwner[i] = Pstream::myProcNo();
        }
    }
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(nearOwner, minEqOp<label>());
        Pstream::listCombineScatter(nearOwner);
    }
    forAll(owner, i)
    {
        if (owner[i] == none && nearOwner[i] != labelMax)
        {
            owner[i] = nearOwner[i];
            ++nOnBoundary_;
            maxOutside_ = max(maxOutside_, minDist[i]);
            if (nearOwner[i] == Pstream::myProcNo())
            {
                cells[i] = nearCell[i];
                locator_.setHint(i, nearCell[i]);
            }
        }
    }
}


void Foam::immersedPairs::checkImmersed
(
    const pointField& x,
    const labelUList& owner
) const
{
    label nMissing = 0;
    label firstMissing = -1;
    forAll(owner, i)
    {
        if (owner[i] == Pstream::nProcs())
        {
            if (firstMissing < 0)
            {
                firstMissing = i;
            }
            ++nMissing;
        }
    }
    if (nMissing)
    {
        FatalErrorInFunction
            << nMissing << " of " << x.size() << " solid nodes lie outside"
            << " the fluid domain (in no fluid cell); the first is node "
            << firstMissing << " at " << x[firstMissing] << nl
            << "    The solid must stay immersed in the fluid mesh"
            << " (bounding box " << boundBox(mesh_.points(), true) << "),"
            << " a node on its boundary within "
            << boundaryTolerance_ << " of its cell's size (the cube root of"
            << " the volume) of a boundary face" << nl
            << "    Move the solid inside the fluid domain or mesh the fluid"
            << " around it"
            << exit(FatalError);
    }
}


void Foam::immersedPairs::findNodeCells(const pointField& x)
{
    labelList cells;
    labelList owner(locator_.locate(x, cells));
    placeOnBoundary(x, owner, cells);
    checkImmersed(x, owner);
    nodeCell_.transfer(cells);
}


const Foam::indexedOctree<Foam::treeDataCell>&
Foam::immersedPairs::cellBoxTree()
{
    if (!cellBoxTree_.valid())
    {
        treeBoundBox cbb(mesh_.points());
        Random rndGenBox(5678);
        cbb = cbb.extend(rndGenBox, 1e-4);
        cbb.min() -= point::uniform(ROOTVSMALL);
        cbb.max() += point::uniform(ROOTVSMALL);
        cellBoxTree_.reset
        (
            new indexedOctree<treeDataCell>
            (
                treeDataCell(true, mesh_, polyMesh::CELL_TETS),
                cbb,
                8,
                10.0,
                6.0
            )
        );
    }
    return *cellBoxTree_;
}


void Foam::immersedPairs::setCellBoxes()
{
    // Cell boxes and the cells with a coupled face, once
    if (cellBb_.size() == mesh_.nCells())
    {
        return;
    }
    const cellList& cells = mesh_.cells();
    const faceList& faces = mesh_.faces();
    const pointField& P = mesh_.points();
    cellBb_.setSize(mesh_.nCells());
    nearCoupled_.setSize(mesh_.nCells());
    nearCoupled_ = false;
    forAll(cells, celli)
    {
        treeBoundBox bb(P[faces[cells[celli][0]][0]], P[faces[cells[celli][0]][0]]);
        for (const label facei : cells[celli])
        {
            for (const label pointi : faces[facei])
            {
                bb.add(P[pointi]);
            }
            if (!mesh_.isInternalFace(facei))
            {
                const label patchi = mesh_.boundaryMesh().whichPatch(facei);
                if (mesh_.boundaryMesh()[patchi].coupled())
                {
                    nearCoupled_[celli] = true;
                }
            }
        }
        cellBb_[celli] = bb;
    }
    visitedBy_ = labelList(mesh_.nCells(), -1);
}


Foam::labelList Foam::immersedPairs::cellsOverlapping
(
    const pointField& x,
    const tetLabels& t,
    const treeBoundBox& bb
)
{
    // The cells whose box overlaps bb, by a fill over face neighbours
    // from the cells of the element's nodes: the cells that meet bb (an
    // open box) are face-connected and contain the nodes' cells, so the
    // fill reaches every one of them. The octree where a node is not in
    // this rank's cells or the fill meets a coupled face (the rank's part
    // of bb may not be connected).
    const labelListList& cellCells = mesh_.cellCells();
    bool useTree = false;
    DynamicList<label>& found = fillCells_;
    found.clear();
    if (++stamp_ == labelMax)
    {
        visitedBy_ = -1;
        stamp_ = 0;
    }
    const label mark = stamp_;
    for (label k = 0; k < 4 && !useTree; ++k)
    {
        const label c0 = nodeCell_.size() == x.size() ? nodeCell_[t[k]] : -1;
        if (c0 < 0)
        {
            useTree = true;
        }
        else if (visitedBy_[c0] != mark)
        {
            visitedBy_[c0] = mark;
            found.append(c0);
        }
    }
    for (label head = 0; head < found.size() && !useTree; ++head)
    {
        const label celli = found[head];
        if (nearCoupled_[celli])
        {
            useTree = true;
            break;
        }
        for (const label nb : cellCells[celli])
        {
            if (visitedBy_[nb] != mark)
            {
                visitedBy_[nb] = mark;
                if (cellBb_[nb].overlaps(bb))
                {
                    found.append(nb);
                }
            }
        }
    }
    if (useTree)
    {
        return cellBoxTree().findBox(bb);
    }
    return labelList(found);
}


void Foam::immersedPairs::updateCandidates
(
    const pointField& x,
    const List<tetLabels>& elements
)
{
    bool rebuild =
        candidateX_.size() != x.size()
     || candidates_.size() != elements.size();
    if (!rebuild)
    {
        scalar d2 = 0;
        forAll(x, i)
        {
            d2 = max(d2, magSqr(x[i] - candidateX_[i]));
        }
        rebuild = d2 > sqr(margin_);
    }
    if (!rebuild)
    {
        return;
    }

    setCellBoxes();
    candidates_.setSize(elements.size());
    candidateGap_.setSize(elements.size());
    candidateCentreGap_.setSize(elements.size());
    forAll(elements, e)
    {
        const tetLabels& t = elements[e];
        treeBoundBox bb(x[t[0]], x[t[0]]);
        for (label k = 1; k < 4; ++k)
        {
            bb.add(x[t[k]]);
        }
        const scalar grow = margin_ + 1e-9*mag(bb.span()) + ROOTVSMALL;
        bb.min() -= point::uniform(grow);
        bb.max() += point::uniform(grow);
        candidates_[e] = cellsOverlapping(x, t, bb);
        candidateGap_[e].setSize(candidates_[e].size());
        candidateGap_[e] = -1;
        candidateCentreGap_[e].setSize(candidates_[e].size());
        candidateCentreGap_[e] = 0;
    }
    candidateX_ = x;
    ++nCandidateUpdates_;
}


Foam::scalar Foam::immersedPairs::cellSeparation
(
    const FixedList<point, 4>& A,
    const treeBoundBox& bb,
    const label celli
) const
{
    // Separation of two boxes: the largest gap along the coordinate axes
    auto boxGap = [](const treeBoundBox& a, const treeBoundBox& b)
    {
        scalar g = -GREAT;
        for (direction k = 0; k < 3; ++k)
        {
            g = max(g, max(b.min()[k] - a.max()[k], a.min()[k] - b.max()[k]));
        }
        return g;
    };

    const cellList& cells = mesh_.cells();
    const faceList& faces = mesh_.faces();
    const pointField& P = mesh_.points();
    const cell& cFaces = cells[celli];

    // A tetrahedral cell is its own decomposition: one test with its four
    // points
    if (cFaces.size() == 4 && faces[cFaces[0]].size() == 3)
    {
        const face& f0 = faces[cFaces[0]];
        label apex = -1;
        for (const label pointi : faces[cFaces[1]])
        {
            if (!f0.found(pointi))
            {
                apex = pointi;
                break;
            }
        }
        const FixedList<point, 4> B({P[f0[0]], P[f0[1]], P[f0[2]], P[apex]});
        treeBoundBox tb(B[0], B[0]);
        tb.add(B[1]);
        tb.add(B[2]);
        tb.add(B[3]);
        const scalar g = boxGap(bb, tb);
        if (g > 0)
        {
            return g;
        }
        return tetSeparation(A, B);
    }

    // The cell's tets (as polyMeshTetDecomposition::cellTetIndices, without
    // its allocations): apart when every one of them is; the distance is
    // at least the smallest of theirs
    scalar gap = GREAT;
    for (const label facei : cFaces)
    {
        const label nTri = faces[facei].size() - 2;
        for (label tetPti = 1; tetPti <= nTri; ++tetPti)
        {
            const tetPointRef tp(tetIndices(celli, facei, tetPti).tet(mesh_));
            const FixedList<point, 4> B({tp.a(), tp.b(), tp.c(), tp.d()});
            treeBoundBox tb(B[0], B[0]);
            tb.add(B[1]);
            tb.add(B[2]);
            tb.add(B[3]);
            scalar g = boxGap(bb, tb);
            if (g <= 0)
            {
                g = tetSeparation(A, B);
                if (g < 0)
                {
                    return -1;
                }
            }
            gap = min(gap, g);
        }
    }
    return gap;
}


namespace
{
    // The largest of an element's nodes' values m
    inline Foam::scalar largest
    (
        const Foam::scalarField& m,
        const Foam::FixedList<Foam::label, 4>& t
    )
    {
        using Foam::max;
        return max(max(m[t[0]], m[t[1]]), max(m[t[2]], m[t[3]]));
    }

    // A kept gap K (pair apart while the element moves less than K) after
    // a motion me: K - me, or -1 (test it) when the motion may have
    // closed it
    inline Foam::scalar rebased(const Foam::scalar K, const Foam::scalar me)
    {
        return K > me ? K - me : Foam::scalar(-1);
    }

    // An element's bounding box, grown by a relative round-off margin
    Foam::treeBoundBox elementBox(const Foam::FixedList<Foam::point, 4>& A)
    {
        Foam::treeBoundBox bb(A[0], A[0]);
        for (Foam::label k = 1; k < 4; ++k)
        {
            bb.add(A[k]);
        }
        const Foam::scalar tol = 1e-9*Foam::mag(bb.span()) + Foam::ROOTVSMALL;
        bb.min() -= Foam::point::uniform(tol);
        bb.max() += Foam::point::uniform(tol);
        return bb;
    }
}


void Foam::immersedPairs::resetCovered()
{
    // Reset the slots of the last search's cells only
    if (slot_.size() != mesh_.nCells())
    {
        slot_ = labelList(mesh_.nCells(), -1);
    }
    for (const label celli : coveredCells_)
    {
        slot_[celli] = -1;
    }
    coveredCells_.clear();
    coveringElement_.clear();
    weights_.clear();
    centreInside_.clear();
    nPairTests_ = 0;
    nPairsSkipped_ = 0;
}


void Foam::immersedPairs::addCovered
(
    const label celli,
    const label e,
    const tetWeights& w,
    const bool centreInside
)
{
    slot_[celli] = coveredCells_.size();
    coveredCells_.append(celli);
    coveringElement_.append(e);
    weights_.append(w);
    centreInside_.append(centreInside);
}


void Foam::immersedPairs::coverCentres
(
    const pointField& x,
    const label e,
    const tetLabels& t,
    const scalar me
)
{
    // The cell centres inside element e (paper Eq. 50 with the solid's
    // shape functions; the lowest element first, as called in order).
    // Candidates: the cached lists (touching, me: the element's motion
    // since the last search) or the centre octree. Touching: a pair still
    // apart by its kept gap has its centre outside (the centre is inside
    // the cell); so has a pair whose centre was found outside at a
    // distance d (at least the largest -w_i h_i, h_i the height over face
    // i) while the element has moved less than d since
    const point& a = x[t[0]];
    const point& b = x[t[1]];
    const point& c = x[t[2]];
    const point& d = x[t[3]];
    const pointField& C = mesh_.cellCentres();
    const bool touching = (coverage_ == coverageType::touching);

    labelList found;
    const scalar* gap = nullptr;
    scalar* centreGap = nullptr;
    if (touching)
    {
        gap = candidateGap_[e].cdata();
        centreGap = candidateCentreGap_[e].data();
    }
    else
    {
        found = centreTree_->findBox(elementBox({a, b, c, d}));
    }
    // heights over the faces opposite each vertex (when needed)
    FixedList<scalar, 4> h(-1);
    const labelUList& cand = touching ? candidates_[e] : found;
    forAll(cand, k)
    {
        // (the kept gaps first: read in order, the slots are not; the
        // centre distance not tested is rebased to this search)
        if (gap && (me < gap[k] || me < centreGap[k]))
        {
            ++nPairsSkipped_;
            centreGap[k] = rebased(centreGap[k], me);
            continue;
        }
        const label celli = cand[k];
        if (slot_[celli] >= 0)
        {
            if (centreGap)
            {
                centreGap[k] = rebased(centreGap[k], me);
            }
            continue;
        }
        ++nPairTests_;
        const tetWeights w(barycentric(C[celli], a, b, c, d));
        const bool in = insideTet(w);
        if (centreGap && in)
        {
            centreGap[k] = -1;
        }
        if (centreGap && !in)
        {
            if (h[0] < 0)
            {
                const scalar V6 = mag(((b - a) ^ (c - a)) & (d - a));
                h[0] = V6/max(mag((c - b) ^ (d - b)), VSMALL);
                h[1] = V6/max(mag((c - a) ^ (d - a)), VSMALL);
                h[2] = V6/max(mag((b - a) ^ (d - a)), VSMALL);
                h[3] = V6/max(mag((b - a) ^ (c - a)), VSMALL);
            }
            scalar dist = 0;
            for (label i = 0; i < 4; ++i)
            {
                dist = max(dist, -w[i]*h[i]);
            }
            // from this search, with a round-off margin
            centreGap[k] = (1 - 1e-9)*dist;
        }
        if (in)
        {
            addCovered(celli, e, w, true);
        }
    }
}


void Foam::immersedPairs::coverTouched
(
    const pointField& x,
    const label e,
    const tetLabels& t,
    const scalar me,
    const scalar meLists
)
{
    // The cells element e touches: a tet of the cell's CELL_TETS
    // decomposition (the one of the inside test) and the element intersect
    // (closed sets: touching counts), by separating axes (cellSeparation;
    // the gap found is kept). Candidates: the cells whose bounding box
    // overlaps the element's. Weights: the barycentric coordinates of the
    // cell centre clamped to the element. me, meLists: the element's
    // motion since the last search and since the lists were built
    const pointField& C = mesh_.cellCentres();
    const FixedList<point, 4> A({x[t[0]], x[t[1]], x[t[2]], x[t[3]]});
    const treeBoundBox bb(elementBox(A));

    // The pairs kept for the next searches are written back in place: a
    // pair whose gap exceeds margin_ cannot touch before the lists are
    // rebuilt (a node moving by more than margin_ rebuilds them) and is
    // dropped
    labelList& cand = candidates_[e];
    scalarList& gap = candidateGap_[e];
    scalarList& centreGap = candidateCentreGap_[e];
    label nKept = 0;
    // (written only where something changes: most pairs stay as they
    // are, and the write-back of unchanged lists costs memory traffic)
    auto keep = [&](const label k, const scalar g)
    {
        if (nKept != k)
        {
            cand[nKept] = cand[k];
            centreGap[nKept] = centreGap[k];
            gap[nKept] = g;
        }
        else if (gap[k] != g)
        {
            gap[k] = g;
        }
        ++nKept;
    };
    forAll(cand, k)
    {
        if (me < gap[k])
        {
            ++nPairsSkipped_;
            keep(k, gap[k] - me);
            continue;
        }
        const label celli = cand[k];
        if (slot_[celli] >= 0)
        {
            // covered already: not tested, may touch
            nearPairs_.append(labelPair(slot_[celli], e));
            keep(k, -1);
            continue;
        }
        ++nPairTests_;
        const scalar g = cellSeparation(A, bb, celli);
        if (g >= 0)
        {
            // apart: kept from this search, with a relative margin for the
            // round-off; dropped when the element cannot reach the cell
            // before the lists are rebuilt (every node then stays within
            // margin_ of candidateX_, so the element moves less than
            // margin_ + meLists from here)
            const scalar kept = (1 - 1e-9)*g;
            if (kept - meLists <= margin_)
            {
                keep(k, kept);
            }
            continue;
        }
        keep(k, -1);

        tetWeights w(barycentric(C[celli], A[0], A[1], A[2], A[3]));
        scalar sum = 0;
        for (scalar& wi : w)
        {
            wi = max(wi, scalar(0));
            sum += wi;
        }
        for (scalar& wi : w)
        {
            wi /= sum;
        }
        nearPairs_.append(labelPair(coveredCells_.size(), e));
        addCovered(celli, e, w, false);
    }
    if (nKept < cand.size())
    {
        cand.setSize(nKept);
        gap.setSize(nKept);
        centreGap.setSize(nKept);
    }
}


void Foam::immersedPairs::groupNearElements()
{
    // The elements that may touch each covered cell, by cell (the pairs
    // of a cell are those not skipped: the kept gap is a lower bound of
    // the distance, so a skipped pair is apart)
    labelList nNear(coveredCells_.size(), 0);
    for (const labelPair& p : nearPairs_)
    {
        ++nNear[p.first()];
    }
    nearElements_.setSize(nNear);
    const labelList& offsets = nearElements_.offsets();
    labelList& near = nearElements_.m();
    nNear = 0;
    for (const labelPair& p : nearPairs_)
    {
        near[offsets[p.first()] + nNear[p.first()]++] = p.second();
    }
}


void Foam::immersedPairs::findCoveredCells
(
    const pointField& x,
    const List<tetLabels>& elements
)
{
    resetCovered();
    if (coverage_ != coverageType::touching)
    {
        forAll(elements, e)
        {
            coverCentres(x, e, elements[e], 0);
        }
        nearElements_.setSize(0);
        return;
    }

    // Touching: each node's motion since the last search (the kept gaps
    // are relative to it) and since the candidate lists were built; an
    // element's is the largest of its nodes'
    const clockValue start(true);
    updateCandidates(x, elements);
    if (debug)
    {
        Info<< "immersedPairs: candidate lists " << start.elapsed()
            << " s" << endl;
    }
    if (lastX_.size() != x.size())
    {
        lastX_ = x;
    }
    scalarField moved(x.size());
    scalarField movedSinceLists(x.size());
    forAll(x, i)
    {
        moved[i] = mag(x[i] - lastX_[i]);
        movedSinceLists[i] = mag(x[i] - candidateX_[i]);
    }

    forAll(elements, e)
    {
        coverCentres(x, e, elements[e], largest(moved, elements[e]));
    }

    nearPairs_.clear();
    const clockValue touchStart(true);
    forAll(elements, e)
    {
        const tetLabels& t = elements[e];
        coverTouched
        (
            x, e, t, largest(moved, t), largest(movedSinceLists, t)
        );
    }
    const double touchTime = touchStart.elapsed();

    // (the kept gaps are now relative to these positions)
    lastX_ = x;
    const clockValue nearStart(true);
    groupNearElements();
    if (debug)
    {
        Info<< "immersedPairs: elements that may touch the covered cells "
            << returnReduce(nearPairs_.size(), sumOp<label>())
            << ", touching pass " << touchTime << " s, by cell "
            << nearStart.elapsed() << " s" << endl;
    }
}


Foam::scalar Foam::immersedPairs::tetSeparation
(
    const FixedList<point, 4>& A,
    const FixedList<point, 4>& B
)
{
    static const label edges[6][2] =
        {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    static const label faces[4][3] =
        {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

    scalar scale = 0;
    for (label i = 0; i < 6; ++i)
    {
        scale = max(scale, magSqr(A[edges[i][1]] - A[edges[i][0]]));
        scale = max(scale, magSqr(B[edges[i][1]] - B[edges[i][0]]));
    }

    // Gap along n (> 0: the projections do not overlap, strictly), scaled
    // to a unit axis; 0 for no axis (parallel edges) or overlap
    auto gapAlong = [&](const vector& n)
    {
        const scalar n2 = magSqr(n);
        if (n2 <= 1e-24*sqr(scale))
        {
            return scalar(0);   // parallel edges: no axis
        }
        scalar minA = GREAT, maxA = -GREAT, minB = GREAT, maxB = -GREAT;
        for (label k = 0; k < 4; ++k)
        {
            const scalar a = n & A[k];
            const scalar b = n & B[k];
            minA = min(minA, a);
            maxA = max(maxA, a);
            minB = min(minB, b);
            maxB = max(maxB, b);
        }
        const scalar g = max(minB - maxA, minA - maxB);
        return g > 0 ? g/Foam::sqrt(n2) : scalar(0);
    };

    for (label f = 0; f < 4; ++f)
    {
        const label* v = faces[f];
        scalar g = gapAlong((A[v[1]] - A[v[0]]) ^ (A[v[2]] - A[v[0]]));
        if (g > 0)
        {
            return g;
        }
        g = gapAlong((B[v[1]] - B[v[0]]) ^ (B[v[2]] - B[v[0]]));
        if (g > 0)
        {
            return g;
        }
    }
    for (label i = 0; i < 6; ++i)
    {
        const vector ea(A[edges[i][1]] - A[edges[i][0]]);
        for (label j = 0; j < 6; ++j)
        {
            const vector eb(B[edges[j][1]] - B[edges[j][0]]);
            const scalar g = gapAlong(ea ^ eb);
            if (g > 0)
            {
                return g;
            }
        }
    }
    return -1;
}


// ************************************************************************* //
