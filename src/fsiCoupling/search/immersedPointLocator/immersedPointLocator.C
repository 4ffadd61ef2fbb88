/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedPointLocator.H"
#include "PstreamReduceOps.H"
#include "Tuple2.H"
#include "processorPolyPatch.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedPointLocator::immersedPointLocator
(
    const polyMesh& mesh,
    const label maxWalk
)
:
    mesh_(mesh),
    search_(mesh, polyMesh::CELL_TETS),
    bounds_(),
    maxWalk_(maxWalk),
    hint_(),
    walkFromHint_(),
    nSteps_(0),
    nWalks_(0),
    nFallback_(0),
    nLeft_(0)
{
    if (mesh_.nCells())
    {
        bounds_ = boundBox(mesh_.points(), false);
        bounds_.inflate(0.01);
    }
    // Cell-face addressing once (the walk uses it)
    mesh_.cells();
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::label Foam::immersedPointLocator::treeSearch(const point& p) const
{
    if (!mesh_.nCells() || !bounds_.contains(p))
    {
        return -1;
    }
    return search_.findCell(p, -1, true);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::label Foam::immersedPointLocator::walk
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


Foam::labelList Foam::immersedPointLocator::locate
(
    const pointField& x,
    labelList& cells,
    const boolUList& active
)
{
    const label n = x.size();
    const label me = Pstream::myProcNo();
    const label none = Pstream::nProcs();
    if (hint_.size() != n)
    {
        hint_ = labelList(n, -1);
        walkFromHint_ = boolList(n, false);
    }
    nSteps_ = 0;
    nWalks_ = 0;
    nFallback_ = 0;
    nLeft_ = 0;

    // 1. A walk from the point's cell of the last search where this rank
    //    held it: it finds nearly every point (a point moves less than a
    //    cell per step)
    cells = labelList(n, -1);
    labelList rank(n, none);
    forAll(x, i)
    {
        if (active.size() && !active[i])
        {
            rank[i] = -1;
            continue;
        }
        if (!walkFromHint_[i])
        {
            continue;
        }
        ++nWalks_;
        const label c = walk(x[i], hint_[i], nSteps_);
        if (c >= 0)
        {
            cells[i] = c;
            rank[i] = me;
        }
        else if (c == -2)
        {
            ++nLeft_;
        }
        else
        {
            ++nFallback_;
        }
    }
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(rank, minEqOp<label>());
        Pstream::listCombineScatter(rank);
    }

    // 2. The octree on every rank for the points no rank's walk found (the
    //    same list on every rank)
    if (rank.found(none))
    {
        forAll(x, i)
        {
            if (rank[i] == none)
            {
                const label c = treeSearch(x[i]);
                if (c >= 0)
                {
                    cells[i] = c;
                    rank[i] = me;
                }
            }
        }
        if (Pstream::parRun())
        {
            Pstream::listCombineGather(rank, minEqOp<label>());
            Pstream::listCombineScatter(rank);
        }
    }

    // 3. Each point to the lowest rank holding it
    forAll(x, i)
    {
        if (cells[i] >= 0)
        {
            hint_[i] = cells[i];
        }
        walkFromHint_[i] = (rank[i] == me && cells[i] >= 0);
        if (rank[i] != me)
        {
            cells[i] = -1;
        }
    }
    return rank;
}


// ************************************************************************* //
