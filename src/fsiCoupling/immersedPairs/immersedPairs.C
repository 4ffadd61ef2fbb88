/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedPairs.H"
#include "Random.H"
#include "PstreamReduceOps.H"
#include "Tuple2.H"
#include "processorPolyPatch.H"

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
    coverage_
    (
        coverageTypeNames.getOrDefault("coverage", dict, coverageType::centre)
    ),
    samples_(dict.getOrDefault<label>("samples", 2)),
    maxWalk_(dict.getOrDefault<label>("maxWalk", 100)),
    nodeCell_(),
    nSteps_(0),
    nWalks_(0),
    nFallback_(0),
    nLeft_(0)
{
    if (samples_ < 1)
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'samples' in " << dict.name() << " must be >= 1"
            << exit(FatalIOError);
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

    // Cell centres inside the elements (paper Eq. 50 with the solid's
    // shape functions), the lowest element first
    forAll(elements, e)
    {
        const tetLabels& t = elements[e];
        const point& a = x[t[0]];
        const point& b = x[t[1]];
        const point& c = x[t[2]];
        const point& d = x[t[3]];

        treeBoundBox bb(a, a);
        bb.add(b);
        bb.add(c);
        bb.add(d);
        const scalar tol = 1e-9*mag(bb.span()) + ROOTVSMALL;
        bb.min() -= point::uniform(tol);
        bb.max() += point::uniform(tol);

        const labelList cand(centreTree_->findBox(bb));
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

    // Cells touched by the elements: those containing a lattice point
    // (m = samples_ intervals per edge, nodes included) of an element.
    // The weights: barycentric coordinates of the cell centre clamped to
    // the element.
    const label m = samples_;
    label dummySteps = 0;
    forAll(elements, e)
    {
        const tetLabels& t = elements[e];
        label seed = -1;
        if (nodeCell_.size() == x.size())
        {
            seed = nodeCell_[t[0]];
        }

        for (label i = 0; i <= m; ++i)
        {
            for (label j = 0; i + j <= m; ++j)
            {
                for (label k = 0; i + j + k <= m; ++k)
                {
                    const label l = m - i - j - k;
                    const point p
                    (
                        (i*x[t[0]] + j*x[t[1]] + k*x[t[2]] + l*x[t[3]])
                       /scalar(m)
                    );
                    label celli = -1;
                    if (seed >= 0)
                    {
                        celli = max(walk(p, seed, dummySteps), label(-1));
                    }
                    if (celli < 0)
                    {
                        celli = search_.findCell(p, -1, true);
                    }
                    if (celli < 0 || slot[celli] >= 0)
                    {
                        continue;
                    }
                    seed = celli;

                    tetWeights w
                    (
                        barycentric
                        (
                            C[celli], x[t[0]], x[t[1]], x[t[2]], x[t[3]]
                        )
                    );
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
    }
}


// ************************************************************************* //
