/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedPairs.H"
#include "Random.H"
#include "PstreamReduceOps.H"
#include "Tuple2.H"
#include "processorPolyPatch.H"
#include "treeDataCell.H"
#include "polyMeshTetDecomposition.H"


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
    search_(mesh, polyMesh::CELL_TETS),
    centreTree_(),
    cellBoxTree_(),
    coverage_
    (
        coverageTypeNames.getOrDefault("coverage", dict, coverageType::centre)
    ),

    maxWalk_(dict.getOrDefault<label>("maxWalk", 100)),
    nodeCell_(),
    nSteps_(0),
    nWalks_(0),
    nFallback_(0),
    nLeft_(0),
    candidates_(),
    candidateX_(),
    margin_(0),
    nCandidateUpdates_(0)
{
    // a quarter of the smallest cell's size
    if (mesh_.nCells())
    {
        margin_ = 0.25*Foam::cbrt(min(mesh_.cellVolumes()));
    }
    // The cell bounding-box octree of the touching coverage (cached
    // boxes), built once
    if (coverage_ == coverageType::touching)
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

    // Cell-face addressing once (the walk uses it)
    mesh_.cells();
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::label Foam::immersedPairs::walk
(
    const point& p,
    const label start,
    label& steps
) const
{
    const vectorField& Cf = mesh_.faceCentres();
    const vectorField& Sf = mesh_.faceAreas();
    const vectorField& C = mesh_.cellCentres();
    const labelList& own = mesh_.faceOwner();
    const labelList& nei = mesh_.faceNeighbour();
    const cellList& cells = mesh_.cells();

    label c = start;
    for (label k = 0; k <= maxWalk_; ++k)
    {
        if (inside(p, c))
        {
            return c;
        }

        // The face the point is most outside of, relative to the cell
        // centre's distance to the face plane (Eq. 51 on tets)
        scalar best = 0;
        label bestFace = -1;
        for (const label facei : cells[c])
        {
            const vector n(own[facei] == c ? Sf[facei] : -Sf[facei]);
            const scalar dc = (Cf[facei] - C[c]) & n;
            const scalar o = ((p - Cf[facei]) & n)/max(dc, VSMALL);
            if (o > best)
            {
                best = o;
                bestFace = facei;
            }
        }
        if (bestFace >= 0 && !mesh_.isInternalFace(bestFace))
        {
            const label patchi =
                mesh_.boundaryMesh().whichPatch(bestFace);
            if (isA<processorPolyPatch>(mesh_.boundaryMesh()[patchi]))
            {
                // Most likely on the neighbouring rank
                return -2;
            }
        }
        if (bestFace < 0 || !mesh_.isInternalFace(bestFace))
        {
            // No face plane separates the point (a non-convex cell or
            // warped faces, e.g. polyDualMesh) or the best face is on the
            // boundary: test the face neighbours, most-outside face first
            const cell& cFaces = cells[c];
            List<Tuple2<scalar, label>> order(cFaces.size());
            forAll(cFaces, i)
            {
                const label facei = cFaces[i];
                const vector n(own[facei] == c ? Sf[facei] : -Sf[facei]);
                const scalar dc = (Cf[facei] - C[c]) & n;
                order[i] = Tuple2<scalar, label>
                (
                    -((p - Cf[facei]) & n)/max(dc, VSMALL),
                    facei
                );
            }
            Foam::sort(order);
            for (const Tuple2<scalar, label>& o : order)
            {
                const label facei = o.second();
                if (mesh_.isInternalFace(facei))
                {
                    const label nb =
                        (own[facei] == c ? nei[facei] : own[facei]);
                    if (inside(p, nb))
                    {
                        ++steps;
                        return nb;
                    }
                }
            }
            return -1;
        }
        c = (own[bestFace] == c ? nei[bestFace] : own[bestFace]);
        ++steps;
    }
    return -1;
}


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


void Foam::immersedPairs::findNodeCells(const pointField& x)
{
    const label n = x.size();
    if (nodeCell_.size() != n)
    {
        nodeCell_ = labelList(n, -1);
    }
    nSteps_ = 0;
    nWalks_ = 0;
    nFallback_ = 0;
    nLeft_ = 0;

    labelList cells(n, -1);
    forAll(x, i)
    {
        label c = -1;
        if (nodeCell_[i] >= 0)
        {
            ++nWalks_;
            c = walk(x[i], nodeCell_[i], nSteps_);
            if (c == -2)
            {
                ++nLeft_;
            }
            else if (c < 0)
            {
                ++nFallback_;
            }
        }
        if (c < 0)
        {
            c = search_.findCell(x[i], -1, true);
        }
        cells[i] = c;
    }

    // Each node to one rank: the lowest of those whose cells contain it
    labelList owner(n, labelMax);
    forAll(cells, i)
    {
        if (cells[i] >= 0)
        {
            owner[i] = Pstream::myProcNo();
        }
    }
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(owner, minEqOp<label>());
        Pstream::listCombineScatter(owner);
        forAll(cells, i)
        {
            if (owner[i] != Pstream::myProcNo())
            {
                cells[i] = -1;
            }
        }
    }

    label nMissing = 0;
    label firstMissing = -1;
    forAll(owner, i)
    {
        if (owner[i] == labelMax)
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
            << nMissing << " of " << n << " solid nodes lie outside the fluid"
            << " domain (in no fluid cell); the first is node "
            << firstMissing << " at " << x[firstMissing] << nl
            << "    The solid must stay immersed in the fluid mesh"
            << " (bounding box " << boundBox(mesh_.points(), true) << ")"
            << exit(FatalError);
    }

    nodeCell_.transfer(cells);
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

    const indexedOctree<treeDataCell>& cellTree = *cellBoxTree_;
    candidates_.setSize(elements.size());
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
        candidates_[e] = cellTree.findBox(bb);
    }
    candidateX_ = x;
    ++nCandidateUpdates_;
}


void Foam::immersedPairs::findCoveredCells
(
    const pointField& x,
    const List<tetLabels>& elements
)
{
    coveredCells_.clear();
    coveringElement_.clear();
    weights_.clear();
    centreInside_.clear();

    const pointField& C = mesh_.cellCentres();

    // Index into the lists of each covered cell
    labelList slot(mesh_.nCells(), -1);

    const bool touching = (coverage_ == coverageType::touching);
    if (touching)
    {
        updateCandidates(x, elements);
    }

    // Cell centres inside the elements (paper Eq. 50 with the solid's
    // shape functions), the lowest element first; candidates: the cached
    // lists (touching) or the centre octree
    forAll(elements, e)
    {
        const tetLabels& t = elements[e];
        const point& a = x[t[0]];
        const point& b = x[t[1]];
        const point& c = x[t[2]];
        const point& d = x[t[3]];

        labelList found;
        if (!touching)
        {
            treeBoundBox bb(a, a);
            bb.add(b);
            bb.add(c);
            bb.add(d);
            const scalar tol = 1e-9*mag(bb.span()) + ROOTVSMALL;
            bb.min() -= point::uniform(tol);
            bb.max() += point::uniform(tol);
            found = centreTree_->findBox(bb);
        }
        const labelUList& cand = touching ? candidates_[e] : found;
        for (const label celli : cand)
        {
            if (slot[celli] >= 0)
            {
                continue;
            }
            const tetWeights w(barycentric(C[celli], a, b, c, d));
            if (insideTet(w))
            {
                slot[celli] = coveredCells_.size();
                coveredCells_.append(celli);
                coveringElement_.append(e);
                weights_.append(w);
                centreInside_.append(true);
            }
        }
    }

    if (coverage_ != coverageType::touching)
    {
        return;
    }

    // Cells touched by the elements: a tet of the cell's CELL_TETS
    // decomposition (the one of the inside test) and the element intersect
    // (closed sets: touching counts), by separating axes. Candidates: the
    // cells whose bounding box overlaps the element's. Weights: the
    // barycentric coordinates of the cell centre clamped to the element.
    const cellList& cells = mesh_.cells();
    const faceList& faces = mesh_.faces();
    forAll(elements, e)
    {
        const tetLabels& t = elements[e];
        const FixedList<point, 4> A({x[t[0]], x[t[1]], x[t[2]], x[t[3]]});

        treeBoundBox bb(A[0], A[0]);
        for (label k = 1; k < 4; ++k)
        {
            bb.add(A[k]);
        }
        const scalar tol = 1e-9*mag(bb.span()) + ROOTVSMALL;
        bb.min() -= point::uniform(tol);
        bb.max() += point::uniform(tol);

        for (const label celli : candidates_[e])
        {
            if (slot[celli] >= 0)
            {
                continue;
            }
            // The cell's tets (as polyMeshTetDecomposition::cellTetIndices,
            // without its allocations); a bounding-box check before the
            // separating axes. A tetrahedral cell is its own decomposition:
            // one test with its four points
            bool hit = false;
            const cell& cFaces = cells[celli];
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
                const pointField& P = mesh_.points();
                const FixedList<point, 4> B
                    ({P[f0[0]], P[f0[1]], P[f0[2]], P[apex]});
                hit = tetsIntersect(A, B);
                if (!hit)
                {
                    continue;
                }
            }
            for (const label facei : cFaces)
            {
                const label nTri = faces[facei].size() - 2;
                for (label tetPti = 1; tetPti <= nTri && !hit; ++tetPti)
                {
                    const tetPointRef tp
                    (
                        tetIndices(celli, facei, tetPti).tet(mesh_)
                    );
                    const FixedList<point, 4> B
                        ({tp.a(), tp.b(), tp.c(), tp.d()});
                    treeBoundBox tb(B[0], B[0]);
                    tb.add(B[1]);
                    tb.add(B[2]);
                    tb.add(B[3]);
                    hit = tb.overlaps(bb) && tetsIntersect(A, B);
                }
                if (hit)
                {
                    break;
                }
            }
            if (!hit)
            {
                continue;
            }

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
            slot[celli] = coveredCells_.size();
            coveredCells_.append(celli);
            coveringElement_.append(e);
            weights_.append(w);
            centreInside_.append(false);
        }
    }
}


bool Foam::immersedPairs::tetsIntersect
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

    // Separated along n: the projections do not overlap (strictly)
    auto separated = [&](const vector& n)
    {
        if (magSqr(n) <= 1e-24*sqr(scale))
        {
            return false;   // parallel edges: no axis
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
        return maxA < minB || maxB < minA;
    };

    for (label f = 0; f < 4; ++f)
    {
        const label* v = faces[f];
        if (separated((A[v[1]] - A[v[0]]) ^ (A[v[2]] - A[v[0]])))
        {
            return false;
        }
        if (separated((B[v[1]] - B[v[0]]) ^ (B[v[2]] - B[v[0]])))
        {
            return false;
        }
    }
    for (label i = 0; i < 6; ++i)
    {
        const vector ea(A[edges[i][1]] - A[edges[i][0]]);
        for (label j = 0; j < 6; ++j)
        {
            const vector eb(B[edges[j][1]] - B[edges[j][0]]);
            if (separated(ea ^ eb))
            {
                return false;
            }
        }
    }
    return true;
}


// ************************************************************************* //
