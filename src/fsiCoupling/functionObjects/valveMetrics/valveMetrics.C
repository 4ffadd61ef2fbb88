/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "valveMetrics.H"
#include "processorPolyPatch.H"
#include "immersedMethod.H"
#include "immersedSolid.H"
#include "deformableSolid.H"
#include "fvOptions.H"
#include "volFields.H"
#include "surfaceFields.H"
#include "triSurfaceTools.H"
#include "mergePoints.H"
#include "clockTime.H"
#include "nullObject.H"
#include "vector2D.H"
#include "addToRunTimeSelectionTable.H"

#include "dynamics/ExplicitSolid.hpp"

#include <Eigen/Eigenvalues>
#include <vector>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(valveMetrics, 0);
    addToRunTimeSelectionTable(functionObject, valveMetrics, dictionary);
}
}


namespace
{

//- Pa per mmHg (the project's constant: tutorials/aorticValve/0.orig/p)
const Foam::scalar paPerMmHg = 133.322;

//- Union-find root with path halving
Foam::label root(Foam::labelList& parent, Foam::label i)
{
    while (parent[i] != i)
    {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

const Foam::immersedSolid&
Foam::functionObjects::valveMetrics::findSolid(const dictionary& dict) const
{
    const fv::optionList& opts = fv::options::New(mesh_);
    wordList names(opts.size());
    forAll(opts, i)
    {
        const fv::option& opt = opts[i];
        names[i] = opt.name();
        if (optionName_.size() && opt.name() != optionName_)
        {
            continue;
        }
        const fv::immersedMethod* m =
            dynamic_cast<const fv::immersedMethod*>(&opt);
        if (m)
        {
            return m->solid();
        }
    }
    FatalIOErrorInFunction(dict)
        << "function object " << name() << " (type " << typeName
        << ") in " << dict.name() << ": no immersed solid (an fvOption of"
        << " type immersedElasticForce or immersedForcing)";
    if (optionName_.size())
    {
        FatalIOError<< " named " << optionName_ << " (entry fvOption)";
    }
    FatalIOError
        << " among the case's fvOptions " << names
        << ": the valve metrics need the immersed solid"
        << exit(FatalIOError);
    return NullObjectRef<immersedSolid>();
}


Foam::label Foam::functionObjects::valveMetrics::patch
(
    const dictionary& dict,
    const word& key,
    const word& def
) const
{
    const word patchName(dict.getOrDefault<word>(key, def));
    const label patchi = mesh_.boundaryMesh().findPatchID(patchName);
    if (patchi < 0)
    {
        FatalIOErrorInFunction(dict)
            << "function object " << name() << " in " << dict.name()
            << ": entry " << key << ": no patch " << patchName
            << " in the mesh; patches: " << mesh_.boundaryMesh().names()
            << exit(FatalIOError);
    }
    return patchi;
}


void Foam::functionObjects::valveMetrics::setDiscCells()
{
    const vectorField& C = mesh_.C();
    DynamicList<label> cells;
    DynamicList<scalar> axial;
    forAll(C, celli)
    {
        const vector d(C[celli] - origin_);
        const scalar s = d & axis_;
        if (magSqr(d - s*axis_) < sqr(radius_))
        {
            cells.append(celli);
            axial.append(s);
        }
    }
    discCells_.transfer(cells);
    discCellAxial_.transfer(axial);
}


void Foam::functionObjects::valveMetrics::setParts(const immersedSolid& s)
{
    const List<solidTet>& tets = s.elements();
    const label n = s.nPoints();

    // parts: nodes connected through elements (union-find)
    labelList parent(identity(n));
    for (const solidTet& t : tets)
    {
        const label r0 = root(parent, t[0]);
        for (label k = 1; k < 4; ++k)
        {
            const label rk = root(parent, t[k]);
            if (rk != r0)
            {
                parent[rk] = r0;
            }
        }
    }
    boolList used(n, false);
    for (const solidTet& t : tets)
    {
        for (const label i : t)
        {
            used[i] = true;
        }
    }
    labelList partOfRoot(n, -1);
    nodePart_.setSize(n);
    nodePart_ = -1;
    nParts_ = 0;
    for (label i = 0; i < n; ++i)
    {
        if (!used[i])
        {
            continue;   // in no element: in no part
        }
        const label r = root(parent, i);
        if (partOfRoot[r] < 0)
        {
            partOfRoot[r] = nParts_++;
        }
        nodePart_[i] = partOfRoot[r];
    }
}


void Foam::functionObjects::valveMetrics::setSurfaces(const immersedSolid& s)
{
    // the surface on node labels
    List<labelledTri> tris;
    labelList surfacePoints;
    CompactListList<label> elementTriangles;
    s.surface(tris, surfacePoints, elementTriangles);
    surfaceNodes_ = surfacePoints;
    surfaceTriangles_.setSize(tris.size());
    forAll(tris, triI)
    {
        const labelledTri& t = tris[triI];
        surfaceTriangles_[triI] = labelledTri
        (
            surfacePoints[t[0]],
            surfacePoints[t[1]],
            surfacePoints[t[2]],
            0
        );
    }

    // each part's surface, compact numbering
    List<DynamicList<labelledTri>> partTris(nParts_);
    List<DynamicList<label>> partPts(nParts_);
    labelList local(s.nPoints(), -1);
    for (const labelledTri& t : surfaceTriangles_)
    {
        const label parti = nodePart_[t[0]];
        labelledTri lt(t);
        for (label k = 0; k < 3; ++k)
        {
            if (local[t[k]] < 0)
            {
                local[t[k]] = partPts[parti].size();
                partPts[parti].append(t[k]);
            }
            lt[k] = local[t[k]];
        }
        partTris[parti].append(lt);
    }
    partPoints_.setSize(nParts_);
    partSurfaces_.clear();
    partSurfaces_.setSize(nParts_);
    forAll(partTris, parti)
    {
        partPoints_[parti].transfer(partPts[parti]);
        partSurfaces_.set
        (
            parti,
            new triSurface
            (
                partTris[parti],
                pointField
                (
                    UIndirectList<point>(s.points0(), partPoints_[parti])
                )
            )
        );
    }
}


void Foam::functionObjects::valveMetrics::setPartDepths
(
    const immersedSolid& s
)
{
    // each node's fewest edges to the surface (breadth-first from the
    // surface nodes), and per part the largest over its elements of the
    // fewest of their nodes' (partDepthBound)
    const List<solidTet>& tets = s.elements();
    labelListList neighbours(s.nPoints());
    {
        List<DynamicList<label>> nbr(s.nPoints());
        for (const solidTet& t : tets)
        {
            for (label a = 0; a < 4; ++a)
            {
                for (label b = 0; b < 4; ++b)
                {
                    if (a != b && !nbr[t[a]].found(t[b]))
                    {
                        nbr[t[a]].append(t[b]);
                    }
                }
            }
        }
        forAll(nbr, i)
        {
            neighbours[i].transfer(nbr[i]);
        }
    }
    labelList edges(s.nPoints(), -1);
    DynamicList<label> front(surfaceNodes_);
    for (const label i : surfaceNodes_)
    {
        edges[i] = 0;
    }
    while (front.size())
    {
        DynamicList<label> next;
        for (const label i : front)
        {
            for (const label j : neighbours[i])
            {
                if (edges[j] < 0)
                {
                    edges[j] = edges[i] + 1;
                    next.append(j);
                }
            }
        }
        front.transfer(next);
    }
    partDepthEdges_.setSize(nParts_);
    partDepthEdges_ = 0;
    for (const solidTet& t : tets)
    {
        label fewest = labelMax;
        for (const label i : t)
        {
            fewest = min(fewest, edges[i]);
        }
        const label parti = nodePart_[t[0]];
        partDepthEdges_[parti] = max(partDepthEdges_[parti], fewest);
    }
}


void Foam::functionObjects::valveMetrics::setSolid(const immersedSolid& s)
{
    setParts(s);
    setSurfaces(s);
    setPartDepths(s);

    // tributary areas of the reference surface (PenaltyContact: a third
    // of each boundary triangle's area to each of its nodes)
    const pointField& X = s.points0();
    contactArea_.setSize(s.nPoints());
    contactArea_ = 0;
    for (const labelledTri& t : surfaceTriangles_)
    {
        const scalar A = t.mag(X);
        for (label k = 0; k < 3; ++k)
        {
            contactArea_[t[k]] += A/3;
        }
    }

    solidReady_ = true;

    if (Pstream::master())
    {
        Info<< type() << ' ' << name() << ": the solid has " << nParts_
            << " connected parts (leaflets), " << surfaceTriangles_.size()
            << " surface triangles on " << surfaceNodes_.size()
            << " nodes; node sets " << s.nodeSetNames() << endl;
    }
}


Foam::autoPtr<Foam::triSurface>
Foam::functionObjects::valveMetrics::gatherPatches
(
    const labelList& patches
) const
{
    // local triangles (fan triangulation keeps the outward orientation)
    List<pointField> allPoints(Pstream::nProcs());
    List<List<labelledTri>> allTris(Pstream::nProcs());
    {
        DynamicList<point> points;
        DynamicList<labelledTri> tris;
        for (const label patchi : patches)
        {
            const polyPatch& pp = mesh_.boundaryMesh()[patchi];
            const label start = points.size();
            points.append(pp.localPoints());
            for (const face& f : pp.localFaces())
            {
                for (label k = 1; k < f.size() - 1; ++k)
                {
                    tris.append
                    (
                        labelledTri
                        (
                            start + f[0], start + f[k], start + f[k + 1], 0
                        )
                    );
                }
            }
        }
        allPoints[Pstream::myProcNo()].transfer(points);
        allTris[Pstream::myProcNo()].transfer(tris);
    }
    Pstream::gatherList(allPoints);
    Pstream::gatherList(allTris);

    if (!Pstream::master())
    {
        return autoPtr<triSurface>::New();
    }

    label nPoints = 0;
    label nTris = 0;
    forAll(allPoints, proci)
    {
        nPoints += allPoints[proci].size();
        nTris += allTris[proci].size();
    }
    pointField points(nPoints);
    List<labelledTri> faces(nTris);
    nPoints = 0;
    nTris = 0;
    forAll(allPoints, proci)
    {
        forAll(allPoints[proci], i)
        {
            points[nPoints + i] = allPoints[proci][i];
        }
        for (const labelledTri& t : allTris[proci])
        {
            faces[nTris++] = labelledTri
            (
                t[0] + nPoints, t[1] + nPoints, t[2] + nPoints, 0
            );
        }
        nPoints += allPoints[proci].size();
    }

    // the points that patches and ranks share (copies of the same mesh
    // points)
    if (points.size())
    {
        labelList pointMap;
        pointField merged;
        const boundBox bb(points, false);
        mergePoints(points, 1e-9*bb.mag(), false, pointMap, merged);
        for (labelledTri& t : faces)
        {
            for (label k = 0; k < 3; ++k)
            {
                t[k] = pointMap[t[k]];
            }
        }
        points.transfer(merged);
    }

    return autoPtr<triSurface>::New(faces, points);
}


void Foam::functionObjects::valveMetrics::setWall()
{
    wall_ = gatherPatches(labelList(one(), wallPatch_));
    wallSearch_.reset(new triSurfaceSearch(wall_()));

    // the fluid domain's boundary, closed: every patch but the processor
    // patches (the ranks' boundaries)
    DynamicList<label> patches;
    forAll(mesh_.boundaryMesh(), patchi)
    {
        if (!isA<processorPolyPatch>(mesh_.boundaryMesh()[patchi]))
        {
            patches.append(patchi);
        }
    }
    domain_ = gatherPatches(patches);
    domainSearch_.reset(new triSurfaceSearch(domain_()));
}


Foam::scalar Foam::functionObjects::valveMetrics::orificeArea
(
    const pointField& x
) const
{
    // metrics.py orifice_area: cell centres (i + 1/2) h - r_c of an n x n
    // raster of [-r_c, r_c]^2 in the plane (e1, e2) through the origin
    const label n = resolution_;
    const scalar h = 2*radius_/n;
    std::vector<char> covered(n*n, 0);

    // the cells whose centres lie in [lo, hi]
    auto first = [&](const scalar lo)
    {
        return max(label(std::ceil((lo + radius_)/h - 0.5)), label(0));
    };
    auto last = [&](const scalar hi)
    {
        return min(label(std::floor((hi + radius_)/h - 0.5)), n - 1);
    };

    for (const labelledTri& t : surfaceTriangles_)
    {
        vector2D q[3];
        for (label k = 0; k < 3; ++k)
        {
            const vector d(x[t[k]] - origin_);
            q[k] = vector2D(d & e1_, d & e2_);
        }
        const vector2D& a = q[0];
        const vector2D b(q[1] - a);
        const vector2D c(q[2] - a);
        const scalar det = b.x()*c.y() - c.x()*b.y();
        if (mag(det) < VSMALL)
        {
            continue;   // seen edge-on: covers nothing
        }
        const label i0 = first(min(min(q[0].x(), q[1].x()), q[2].x()));
        const label i1 = last(max(max(q[0].x(), q[1].x()), q[2].x()));
        const label j0 = first(min(min(q[0].y(), q[1].y()), q[2].y()));
        const label j1 = last(max(max(q[0].y(), q[1].y()), q[2].y()));
        for (label i = i0; i <= i1; ++i)
        {
            const scalar px = (i + 0.5)*h - radius_ - a.x();
            for (label j = j0; j <= j1; ++j)
            {
                const scalar py = (j + 0.5)*h - radius_ - a.y();
                // barycentric coordinates of the centre (a centre on an
                // edge counts as covered, as in metrics.py)
                const scalar l1 = (px*c.y() - c.x()*py)/det;
                const scalar l2 = (b.x()*py - px*b.y())/det;
                if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1)
                {
                    covered[i*n + j] = 1;
                }
            }
        }
    }

    label open = 0;
    for (label i = 0; i < n; ++i)
    {
        const scalar px = (i + 0.5)*h - radius_;
        for (label j = 0; j < n; ++j)
        {
            const scalar py = (j + 0.5)*h - radius_;
            if (!covered[i*n + j] && sqr(px) + sqr(py) < sqr(radius_))
            {
                ++open;
            }
        }
    }
    return open*sqr(h);
}


Foam::scalarField Foam::functionObjects::valveMetrics::partDepthBound
(
    const pointField& x
) const
{
    // A point q of an element lies within the element's longest edge of
    // each of its nodes v (the distance from v over the tetrahedron is
    // largest at a vertex), and v within k L of the surface when k edges
    // of length at most L lead from it to a surface node: so q lies
    // within (k + 1) L of the part's surface, k the fewest edges of the
    // element's nodes (partDepthEdges_)
    scalarField L(nParts_, 0);
    for (const solidTet& t : solid_->elements())
    {
        const label parti = nodePart_[t[0]];
        for (label a = 0; a < 4; ++a)
        {
            for (label b = a + 1; b < 4; ++b)
            {
                L[parti] = max(L[parti], magSqr(x[t[a]] - x[t[b]]));
            }
        }
    }
    scalarField bound(nParts_);
    forAll(bound, parti)
    {
        bound[parti] = (partDepthEdges_[parti] + 1)*Foam::sqrt(L[parti]);
    }
    return bound;
}


Foam::scalar Foam::functionObjects::valveMetrics::leafletGap
(
    const pointField& x
) const
{
    // The octree's nearest search within a radius rho finds every node
    // whose distance to the part's surface is below rho. A node inside
    // part j lies within depth_j of its surface (partDepthBound), so a
    // search with rho >= depth_j finds every node inside it, and a node
    // it misses lies outside, farther than rho: it cannot lower a gap
    // already at most rho. Each part is searched with rho the larger of
    // depth_j and the smallest gap so far; while no gap is known, from
    // twice the last row's gap (a guess only), widened fourfold until a
    // node is found. The result is the exhaustive search's.
    const scalarField depth(partDepthBound(x));
    const boundBox bb(x, false);
    const scalar span = bb.mag();
    scalar gap = GREAT;
    for (label partj = 0; partj < nParts_; ++partj)
    {
        triSurface& surf = partSurfaces_[partj];
        if (surf.empty())
        {
            continue;
        }
        surf.movePoints
        (
            pointField(UIndirectList<point>(x, partPoints_[partj]))
        );
        const triSurfaceSearch search(surf);
        scalar rho = depth[partj];
        if (gap < GREAT)
        {
            rho = max(rho, gap);
        }
        else if (lastLeafletGap_ > 0)
        {
            rho = max(rho, 2*lastLeafletGap_);
        }
        while (true)
        {
            for (const label nodei : surfaceNodes_)
            {
                if (nodePart_[nodei] == partj)
                {
                    continue;
                }
                const point& p = x[nodei];
                // (strictly within the radius: widened by a rounding)
                const pointIndexHit hit =
                    search.tree().findNearest(p, sqr(rho*(1 + 1e-9)));
                if (!hit.hit())
                {
                    continue;
                }
                scalar d = mag(p - hit.hitPoint());
                if
                (
                    triSurfaceTools::surfaceSide(surf, p, hit.index())
                 == triSurfaceTools::INSIDE
                )
                {
                    d = -d;     // inside the other leaflet
                }
                gap = min(gap, d);
            }
            // a gap known (found in this pass, at most rho, or from
            // another part, which rho is at least): every node missed is
            // farther than rho and cannot lower it. Beyond the solid's
            // span (or none to search) every node has been found
            if (gap < GREAT || rho > span || !(rho > 0))
            {
                break;
            }
            rho *= 4;
        }
    }
    lastLeafletGap_ = gap < GREAT ? gap : -1;
    return gap;
}


Foam::scalar Foam::functionObjects::valveMetrics::wallGap
(
    const immersedSolid& s
) const
{
    if (!wall_.valid() || wall_().empty())
    {
        return GREAT;
    }
    const pointField& x = s.points();
    const vectorField free(s.freeComponents());
    // The nodes inside the fluid domain (its closed boundary's octree) are
    // searched within rho, the smallest gap so far (while none is known,
    // twice the last row's gap, widened fourfold until a node is found):
    // a node inside the fluid that the search misses lies farther than
    // rho from the wall and cannot lower the gap. A node outside the
    // fluid (behind the wall) is searched without bound. The result is
    // the exhaustive search's
    DynamicList<label> nodes(surfaceNodes_.size());
    for (const label nodei : surfaceNodes_)
    {
        if (free.size() && cmptSum(free[nodei]) == 0)
        {
            continue;   // held (the attachment)
        }
        nodes.append(nodei);
    }
    const boolList inside
    (
        domainSearch_.valid() && domain_().size()
      ? domainSearch_().calcInside(pointField(UIndirectList<point>(x, nodes)))
      : boolList(nodes.size(), false)
    );
    // (no node lies farther than span from the wall)
    boundBox bb(wall_().points(), false);
    bb.add(pointField(UIndirectList<point>(x, nodes)));
    const scalar span = bb.mag();
    scalar rho = lastWallGap_ > 0 ? 2*lastWallGap_ : GREAT;
    scalar gap = GREAT;
    while (true)
    {
        forAll(nodes, k)
        {
            const point& p = x[nodes[k]];
            const scalar r = inside[k] ? min(rho, gap) : GREAT;
            const pointIndexHit hit =
                wallSearch_().tree().findNearest
                (
                    p,
                    r < GREAT ? sqr(r*(1 + 1e-9)) : sqr(GREAT)
                );
            if (!hit.hit())
            {
                continue;
            }
            scalar d = mag(p - hit.hitPoint());
            if
            (
                triSurfaceTools::surfaceSide(wall_(), p, hit.index())
             == triSurfaceTools::OUTSIDE
            )
            {
                d = -d;     // behind the wall (its normals leave the fluid)
            }
            gap = min(gap, d);
        }
        // every node missed lies inside the fluid, farther than rho: done
        // when the gap is at most rho
        if (gap <= rho || nodes.empty() || rho > span)
        {
            break;
        }
        rho *= 4;
    }
    lastWallGap_ = gap < GREAT ? gap : -1;
    return gap;
}


void Foam::functionObjects::valveMetrics::solidLoads
(
    const immersedSolid& s,
    scalar& maxPrincipal,
    scalar& maxVonMises,
    scalar& contactForce
) const
{
    maxPrincipal = 0;
    maxVonMises = 0;
    contactForce = 0;
    const immersedSolids::deformable* d =
        dynamic_cast<const immersedSolids::deformable*>(&s);
    if (!d)
    {
        return;
    }
    const smoothedSolid::ExplicitSolid& es = d->solid();

    // element Cauchy stress, symmetrised, as smoothedSolid's VtuSeries
    std::vector<smoothedSolid::Mat3> sigma;
    std::vector<double> J;
    es.elementStress(sigma, J);
    maxPrincipal = -GREAT;
    for (const smoothedSolid::Mat3& S : sigma)
    {
        const smoothedSolid::Mat3 sym = 0.5*(S + S.transpose());
        const smoothedSolid::Mat3 dev =
            sym - sym.trace()/3.0*smoothedSolid::Mat3::Identity();
        maxVonMises =
            max(maxVonMises, std::sqrt(1.5*dev.cwiseProduct(dev).sum()));
        Eigen::SelfAdjointEigenSolver<smoothedSolid::Mat3> eig
        (
            sym,
            Eigen::EigenvaluesOnly
        );
        maxPrincipal = max(maxPrincipal, scalar(eig.eigenvalues().maxCoeff()));
    }
    if (sigma.empty())
    {
        maxPrincipal = 0;
    }

    // contact: pressure times the tributary area PenaltyContact divided by
    const std::vector<double>& pc = es.contactPressure();
    const label n = min(label(pc.size()), contactArea_.size());
    for (label i = 0; i < n; ++i)
    {
        contactForce += pc[i]*contactArea_[i];
    }
}


void Foam::functionObjects::valveMetrics::writeFileHeader(Ostream& os)
{
    writeHeader(os, "Valve metrics (src/fsiCoupling/functionObjects/valveMetrics)");
    writeHeaderValue(os, "rho [kg/m3]", rho_);
    writeHeaderValue(os, "mu [Pa s]", mu_);
    writeHeaderValue
    (
        os,
        "inletPatch",
        mesh_.boundaryMesh()[inletPatch_].name()
    );
    writeHeaderValue
    (
        os,
        "outletPatch",
        mesh_.boundaryMesh()[outletPatch_].name()
    );
    writeHeaderValue(os, "wallPatch", mesh_.boundaryMesh()[wallPatch_].name());
    writeHeaderValue(os, "axis", axis_);
    writeHeaderValue(os, "origin [m]", origin_);
    writeHeaderValue(os, "annulusRadius [m]", radius_);
    writeHeaderValue(os, "resolution", resolution_);
    writeHeaderValue(os, "GOA raster cell h [m]", 2*radius_/resolution_);
    writeHeader
    (
        os,
        "GOA error <= sqrt(2) L h + few h^2, L the open region's outline"
    );
    writeCommented(os, "Time");
    for
    (
        const char* col :
        {
            "Q_inlet[m3/s]", "Q_outlet[m3/s]", "dp[mmHg]", "GOA[mm2]",
            "Re[-]", "maxDisplacement[mm]", "maxPrincipalStress[kPa]",
            "maxVonMises[kPa]", "contactForce[N]", "gapLeaflets[mm]",
            "gapWall[mm]", "leak[m3/s]"
        }
    )
    {
        writeTabbed(os, col);
    }
    if (beat_.valid())
    {
        writeTabbed(os, "p_upstream[mmHg]");
        writeTabbed(os, "p_downstream[mmHg]");
        writeTabbed(os, "v_jet[m/s]");
    }
    os  << endl;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::functionObjects::valveMetrics::valveMetrics
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    fvMeshFunctionObject(name, runTime, dict),
    writeFile(mesh_, name, typeName, dict),
    UName_("U"),
    pName_("p"),
    phiName_("phi"),
    inletPatch_(-1),
    outletPatch_(-1),
    wallPatch_(-1),
    rho_(0),
    mu_(0),
    axis_(0, 0, 1),
    e1_(1, 0, 0),
    e2_(0, 1, 0),
    origin_(Zero),
    radius_(0),
    resolution_(400),
    optionName_(),
    solid_(nullptr),
    solidReady_(false),
    nParts_(0),
    lastLeafletGap_(-1),
    lastWallGap_(-1),
    warnedTime_(false),
    upstream_(Zero),
    downstream_(Zero),
    upstreamCell_(-1),
    downstreamCell_(-1)
{
    read(dict);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::functionObjects::valveMetrics::checkPositive
(
    const dictionary& dict,
    const word& key,
    const scalar value
) const
{
    if (!(value > 0))
    {
        FatalIOErrorInFunction(dict)
            << "function object " << name() << " in " << dict.name()
            << ": entry " << key << ' ' << value << " must be positive"
            << exit(FatalIOError);
    }
}


void Foam::functionObjects::valveMetrics::readViscosity(const dictionary& dict)
{
    if (dict.found("mu"))
    {
        mu_ = dict.get<scalar>("mu");
        checkPositive(dict, "mu", mu_);
        return;
    }
    // rho nu of constant/transportProperties (the solver's, if it has read
    // it)
    autoPtr<IOdictionary> own;
    const IOdictionary* transport =
        mesh_.findObject<IOdictionary>("transportProperties");
    if (!transport)
    {
        own.reset
        (
            new IOdictionary
            (
                IOobject
                (
                    "transportProperties",
                    mesh_.time().constant(),
                    mesh_,
                    IOobject::MUST_READ,
                    IOobject::NO_WRITE,
                    false
                )
            )
        );
        transport = own.get();
    }
    if (!transport->found("nu"))
    {
        FatalIOErrorInFunction(dict)
            << "function object " << name() << " in " << dict.name()
            << ": no entry mu, and no nu in " << transport->objectPath()
            << ": give the dynamic viscosity as mu [Pa s]"
            << exit(FatalIOError);
    }
    mu_ = rho_*dimensionedScalar("nu", dimViscosity, *transport).value();
    checkPositive(dict, "mu (rho nu)", mu_);
}


void Foam::functionObjects::valveMetrics::readDisc(const dictionary& dict)
{
    const vector axis(dict.getOrDefault<vector>("axis", vector(0, 0, 1)));
    if (mag(axis) < VSMALL)
    {
        FatalIOErrorInFunction(dict)
            << "function object " << name() << " in " << dict.name()
            << ": entry axis " << axis << " is zero" << exit(FatalIOError);
    }
    axis_ = axis/mag(axis);
    // e1: the x direction (else y) across the axis; e2 = axis x e1
    const vector ref(mag(axis_.x()) < 0.9 ? vector(1, 0, 0) : vector(0, 1, 0));
    e1_ = ref - (ref & axis_)*axis_;
    e1_ /= mag(e1_);
    e2_ = axis_ ^ e1_;
    origin_ = dict.getOrDefault<point>("origin", Zero);
    radius_ = dict.getOrDefault<scalar>("annulusRadius", 9.1e-3);
    checkPositive(dict, "annulusRadius", radius_);
    resolution_ = dict.getOrDefault<label>("resolution", 400);
    if (resolution_ < 2)
    {
        FatalIOErrorInFunction(dict)
            << "function object " << name() << " in " << dict.name()
            << ": entry resolution " << resolution_ << " must be at least 2"
            << exit(FatalIOError);
    }
}


bool Foam::functionObjects::valveMetrics::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    writeFile::read(dict);

    UName_ = dict.getOrDefault<word>("U", "U");
    pName_ = dict.getOrDefault<word>("p", "p");
    phiName_ = dict.getOrDefault<word>("phi", "phi");

    inletPatch_ = patch(dict, "inletPatch", "inlet");
    outletPatch_ = patch(dict, "outletPatch", "outlet");
    wallPatch_ = patch(dict, "wallPatch", "wall");

    rho_ = dict.get<scalar>("rho");
    checkPositive(dict, "rho", rho_);
    readViscosity(dict);
    readDisc(dict);
    optionName_ = dict.getOrDefault<word>("fvOption", word::null);

    solid_ = &findSolid(dict);
    solidReady_ = false;
    wallSearch_.clear();
    wall_.clear();
    domainSearch_.clear();
    domain_.clear();
    setDiscCells();
    readBeats(dict);

    return true;
}


Foam::label Foam::functionObjects::valveMetrics::sampleCell
(
    const dictionary& dict,
    const word& key,
    const point& p
) const
{
    const label celli = mesh_.findCell(p);
    if (returnReduce(celli >= 0 ? 1 : 0, sumOp<label>()) == 0)
    {
        FatalIOErrorInFunction(dict)
            << "function object " << name() << " in " << dict.name()
            << ": entry beats." << key << ' ' << p
            << " lies outside the fluid mesh: give a point inside it [m]"
            << exit(FatalIOError);
    }
    return celli;
}


void Foam::functionObjects::valveMetrics::readBeats(const dictionary& dict)
{
    beat_.clear();
    beatFile_.clear();
    previousBeat_.clear();
    if (!dict.found("beats"))
    {
        return;
    }
    const dictionary& b = dict.subDict("beats");
    const scalar period = b.get<scalar>("period");
    checkPositive(b, "period", period);
    const scalar start = b.getOrDefault<scalar>("start", 0);
    const scalar fraction = b.getOrDefault<scalar>("openFraction", 0.1);
    if (!(fraction > 0 && fraction < 1))
    {
        FatalIOErrorInFunction(b)
            << "function object " << name() << " in " << dict.name()
            << ": entry beats.openFraction " << fraction
            << " must lie between 0 and 1" << exit(FatalIOError);
    }
    upstream_ = b.get<point>("upstream");
    downstream_ = b.get<point>("downstream");
    upstreamCell_ = sampleCell(dict, "upstream", upstream_);
    downstreamCell_ = sampleCell(dict, "downstream", downstream_);

    // the jet: the disc's cells from the origin's plane to the downstream
    // point
    const scalar zDown = (downstream_ - origin_) & axis_;
    DynamicList<label> jet(discCells_.size());
    forAll(discCells_, k)
    {
        if (discCellAxial_[k] >= 0 && discCellAxial_[k] <= zDown)
        {
            jet.append(discCells_[k]);
        }
    }
    jetCells_.transfer(jet);

    beat_.reset(new valveBeat(period, rho_, fraction));
    const scalar t = time_.value();
    beat_->restartAt(t, start);
    if (Pstream::master() && writeToFile())
    {
        beatFile_ = createFile("beats");
        writeHeader
        (
            beatFile_(),
            "Valve metrics per beat "
            "(src/fsiCoupling/functionObjects/valveMetrics/valveBeat.H)"
        );
        writeHeaderValue(beatFile_(), "period [s]", period);
        writeHeaderValue(beatFile_(), "rho [kg/m3]", rho_);
        writeHeaderValue(beatFile_(), "upstream [m]", upstream_);
        writeHeaderValue(beatFile_(), "downstream [m]", downstream_);
        writeHeaderValue(beatFile_(), "openFraction", fraction);
        valveBeat::writeHeader(beatFile_());
        beatFile_().flush();
    }
    // the start time's sample, if the solver's fields are there
    if (mesh_.foundObject<surfaceScalarField>(phiName_))
    {
        sampleBeat();
    }
}


Foam::scalar Foam::functionObjects::valveMetrics::sampledPressure
(
    const label celli
) const
{
    const volScalarField& p = lookupObject<volScalarField>(pName_);
    scalar v = celli >= 0 ? p[celli] : 0;
    label n = celli >= 0 ? 1 : 0;
    reduce(v, sumOp<scalar>());
    reduce(n, sumOp<label>());
    return v/n;     // a point on a face shared by ranks: their mean
}


void Foam::functionObjects::valveMetrics::sampleBeat()
{
    scalar Qin = 0;
    scalar Qout = 0;
    scalar dp = 0;
    flowMetrics(Qin, Qout, dp);
    const scalar pUp = rho_*sampledPressure(upstreamCell_);
    const scalar pDown = rho_*sampledPressure(downstreamCell_);
    beat_->addFlow(time_.value(), Qin, pUp - pDown, pDown, jetVelocity());
}


Foam::scalar Foam::functionObjects::valveMetrics::jetVelocity() const
{
    const volVectorField& U = lookupObject<volVectorField>(UName_);
    scalar vJet = -GREAT;
    for (const label celli : jetCells_)
    {
        vJet = max(vJet, U[celli] & axis_);
    }
    return returnReduce(vJet, maxOp<scalar>());
}


void Foam::functionObjects::valveMetrics::finishBeat()
{
    valveBeat& b = *beat_;
    if (Pstream::master())
    {
        if (b.complete(1e-9*(b.end() - b.start())))
        {
            const valveBeat::metrics m = b.evaluate();
            Log << type() << ' ' << name() << ": beat " << m.beat << " ("
                << m.start << " to " << b.end() << " s): stroke volume "
                << m.strokeVolume*1e6 << " ml, regurgitant fraction "
                << 100*m.regurgitantFraction << " %, mean gradient "
                << m.meanGradient/paPerMmHg << " mmHg, EOA " << m.EOA*1e4
                << " cm2, aortic pressure " << m.aorticMax/paPerMmHg << '/'
                << m.aorticMin/paPerMmHg << " mmHg" << endl;
            if (beatFile_.valid())
            {
                valveBeat::writeRow(beatFile_(), m, previousBeat_.get());
                beatFile_().flush();
            }
            previousBeat_.reset(new valveBeat::metrics(m));
        }
        else
        {
            Log << type() << ' ' << name() << ": beat " << b.beat() + 1
                << " (" << b.start() << " to " << b.end()
                << " s) not covered from its start by this run: no row"
                << endl;
            previousBeat_.clear();
        }
    }
    b.next();
}


bool Foam::functionObjects::valveMetrics::execute()
{
    if (!beat_.valid())
    {
        return true;
    }
    const scalar t = time_.value();
    const scalar tol = 1e-9*(beat_->end() - beat_->start());
    while (t > beat_->end() + tol)
    {
        finishBeat();
    }
    sampleBeat();
    return true;
}


bool Foam::functionObjects::valveMetrics::end()
{
    if
    (
        beat_.valid()
     && time_.value() >= beat_->end() - 1e-9*(beat_->end() - beat_->start())
    )
    {
        finishBeat();
    }
    return true;
}


void Foam::functionObjects::valveMetrics::prepare(const immersedSolid& s)
{
    if (!solidReady_)
    {
        setSolid(s);
    }
    if (!wall_.valid())
    {
        setWall();      // collective, once (the fluid mesh is fixed)
        if (!wall_.valid())
        {
            wall_.reset(new triSurface());  // (not the master)
        }
    }
    const scalar t = time_.value();
    if
    (
        !warnedTime_
     && mag(s.time() - t) > 1e-3*max(time_.deltaTValue(), SMALL)
    )
    {
        WarningInFunction
            << type() << ' ' << name() << ": the immersed solid is of time "
            << s.time() << ", not of the current time " << t
            << " (postProcess reads the solid once): its metrics are of "
            << "that time" << endl;
        warnedTime_ = true;
    }
}


void Foam::functionObjects::valveMetrics::flowMetrics
(
    scalar& Qin,
    scalar& Qout,
    scalar& dp
) const
{
    // flow rates and the area-weighted mean pressures of the inlet and
    // the outlet, summed over the ranks
    const surfaceScalarField& phi = lookupObject<surfaceScalarField>(phiName_);
    const volScalarField& p = lookupObject<volScalarField>(pName_);
    Qin = -sum(phi.boundaryField()[inletPatch_]);
    Qout = sum(phi.boundaryField()[outletPatch_]);
    const scalarField& magSfIn = mesh_.magSf().boundaryField()[inletPatch_];
    const scalarField& magSfOut = mesh_.magSf().boundaryField()[outletPatch_];
    scalar pAin = sum(p.boundaryField()[inletPatch_]*magSfIn);
    scalar pAout = sum(p.boundaryField()[outletPatch_]*magSfOut);
    scalar Ain = sum(magSfIn);
    scalar Aout = sum(magSfOut);
    reduce(Qin, sumOp<scalar>());
    reduce(Qout, sumOp<scalar>());
    reduce(pAin, sumOp<scalar>());
    reduce(pAout, sumOp<scalar>());
    reduce(Ain, sumOp<scalar>());
    reduce(Aout, sumOp<scalar>());
    dp = rho_*(pAin/Ain - pAout/Aout)/paPerMmHg;
}


Foam::scalar Foam::functionObjects::valveMetrics::peakAxialVelocity
(
    const pointField& x
) const
{
    // the largest axial velocity of the disc's cells between the solid's
    // lowest and highest point (all ranks; -GREAT if none)
    const volVectorField& U = lookupObject<volVectorField>(UName_);
    scalar sMin = GREAT;
    scalar sMax = -GREAT;
    for (const point& xi : x)
    {
        const scalar si = (xi - origin_) & axis_;
        sMin = min(sMin, si);
        sMax = max(sMax, si);
    }
    scalar vPeak = -GREAT;
    forAll(discCells_, i)
    {
        if (discCellAxial_[i] >= sMin && discCellAxial_[i] <= sMax)
        {
            vPeak = max(vPeak, U[discCells_[i]] & axis_);
        }
    }
    reduce(vPeak, maxOp<scalar>());
    return vPeak;
}


bool Foam::functionObjects::valveMetrics::write()
{
    clockTime clock;
    const immersedSolid& s = *solid_;
    prepare(s);

    // fluid (all ranks)
    scalar Qin = 0;
    scalar Qout = 0;
    scalar dp = 0;
    flowMetrics(Qin, Qout, dp);
    const scalar leak = Qout < 0 ? -Qout : 0;
    const pointField& x = s.points();
    const scalar vPeak = peakAxialVelocity(x);
    const bool haveRe = vPeak > -GREAT;
    const scalar Re = haveRe ? 2*rho_*vPeak*radius_/mu_ : 0;
    // with beats: the sampled pressures [Pa] and the jet's velocity
    scalar pUp = 0;
    scalar pDown = 0;
    scalar vJet = 0;
    if (beat_.valid())
    {
        pUp = rho_*sampledPressure(upstreamCell_);
        pDown = rho_*sampledPressure(downstreamCell_);
        vJet = jetVelocity();
    }

    if (!Pstream::master())
    {
        return true;
    }

    // solid (master; replicated)
    const scalar GOA = orificeArea(x);
    scalar maxDisp = 0;
    const pointField& X = s.points0();
    forAll(x, i)
    {
        maxDisp = max(maxDisp, mag(x[i] - X[i]));
    }
    scalar maxPrincipal = 0;
    scalar maxVonMises = 0;
    scalar contactForce = 0;
    solidLoads(s, maxPrincipal, maxVonMises, contactForce);
    if (beat_.valid())
    {
        beat_->addValve(time_.value(), GOA, maxPrincipal);
    }
    const scalar gapL = leafletGap(x);
    const scalar gapW = wallGap(s);

    auto mm = [](const scalar v) { return v*1e3; };

    Log << type() << ' ' << name() << ": Q_inlet " << Qin << " Q_outlet "
        << Qout << " m3/s, dp " << dp << " mmHg, GOA " << GOA*1e6
        << " mm2, v " << vPeak << " m/s, Re " << Re << ", maxDisplacement "
        << mm(maxDisp) << " mm, maxPrincipalStress " << maxPrincipal*1e-3
        << " kPa, maxVonMises " << maxVonMises*1e-3 << " kPa, contactForce "
        << contactForce << " N, gapLeaflets "
        << (nParts_ > 1 ? mm(gapL) : 0) << " mm, gapWall " << mm(gapW)
        << " mm, leak " << leak << " m3/s; the row took "
        << clock.elapsedTime() << " s" << endl;

    if (!writeToFile())
    {
        return true;
    }
    OFstream& os = file();
    if (!writtenHeader_)
    {
        writeFileHeader(os);
        writtenHeader_ = true;
    }
    auto col = [&](const bool valid, const scalar v)
    {
        os  << tab;
        if (valid)
        {
            os  << v;
        }
        else
        {
            os  << "nan";
        }
    };
    writeCurrentTime(os);
    col(true, Qin);
    col(true, Qout);
    col(true, dp);
    col(true, GOA*1e6);
    col(haveRe, Re);
    col(true, mm(maxDisp));
    col(true, maxPrincipal*1e-3);
    col(true, maxVonMises*1e-3);
    col(true, contactForce);
    col(nParts_ > 1 && gapL < GREAT, mm(gapL));
    col(gapW < GREAT, mm(gapW));
    col(true, leak);
    if (beat_.valid())
    {
        col(true, pUp/paPerMmHg);
        col(true, pDown/paPerMmHg);
        col(true, vJet);
    }
    os  << endl;

    return true;
}


// ************************************************************************* //
