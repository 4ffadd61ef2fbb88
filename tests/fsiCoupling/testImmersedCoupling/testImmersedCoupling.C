/*---------------------------------------------------------------------------*\
    isfem: test of fsiCoupling (immersed solid, FSI pairs, interpolation)
-------------------------------------------------------------------------------
Application
    testImmersedCoupling

Description
    Run in a case with a fluid mesh and constant/solidProperties:

        -test solid    the solid object: sizes, rigid motion against the
                       analytic positions, a deformable solid's advance
        -test force    a free deformable solid under a nodal external force:
                       momentum against the impulse
        -test pairs    F-S and S-F pairs against brute force (every cell
                       with the same inside test) for random placements
        -test walk     mean walk steps per node per step while the (rigid)
                       solid moves by its prescribed motion
        -test interp   both interpolation directions on linear fields
        -test coverage covered cells of a (thin) solid where it is, against
                       the cells a dense lattice of its points lies in
        -test coupling the immersedCoupling object over 5 steps of the rigid
                       motion: transfers exact for linear fields
        -test enclosed the enclosed fluid regions kept up to date as the
                       solid moves, against a whole fill each step
        -test outside  the solid shifted by -shift (x y z): must stop with
                       a FatalError
        -test balancedFlux  the balanced body force's flux and
                       reconstruction (balancedForceFlux): symmetric and
                       positive, linear interpolation not; a uniform force
        -test wallPoints  cellTetTransfer's wall points (free, slip,
                       noSlip) beside the cube's walls: the near-wall
                       interpolation of a field vanishing on a wall, and
                       spread as gather's transpose under each condition
        -test wallInterp  the forcing of cutCells interpolation
                       (immersedWallInterpolation) beside a tilted plane:
                       a velocity linear in the distance to the wall is
                       Fadlun's value in every forcing cell (the forcing's
                       residual and reaction vanish), a quadratic one not

    Prints 'measured ... reference ... tolerance' lines and 'PASS'/'FAIL';
    exits non-zero on FAIL.

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "immersedSolid.H"
#include "immersedCoupling.H"
#include "deformableSolid.H"
#include "immersedPairs.H"
#include "immersedInterpolation.H"
#include "immersedBoundary.H"
#include "interpolation.H"
#include "immersedElasticForce.H"
#include "Random.H"
#include "Function1.H"
#include "calculatedFvPatchField.H"
#include "meshSearch.H"
#include "polyMeshTetDecomposition.H"
#include "immersedCutCells.H"
#include "triSurface.H"
#include "triSurfaceSearch.H"
#include "immersedWallInterpolation.H"
#include "fvMatrices.H"
#include "balancedForceFlux.H"
#include "zeroGradientFvPatchFields.H"
#include "cellTetTransfer.H"
#include "syncTools.H"

using namespace Foam;

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

static bool allPassed = true;

// A closed triangulated surface from points and triangles, oriented
// outward (flipped if its signed volume is negative); its volume
static triSurface closedSurface
(
    const pointField& pts,
    List<labelledTri> tris,
    scalar& volume
)
{
    volume = 0;
    for (const labelledTri& t : tris)
    {
        volume += (pts[t[0]] & (pts[t[1]] ^ pts[t[2]]))/6;
    }
    if (volume < 0)
    {
        for (labelledTri& t : tris)
        {
            std::swap(t[1], t[2]);
        }
        volume = -volume;
    }
    return triSurface(tris, geometricSurfacePatchList(), pts);
}


// A hexahedron's closed surface from its 8 corners, listed as the
// tilted prism below lists them: (a, b) over {-1, 2}^2, a outer, each
// corner's bottom then top
static triSurface hexSurface(const pointField& pts)
{
    // corners: 0 (-1,-1) 2 (-1,2) 4 (2,-1) 6 (2,2); +1 on top
    List<labelledTri> tris
    ({
        labelledTri(0, 4, 6, 0), labelledTri(0, 6, 2, 0),
        labelledTri(1, 3, 7, 0), labelledTri(1, 7, 5, 0),
        labelledTri(0, 1, 5, 0), labelledTri(0, 5, 4, 0),
        labelledTri(2, 6, 7, 0), labelledTri(2, 7, 3, 0),
        labelledTri(0, 2, 3, 0), labelledTri(0, 3, 1, 0),
        labelledTri(4, 5, 7, 0), labelledTri(4, 7, 6, 0)
    });
    scalar volume;
    return closedSurface(pts, tris, volume);
}


// The prism below the tilted plane z = z0 + s (x - 0.5) over [-1, 2]^2,
// down to z = -1: its top crosses the box [0,1]^3 as a plane
static triSurface tiltedPrism(const scalar z0, const scalar s)
{
    pointField pts(8);
    label k = 0;
    for (const scalar x : {-1.0, 2.0})
    for (const scalar y : {-1.0, 2.0})
    {
        pts[k++] = point(x, y, -1);
        pts[k++] = point(x, y, z0 + s*(x - 0.5));
    }
    return hexSurface(pts);
}


// Icosphere of radius R about c, n subdivisions (points projected on the
// sphere)
static triSurface icosphere
(
    const point& c,
    const scalar R,
    const label n,
    scalar& volume
)
{
    const scalar g = (1 + std::sqrt(5.0))/2;
    DynamicList<point> p
    ({
        point(-1, g, 0), point(1, g, 0), point(-1, -g, 0), point(1, -g, 0),
        point(0, -1, g), point(0, 1, g), point(0, -1, -g), point(0, 1, -g),
        point(g, 0, -1), point(g, 0, 1), point(-g, 0, -1), point(-g, 0, 1)
    });
    DynamicList<FixedList<label, 3>> t
    ({
        {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
        {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
        {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
        {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}
    });
    for (point& q : p) { q /= mag(q); }
    for (label level = 0; level < n; ++level)
    {
        HashTable<label, edge, Hash<edge>> mid;
        auto midpoint = [&](const label a, const label b)
        {
            const edge e(a, b);
            const auto iter = mid.cfind(e);
            if (iter.found()) { return *iter; }
            point m = 0.5*(p[a] + p[b]);
            m /= mag(m);
            p.append(m);
            mid.insert(e, p.size() - 1);
            return label(p.size() - 1);
        };
        DynamicList<FixedList<label, 3>> next;
        for (const FixedList<label, 3>& f : t)
        {
            const label ab = midpoint(f[0], f[1]);
            const label bc = midpoint(f[1], f[2]);
            const label ca = midpoint(f[2], f[0]);
            next.append(FixedList<label, 3>({f[0], ab, ca}));
            next.append(FixedList<label, 3>({f[1], bc, ab}));
            next.append(FixedList<label, 3>({f[2], ca, bc}));
            next.append(FixedList<label, 3>({ab, bc, ca}));
        }
        t.transfer(next);
    }
    pointField pts(p.size());
    forAll(p, i) { pts[i] = c + R*p[i]; }
    List<labelledTri> tris(t.size());
    forAll(t, i) { tris[i] = labelledTri(t[i][0], t[i][1], t[i][2], 0); }
    return closedSurface(pts, tris, volume);
}



void check
(
    const word& what,
    const scalar measured,
    const scalar reference,
    const scalar tol,
    const bool pass
)
{
    Info<< "    " << what << ": measured " << measured
        << "  reference " << reference << "  tolerance " << tol
        << (pass ? "  PASS" : "  FAIL") << endl;
    allPassed = allPassed && pass;
}


// Random rotation (Rodrigues) of angle in [0, pi) about a random axis
tensor randomRotation(Random& rnd)
{
    vector k(rnd.sample01<vector>() - vector::uniform(0.5));
    k /= mag(k) + ROOTVSMALL;
    const scalar t = constant::mathematical::pi*rnd.sample01<scalar>();
    const tensor K(0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0);
    return Foam::cos(t)*I + Foam::sin(t)*K + (1 - Foam::cos(t))*sqr(k);
}


// Brute force F-S: first cell whose bounding box holds p and which contains
// it by the same inside test
label bruteCell
(
    const immersedPairs& pairs,
    const List<boundBox>& cellBb,
    const point& p
)
{
    forAll(cellBb, c)
    {
        if (cellBb[c].contains(p) && pairs.inside(p, c))
        {
            return c;
        }
    }
    return -1;
}


int main(int argc, char *argv[])
{
    argList::addOption
    (
        "transferPoints", "word",
        "carriedFlux: immersedElasticForce's transferPoints"
        " (nodes | elements; default nodes)"
    );
    argList::addOption
    (
        "wallPoints", "word",
        "carriedFlux: immersedElasticForce's wallPoints"
        " (free | slip | noSlip; default free)"
    );
    argList::addOption("test", "name", "solid | force | pairs | walk | interp | carriedFlux | balancedFlux | wallPoints | coverage | coupling | enclosed | outside | cutCells | wallInterp");
    argList::addOption("placements", "N", "random placements (pairs)");
    argList::addOption("steps", "N", "motion steps (walk)");
    argList::addOption("shift", "vector", "translation (outside)");

    #include "setRootCase.H"
    #include "createTime.H"
    #include "createMesh.H"

    const word test(args.get<word>("test"));
    const IOdictionary props
    (
        IOobject
        (
            "solidProperties",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );
    autoPtr<immersedSolid> solidPtr(immersedSolid::New(runTime, props));
    immersedSolid& solid = *solidPtr;

    const dictionary couplingDict
    (
        props.subOrEmptyDict("coupling")
    );

    Info<< "solid: " << solid.nPoints() << " nodes, " << solid.nElements()
        << " elements; fluid: " << mesh.nCells() << " cells" << nl << endl;

    const pointField& C = mesh.cellCentres();
    const point solidCentre(average(solid.points0()));

    if (test == "solid")
    {
        // Rigid: positions after advancing against the analytic motion
        // (the case's solidProperties: translation + rotation)
        if (!solid.isDeformable())
        {
            const dictionary& m = props.subDict("motion");
            const vector v(Function1<vector>::New("velocity", m)->value(0));
            const point o(m.get<point>("origin"));
            vector k(m.get<vector>("axis"));
            k /= mag(k);
            const scalar w = Function1<scalar>::New("omega", m)->value(0);
            const scalar dt = 0.01;
            const label n = 10;
            for (label i = 0; i < n; ++i)
            {
                solid.advance(dt);
            }
            const scalar T = n*dt;
            const scalar th = w*T;
            const tensor K(0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0);
            const tensor R(Foam::cos(th)*I + Foam::sin(th)*K + (1 - Foam::cos(th))*sqr(k));
            scalar err = 0, errV = 0;
            forAll(solid.points(), i)
            {
                const point x(o + v*T + (R & (solid.points0()[i] - o)));
                const vector u(v + w*(k ^ (x - o - v*T)));
                err = max(err, mag(x - solid.points()[i]));
                errV = max(errV, mag(u - solid.velocities()[i]));
            }
            check("rigid position error", err, 0, 1e-12, err < 1e-12);
            check("rigid velocity error", errV, 0, 1e-12, errV < 1e-12);
        }
        else
        {
            // Deformable at rest, no load: stays at rest
            const scalar dt = 1e-4;
            solid.advance(dt);
            const scalar d = max(mag(solid.points() - solid.points0()));
            check("deformable at rest, max displacement", d, 0, 1e-12, d < 1e-12);
            check("deformable time", solid.time(), dt, 1e-15,
                mag(solid.time() - dt) < 1e-15);
        }
    }
    else if (test == "force")
    {
        // A free deformable solid under a constant nodal external force
        // (total F) for T from rest. velocities() is the mean over the
        // step, (x(T) - x(0))/T (deformable::tryAdvance), and the centre
        // of mass moves by F T^2/(2M): sum m v = F T/2. The central
        // difference gives it to O(h): checked |2 sum m v/(F T) - 1| <= 1/N
        // (N sub-steps)
        immersedSolids::deformable& d =
            refCast<immersedSolids::deformable>(solid);
        const vector F(0.6, -0.3, 0.2);
        solid.externalForce() = F/scalar(solid.nPoints());
        const scalar T = 0.05;
        solid.advance(T);
        const scalarField m(d.lumpedMass());
        const vector P(sum(m*solid.velocities()));
        const label N = d.lastSubSteps();
        const scalar ratio = 2*(P & F)/(magSqr(F)*T);
        const scalar perp = mag(P - ((P & F)/magSqr(F))*F)/(mag(F)*T);
        Info<< "sub-steps " << N << ", total mass " << sum(m) << endl;
        check("2 sum m v / (F T)", ratio, 1, 1.0/N, mag(ratio - 1) <= 1.0/N);
        check("momentum across F / (|F| T)", perp, 0, 1e-10, perp < 1e-10);
        check("sub-cycled (sub-steps > 1)", N, 2, 0, N > 1);
        const vector Fsum(sum(d.externalForce()));
        Info<< "    total external force " << Fsum << endl;
    }
    else if (test == "pairs")
    {
        immersedPairs pairs(mesh, couplingDict);
        const label nPlace = args.getOrDefault<label>("placements", 10);

        List<boundBox> cellBb(mesh.nCells());
        forAll(cellBb, c)
        {
            cellBb[c] = boundBox(mesh.points(), mesh.cellPoints()[c], false);
            cellBb[c].inflate(1e-9);
        }

        const boundBox meshBb(mesh.points(), true);
        Random rnd(42);
        label nodesTotal = 0, nodesEqual = 0;
        label sfTotal = 0, sfEqual = 0, sfBrute = 0;
        scalar wErr = 0;
        label steps = 0, walks = 0, fallback = 0;
        for (label k = 0; k < nPlace; ++k)
        {
            // Random rotation about the solid's centre and a random centre
            // in the middle half of the fluid box
            const tensor R(randomRotation(rnd));
            const point c
            (
                meshBb.min()
              + cmptMultiply
                (
                    vector::uniform(0.3) + 0.4*rnd.sample01<vector>(),
                    meshBb.span()
                )
            );
            pointField x(c + (R & (solid.points0() - solidCentre)));

            pairs.findNodeCells(x);
            steps += pairs.nSteps();
            walks += pairs.nWalks();
            fallback += pairs.nFallback();
            forAll(x, i)
            {
                ++nodesTotal;
                if (bruteCell(pairs, cellBb, x[i]) == pairs.nodeCells()[i])
                {
                    ++nodesEqual;
                }
            }

            pairs.findCoveredCells(x, solid.elements());
            labelList cellSlot(mesh.nCells(), -1);
            forAll(pairs.coveredCells(), s)
            {
                if (pairs.centreInside()[s])
                {
                    cellSlot[pairs.coveredCells()[s]] = s;
                }
            }
            // Brute force: every cell against every element, lowest first
            forAll(C, celli)
            {
                label found = -1;
                immersedPairs::tetWeights wf;
                forAll(solid.elements(), e)
                {
                    const solidTet& t = solid.elements()[e];
                    const immersedPairs::tetWeights w
                    (
                        immersedPairs::barycentric
                        (
                            C[celli], x[t[0]], x[t[1]], x[t[2]], x[t[3]]
                        )
                    );
                    if (immersedPairs::insideTet(w))
                    {
                        found = e;
                        wf = w;
                        break;
                    }
                }
                const label s = cellSlot[celli];
                if (found >= 0)
                {
                    ++sfBrute;
                }
                if (found >= 0 || s >= 0)
                {
                    ++sfTotal;
                    if
                    (
                        found >= 0 && s >= 0
                     && pairs.coveringElement()[s] == found
                    )
                    {
                        ++sfEqual;
                        for (label a = 0; a < 4; ++a)
                        {
                            wErr = max(wErr, mag(wf[a] - pairs.weights()[s][a]));
                        }
                    }
                }
            }
        }
        // Sums over ranks (in parallel each rank checks its own cells; a
        // node is counted as equal on a rank when both searches agree there)
        reduce(nodesTotal, sumOp<label>());
        reduce(nodesEqual, sumOp<label>());
        reduce(sfTotal, sumOp<label>());
        reduce(sfEqual, sumOp<label>());
        reduce(sfBrute, sumOp<label>());
        reduce(wErr, maxOp<scalar>());
        reduce(steps, sumOp<label>());
        reduce(walks, sumOp<label>());
        reduce(fallback, sumOp<label>());
        Info<< "F-S: " << nodesTotal << " nodes in " << nPlace
            << " placements; walks " << walks << ", neighbour steps "
            << steps << ", octree fallbacks " << fallback << nl
            << "S-F: " << sfBrute << " covered cells by brute force" << endl;
        check("F-S pairs equal to brute force [%]",
            100.0*nodesEqual/max(nodesTotal, 1), 100, 0, nodesEqual == nodesTotal);
        check("S-F pairs equal to brute force [%]",
            100.0*sfEqual/max(sfTotal, 1), 100, 0,
            sfEqual == sfTotal && sfBrute > 0);
        check("S-F weights max difference", wErr, 0, 1e-12, wErr < 1e-12);
    }
    else if (test == "walk")
    {
        immersedPairs pairs(mesh, couplingDict);
        const label n = args.getOrDefault<label>("steps", 50);
        const scalar dt = runTime.deltaTValue();

        // Mean cell size and the solid's displacement per step
        const scalar h = Foam::cbrt(gAverage(mesh.V()));
        pairs.findNodeCells(solid.points());
        pointField xOld(solid.points());
        label steps = 0, walks = 0, fallback = 0, left = 0;
        scalar moved = 0;
        for (label k = 0; k < n; ++k)
        {
            solid.advance(dt);
            moved += max(mag(solid.points() - xOld));
            xOld = solid.points();
            pairs.findNodeCells(solid.points());
            steps += pairs.nSteps();
            walks += pairs.nWalks();
            fallback += pairs.nFallback();
            left += pairs.nLeft();
        }
        reduce(steps, sumOp<label>());
        reduce(walks, sumOp<label>());
        reduce(fallback, sumOp<label>());
        reduce(left, sumOp<label>());
        Info<< "walks that left the rank through a processor face "
            << "(then searched by the octree): " << left << endl;
        Info<< "mean cell size " << h << ", largest node displacement per"
            << " step " << moved/n << " (" << moved/n/h << " cells)" << nl
            << "walks " << walks << ", neighbour steps " << steps
            << ", octree fallbacks " << fallback << endl;
        const scalar mean = scalar(steps)/max(walks, 1);
        check("mean walk steps per node per step", mean, 2, 2, mean <= 2);
        check("octree fallbacks (not counting processor faces)",
            fallback, 0, 0, fallback == 0);
    }
    else if (test == "carriedFlux")
    {
        // fv::immersedElasticForce with balancedForce yes and nodeVelocity
        // flux: the nodes move with the reconstruction of the face flux
        // (not with the cells' velocity), and the force's face flux
        // (balancedForceFlux::flux of the spread force, the projection's
        // way in) is its transpose: sum_i v_i . F_i = rho sum_f phi_f
        // flux_f/w_f over the faces, w_f = |S_f|/(n_f.d_f) (the faces'
        // inner product of balancedForceFlux; exact where D_c = V_c I:
        // tets)
        const vector U0(0.3, -0.2, 0.5);
        volVectorField U
        (
            IOobject("U", runTime.timeName(), mesh),
            mesh,
            dimensionedVector(dimVelocity, Zero)
        );
        surfaceScalarField phi
        (
            IOobject("phi", runTime.timeName(), mesh),
            mesh.Sf() & dimensionedVector("U0", dimVelocity, U0)
        );
        dictionary optDict;
        optDict.add("type", "immersedElasticForce");
        optDict.add("selectionMode", "all");
        optDict.add("rhoFluid", 1000.0);
        optDict.add
        (
            "transferPoints",
            args.getOrDefault<word>("transferPoints", "nodes")
        );
        optDict.add
        (
            "wallPoints",
            args.getOrDefault<word>("wallPoints", "free")
        );
        fv::immersedElasticForce opt
        (
            "carried", "immersedElasticForce", optDict, mesh
        );
        const scalar rho = 1000.0;

        // (1) a uniform flux with the cells at rest: every free node moves
        // with the flux's velocity
        const vectorField v0(opt.nodeVelocity(U));
        const vectorField free(opt.solid().freeComponents());
        scalar errUniform = 0;
        label nFree = 0;
        forAll(v0, i)
        {
            if (cmptSum(free[i]) > 0)
            {
                errUniform = max(errUniform, mag(v0[i] - U0)/mag(U0));
                ++nFree;
            }
        }

        // (2) a flux that varies from face to face (zero through the
        // boundary, where the force's flux is zero too); the update
        // strains the solid; the power of its force at the nodes'
        // velocities against the power of the force's face flux
        // phi_f = 1e-4 sin(k.x_f) (S_f . a): a flux field (opposite on
        // the two sides of a processor face, as S_f)
        const vector a(1, 0.7, -0.4);
        auto wave = [](const point& x)
        {
            return 1e-4*Foam::sin(37*x.x() + 23*x.y() - 11*x.z());
        };
        forAll(phi, facei)
        {
            phi[facei] =
                wave(mesh.Cf()[facei])*(mesh.Sf()[facei] & a);
        }
        for (auto& pphi : phi.boundaryFieldRef())
        {
            if (pphi.coupled())
            {
                const vectorField pCf(pphi.patch().Cf());
                const vectorField pSf(pphi.patch().Sf());
                forAll(pphi, i)
                {
                    pphi[i] = wave(pCf[i])*(pSf[i] & a);
                }
            }
            else
            {
                pphi = 0;
            }
        }
        U.primitiveFieldRef() = U0;     // the cells do not move the nodes
        ++runTime;
        opt.updateForce();
        const vectorField v(opt.nodeVelocity(U));
        const vectorField& F = opt.nodeForce();
        scalar solidPower = 0, scale = 0, sumMagF = 0;
        vector total(Zero);
        forAll(F, i)
        {
            solidPower += v[i] & F[i];
            scale += mag(v[i])*mag(F[i]);
            sumMagF += mag(F[i]);
            total += F[i];
        }
        // the whole force handed to the fluid's cells (none to the walls:
        // the solid is away from them)
        vector fluidTotal(Zero);
        forAll(opt.force().field(), celli)
        {
            fluidTotal += rho*mesh.V()[celli]*opt.force().field()[celli];
        }
        reduce(fluidTotal, sumOp<vector>());
        const scalar errTotal =
            mag(fluidTotal + opt.wallForce() - total)/sumMagF;
        const scalar errWall = mag(opt.wallForce())/sumMagF;
        volVectorField f
        (
            IOobject("fBalanced", runTime.timeName(), mesh),
            mesh,
            dimensionedVector(dimAcceleration, Zero),
            zeroGradientFvPatchVectorField::typeName
        );
        f.primitiveFieldRef() = opt.force().field();
        f.correctBoundaryConditions();
        const balancedForceFlux balanced(mesh);
        const surfaceScalarField phiF(balanced.flux(f));
        const surfaceScalarField w(mesh.magSf()*mesh.nonOrthDeltaCoeffs());
        scalar fluidPower = 0;
        forAll(phiF, facei)
        {
            fluidPower += rho*phi[facei]*phiF[facei]/w[facei];
        }
        forAll(phiF.boundaryField(), patchi)
        {
            const fvsPatchScalarField& pF = phiF.boundaryField()[patchi];
            if (!pF.coupled())
            {
                continue;
            }
            // a processor face is in both ranks' sums: half each
            forAll(pF, i)
            {
                fluidPower += 0.5*rho*phi.boundaryField()[patchi][i]*pF[i]
                   /w.boundaryField()[patchi][i];
            }
        }
        reduce(fluidPower, sumOp<scalar>());
        // negative control: the force's flux by linear interpolation,
        // f_f . S_f (not the transpose)
        const surfaceScalarField phiLinear(fvc::interpolate(f) & mesh.Sf());
        scalar controlPower = 0;
        forAll(phiLinear, facei)
        {
            controlPower += rho*phi[facei]*phiLinear[facei]/w[facei];
        }
        forAll(phiLinear.boundaryField(), patchi)
        {
            const fvsPatchScalarField& pF = phiLinear.boundaryField()[patchi];
            if (pF.coupled())
            {
                forAll(pF, i)
                {
                    controlPower += 0.5*rho*phi.boundaryField()[patchi][i]
                       *pF[i]/w.boundaryField()[patchi][i];
                }
            }
        }
        reduce(controlPower, sumOp<scalar>());
        const scalar errPower = mag(fluidPower - solidPower)/scale;
        const scalar errControl = mag(controlPower - solidPower)/scale;
        Info<< "free nodes " << nFree << nl
            << "uniform flux, cells at rest: largest relative error of the"
            << " nodes' velocity " << errUniform << " (tolerance 1e-12)" << nl
            << "power: solid sum v.F " << solidPower << " W, face fluxes"
            << " rho sum phi phiF/w " << fluidPower << " W, relative"
            << " difference " << errPower << " (tolerance 1e-12)" << nl
            << "negative control, the force's flux by linear interpolation"
            << " f_f.S_f: relative difference " << errControl
            << " (must exceed 1e-3)" << nl
            << "force: solid " << total << " N, fluid " << fluidTotal
            << " N + walls " << opt.wallForce() << " N, relative difference "
            << errTotal << " (tolerance 1e-12); to the walls " << errWall
            << " (the solid is away from the walls: tolerance 1e-12)"
            << endl;
        bool ok = true;
        auto check = [&](const bool pass, const char* what)
        {
            Info<< what << (pass ? "  PASS" : "  FAIL") << endl;
            ok = ok && pass;
        };
        check(nFree > 0 && errUniform < 1e-12, "uniform flux");
        check(max(mag(F)) > 0, "the update strains the solid");
        check(errPower < 1e-12, "force flux is the transpose (power)");
        check(errControl > 1e-3, "negative control differs");
        check(errTotal < 1e-12, "whole force handed over");
        check(errWall < 1e-12, "no force to the walls");
        if (!ok)
        {
            FatalErrorInFunction << "carriedFlux: a check failed"
                << exit(FatalError);
        }
        Info<< "carriedFlux: all checks passed" << endl;
    }
    else if (test == "balancedFlux")
    {
        // balancedForceFlux (isfemFoam's balanced body force): the force's
        // way to the cells, A f = reconstruct(flux(f)), is symmetric and
        // positive in the cells' volume inner product; with linear
        // interpolation to the faces (the negative control) it is not.
        // Fields that vary from cell to cell, the same on any rank
        auto field = [&](const scalar k)
        {
            volVectorField f
            (
                IOobject("f", runTime.timeName(), mesh),
                mesh,
                dimensionedVector(dimAcceleration, Zero),
                zeroGradientFvPatchVectorField::typeName
            );
            forAll(C, celli)
            {
                const point& x = C[celli];
                f[celli] = vector
                (
                    Foam::sin(k*(37*x.x() + 23*x.y() + 11*x.z())),
                    Foam::cos(k*(13*x.x() - 41*x.y() + 29*x.z())),
                    Foam::sin(k*(31*x.x() + 7*x.y() - 43*x.z()) + 1)
                );
            }
            f.correctBoundaryConditions();
            return f;
        };
        const balancedForceFlux balanced(mesh);
        const scalarField& V = mesh.V();
        auto inner = [&](const volVectorField& a, const volVectorField& b)
        {
            return gSum(V*(a.primitiveField() & b.primitiveField()));
        };
        auto applyAdjoint = [&](const volVectorField& f)
        {
            return balanced.reconstruct(balanced.flux(f));
        };
        auto applyLinear = [&](const volVectorField& f)
        {
            surfaceScalarField phi(fvc::interpolate(f) & mesh.Sf());
            for (auto& pphi : phi.boundaryFieldRef())
            {
                if (!pphi.coupled())
                {
                    pphi = 0;
                }
            }
            return balanced.reconstruct(phi);
        };
        const volVectorField a(field(1)), b(field(1.7));
        {
            const scalar ab = inner(a, applyAdjoint(b));
            const scalar ba = inner(b, applyAdjoint(a));
            const scalar asym = mag(ab - ba)/max(mag(ab), mag(ba));
            check("adjoint flux: asymmetry |<a,Ab> - <b,Aa>|/|<a,Ab>|",
                asym, 0, 1e-12, asym < 1e-12);
            scalar minRatio = GREAT;
            for (const scalar k : {1.0, 0.5, 2.3, 0.05})
            {
                const volVectorField c(field(k));
                minRatio =
                    min(minRatio, inner(c, applyAdjoint(c))/inner(c, c));
            }
            check("adjoint flux: smallest <c,Ac>/<c,c> of 4 fields (> 0)",
                minRatio, 0, 0, minRatio > 0);
        }
        {
            const scalar ab = inner(a, applyLinear(b));
            const scalar ba = inner(b, applyLinear(a));
            const scalar asym = mag(ab - ba)/max(mag(ab), mag(ba));
            check("negative control, linear interpolation: asymmetry"
                " (must exceed 1e-3)", asym, 0, 1e-3, asym > 1e-3);
        }

        // reconstruct() is exact for a uniform field
        const vector f0(0.3, -0.2, 0.5);
        const surfaceScalarField phi0
        (
            mesh.Sf() & dimensionedVector("f0", dimless, f0)
        );
        const volVectorField r0(balanced.reconstruct(phi0));
        scalar errR = 0;
        forAll(r0, celli)
        {
            errR = max(errR, mag(r0[celli] - f0)/mag(f0));
        }
        reduce(errR, maxOp<scalar>());
        check("reconstruct of a uniform flux: max relative error",
            errR, 0, 1e-12, errR < 1e-12);

        // The balanced-force property: the flux of a force f = grad phi
        // (phi = f0.x, any cell values of a linear field) is the
        // Laplacian's flux of phi, |S_f|/(n_f.d_f) (phi_n - phi_o), so
        // that the pressure phi balances it and no flow starts. Exact
        // where D_c = V_c I (planar faces: tets); tolerance 1e-12 there
        // and 5 % (the mean over the faces) on polyhedra
        volVectorField fU
        (
            IOobject("fU", runTime.timeName(), mesh),
            mesh,
            dimensionedVector("f0", dimAcceleration, f0),
            zeroGradientFvPatchVectorField::typeName
        );
        const surfaceScalarField phiU(balanced.flux(fU));
        const surfaceScalarField& rd = mesh.nonOrthDeltaCoeffs();
        scalar sumErr = 0, sumRef = 0;
        forAll(phiU, facei)
        {
            const scalar ref = mesh.magSf()[facei]*rd[facei]
               *(f0 & (C[mesh.neighbour()[facei]] - C[mesh.owner()[facei]]));
            sumErr += mag(phiU[facei] - ref);
            sumRef += mag(ref);
        }
        // processor faces: the owner-to-neighbour vector of the patch
        label nCoupled = 0;
        forAll(mesh.boundary(), patchi)
        {
            const fvPatch& pp = mesh.boundary()[patchi];
            if (!pp.coupled())
            {
                continue;
            }
            const vectorField delta(pp.delta());
            const scalarField& pw = mesh.magSf().boundaryField()[patchi];
            const scalarField& prd = rd.boundaryField()[patchi];
            const scalarField& pphi = phiU.boundaryField()[patchi];
            forAll(pphi, i)
            {
                const scalar ref = pw[i]*prd[i]*(f0 & delta[i]);
                sumErr += mag(pphi[i] - ref);
                sumRef += mag(ref);
                ++nCoupled;
            }
        }
        Info<< "    processor faces checked: "
            << returnReduce(nCoupled, sumOp<label>()) << endl;
        const scalar errF = returnReduce(sumErr, sumOp<scalar>())
           /returnReduce(sumRef, sumOp<scalar>());
        bool tets = true;
        for (const cell& c : mesh.cells())
        {
            tets = tets && c.size() == 4;
        }
        const scalar tolF = returnReduce(tets, andOp<bool>()) ? 1e-12 : 0.05;
        check("flux of f = grad(f0.x) against the Laplacian's flux of"
            " f0.x: sum |difference|/sum |flux| over internal and processor faces",
            errF, 0, tolF, errF < tolF);
        // and its negative control: the flux of linear interpolation,
        // S_f.f0, is not the Laplacian's flux on non-orthogonal tets
        scalar sumLin = 0;
        forAll(phiU, facei)
        {
            const scalar ref = mesh.magSf()[facei]*rd[facei]
               *(f0 & (C[mesh.neighbour()[facei]] - C[mesh.owner()[facei]]));
            sumLin += mag((mesh.Sf()[facei] & f0) - ref);
        }
        const scalar errLin = returnReduce(sumLin, sumOp<scalar>())
           /returnReduce(sumRef, sumOp<scalar>());
        check("negative control, linear interpolation against the"
            " Laplacian's flux (must exceed 0.01)", errLin, 0, 0.01,
            errLin > 0.01);
    }
    else if (test == "interp")
    {
        immersedPairs pairs(mesh, couplingDict);

        // Solid placed at the middle of the fluid box
        const boundBox meshBb(mesh.points(), true);
        const pointField x(solid.points0() - solidCentre + meshBb.centre());
        pairs.findNodeCells(x);
        pairs.findCoveredCells(x, solid.elements());

        // Linear fields
        const scalar p0 = 1.5;
        const vector gp(2, -3, 0.5);
        const vector U0(1, 2, 3);
        const tensor gU(0.5, -1, 2, 1.5, 0.25, -0.75, -2, 1, 0.3);
        auto pExact = [&](const point& y) { return p0 + (gp & y); };
        auto UExact = [&](const point& y) { return U0 + (gU & y); };

        volScalarField p
        (
            IOobject("p", runTime.timeName(), mesh),
            mesh,
            dimensionedScalar(dimless, Zero),
            calculatedFvPatchField<scalar>::typeName
        );
        volVectorField U
        (
            IOobject("U", runTime.timeName(), mesh),
            mesh,
            dimensionedVector(dimless, Zero),
            calculatedFvPatchField<vector>::typeName
        );
        forAll(C, c)
        {
            p[c] = pExact(C[c]);
            U[c] = UExact(C[c]);
        }
        forAll(mesh.boundary(), patchi)
        {
            if (mesh.boundary()[patchi].coupled())
            {
                continue;
            }
            const vectorField& Cf = mesh.boundary()[patchi].Cf();
            fvPatchScalarField& pp = p.boundaryFieldRef()[patchi];
            fvPatchVectorField& Up = U.boundaryFieldRef()[patchi];
            forAll(Cf, f)
            {
                pp[f] = pExact(Cf[f]);
                Up[f] = UExact(Cf[f]);
            }
        }

        // Processor patches: the neighbour rank's cell values
        p.correctBoundaryConditions();
        U.correctBoundaryConditions();

        scalar pMax = 0, UMax = 0;
        forAll(x, i)
        {
            pMax = max(pMax, mag(pExact(x[i])));
            UMax = max(UMax, mag(UExact(x[i])));
        }

        const wordList schemes({"cellLinear", "cellPoint"});
        for (const word& scheme : schemes)
        {
            autoPtr<interpolation<scalar>> pI
            (
                interpolation<scalar>::New(scheme, p)
            );
            autoPtr<interpolation<vector>> UI
            (
                interpolation<vector>::New(scheme, U)
            );
            const scalarField ps
            (
                immersedInterpolation::fluidToSolid(*pI, x, pairs.nodeCells())
            );
            const vectorField Us
            (
                immersedInterpolation::fluidToSolid(*UI, x, pairs.nodeCells())
            );
            scalar ep = 0, eU = 0;
            forAll(x, i)
            {
                ep = max(ep, mag(ps[i] - pExact(x[i])));
                eU = max(eU, mag(Us[i] - UExact(x[i])));
            }
            ep /= pMax;
            eU /= UMax;
            if (scheme == "cellLinear")
            {
                check("fluid->solid p (cellLinear) max rel. error", ep, 0, 1e-10, ep < 1e-10);
                check("fluid->solid U (cellLinear) max rel. error", eU, 0, 1e-10, eU < 1e-10);
            }
            else
            {
                Info<< "    fluid->solid with " << scheme
                    << " (information, not exact): p max rel. error " << ep
                    << ", U " << eU << endl;
            }
        }

        // Solid -> fluid: nodal velocities of the linear field
        vectorField vs(x.size());
        forAll(x, i)
        {
            vs[i] = UExact(x[i]);
        }
        const vectorField vf
        (
            immersedInterpolation::solidToFluid(pairs, solid.elements(), vs)
        );
        scalar e = 0;
        forAll(vf, k)
        {
            e = max(e, mag(vf[k] - UExact(C[pairs.coveredCells()[k]])));
        }
        reduce(e, maxOp<scalar>());
        e /= UMax;
        const label nCovered = returnReduce(vf.size(), sumOp<label>());
        Info<< "    covered cells (all ranks): " << nCovered << endl;
        check("solid->fluid U max rel. error", e, 0, 1e-10,
            e < 1e-10 && nCovered > 0);

        // Every node owned by exactly one rank
        labelList owners(x.size(), 0);
        forAll(owners, i)
        {
            owners[i] = (pairs.nodeCells()[i] >= 0 ? 1 : 0);
        }
        Pstream::listCombineGather(owners, plusEqOp<label>());
        Pstream::listCombineScatter(owners);
        label nBad = 0;
        forAll(owners, i)
        {
            if (owners[i] != 1)
            {
                ++nBad;
            }
        }
        check("nodes not owned by exactly one rank", nBad, 0, 0, nBad == 0);
    }
    else if (test == "coverage")
    {
        // A thin solid where it is (e.g. a plate thinner than the cells):
        // the cells its interior passes through, found by a dense lattice
        // (16 intervals per edge) of points in every element, against the
        // covered cells of 'centre' and 'touching' coverage
        const pointField& x = solid.points();
        meshSearch ms(mesh, polyMesh::CELL_TETS);
        labelHashSet crossed;
        const label m = 16;
        for (const solidTet& t : solid.elements())
        {
            for (label i = 0; i <= m; ++i)
            for (label j = 0; i + j <= m; ++j)
            for (label k = 0; i + j + k <= m; ++k)
            {
                const label l = m - i - j - k;
                const point p
                (
                    (i*x[t[0]] + j*x[t[1]] + k*x[t[2]] + l*x[t[3]])/scalar(m)
                );
                const label c = ms.findCell(p, -1, true);
                if (c >= 0)
                {
                    crossed.insert(c);
                }
            }
        }
        const label nCrossed = returnReduce(crossed.size(), sumOp<label>());
        Info<< "cells the solid passes through (dense lattice): " << nCrossed
            << endl;

        for (const word cov : {"centre", "touching"})
        {
            dictionary d;
            d.add("coverage", cov);
            immersedPairs pairs(mesh, d);
            pairs.findNodeCells(x);
            pairs.findCoveredCells(x, solid.elements());
            labelHashSet covered(pairs.coveredCells());
            label nHit = 0;
            for (const label c : crossed)
            {
                if (covered.found(c))
                {
                    ++nHit;
                }
            }
            reduce(nHit, sumOp<label>());
            const label nCov =
                returnReduce(pairs.coveredCells().size(), sumOp<label>());
            const scalar pct = 100.0*nHit/max(nCrossed, 1);
            Info<< "coverage " << cov << ": " << nCov << " covered cells"
                << endl;
            if (cov == "touching")
            {
                // Brute force: every (cell, element) pair whose bounding
                // boxes overlap, by the same tet-tet test
                List<treeBoundBox> cellBb(mesh.nCells());
                forAll(cellBb, c)
                {
                    cellBb[c] = treeBoundBox
                    (
                        boundBox(mesh.points(), mesh.cellPoints()[c], false)
                    );
                }
                // element e at positions xx, and its bounding box
                auto elementAt = [&]
                (
                    const pointField& xx,
                    const label e,
                    treeBoundBox& eb
                )
                {
                    const solidTet& t = solid.elements()[e];
                    const FixedList<point, 4> A
                        ({xx[t[0]], xx[t[1]], xx[t[2]], xx[t[3]]});
                    eb = treeBoundBox(A[0], A[0]);
                    for (label k = 1; k < 4; ++k) { eb.add(A[k]); }
                    return A;
                };
                // a tet of the cell's CELL_TETS decomposition meets A
                auto tetsMeet = [&](const FixedList<point, 4>& A, const label c)
                {
                    for
                    (
                        const tetIndices& ti
                      : polyMeshTetDecomposition::cellTetIndices(mesh, c)
                    )
                    {
                        const tetPointRef tp(ti.tet(mesh));
                        if
                        (
                            immersedPairs::tetsIntersect
                            (
                                A,
                                FixedList<point, 4>
                                    ({tp.a(), tp.b(), tp.c(), tp.d()})
                            )
                        )
                        {
                            return true;
                        }
                    }
                    return false;
                };
                auto bruteTouching = [&](const pointField& xx)
                {
                    labelHashSet brute;
                    forAll(solid.elements(), e)
                    {
                        treeBoundBox eb;
                        const FixedList<point, 4> A(elementAt(xx, e, eb));
                        forAll(cellBb, c)
                        {
                            if (brute.found(c) || !cellBb[c].overlaps(eb))
                            {
                                continue;
                            }
                            const immersedPairs::tetWeights w
                            (
                                immersedPairs::barycentric
                                (
                                    C[c], A[0], A[1], A[2], A[3]
                                )
                            );
                            const bool hit =
                                immersedPairs::insideTet(w) || tetsMeet(A, c);
                            if (hit)
                            {
                                brute.insert(c);
                            }
                        }
                    }
                    return brute;
                };
                // nearElements (a superset of the touching elements of
                // each covered cell) and the wall location from them
                // against the octree of the whole surface
                List<labelledTri> tris;
                labelList surfPoints;
                CompactListList<label> elemTris;
                solid.surface(tris, surfPoints, elemTris);
                immersedBoundary boundary(mesh);
                auto checkNear = [&](const pointField& xx, const word& when)
                {
                    const labelUList& cov = pairs.coveredCells();
                    const CompactListList<label>& near = pairs.nearElements();
                    label nTouch = 0, nMissing = 0, nNear = 0;
                    forAll(cov, i)
                    {
                        const labelHashSet listed(near[i]);
                        nNear += listed.size();
                        const label c = cov[i];
                        forAll(solid.elements(), e)
                        {
                            treeBoundBox eb;
                            const FixedList<point, 4> A(elementAt(xx, e, eb));
                            if (!cellBb[c].overlaps(eb))
                            {
                                continue;
                            }
                            const bool hit = tetsMeet(A, c);
                            if (hit)
                            {
                                ++nTouch;
                                if (!listed.found(e)) ++nMissing;
                            }
                        }
                    }
                    reduce(nTouch, sumOp<label>());
                    reduce(nMissing, sumOp<label>());
                    reduce(nNear, sumOp<label>());
                    Info<< "    " << when << ": touching element-cell pairs "
                        << nTouch << ", listed by nearElements " << nNear
                        << endl;
                    check
                    (
                        "nearElements: touching pairs not listed",
                        nMissing, 0, 0, nMissing == 0 && nTouch > 0
                    );

                    boundary.update(cov, vectorField(cov.size(), Zero));
                    const pointField sp(UIndirectList<point>(xx, surfPoints));
                    boundary.locateWall(triSurface(tris, sp));
                    const scalarList octree(boundary.wallFraction());
                    boundary.locateWall(sp, tris, near, elemTris);
                    const scalarList& local = boundary.wallFraction();
                    // negative control: the covering element only
                    const labelUList& covering = pairs.coveringElement();
                    CompactListList<label> one(labelList(cov.size(), 1));
                    forAll(covering, i)
                    {
                        one.m()[i] = covering[i];
                    }
                    immersedBoundary control(mesh);
                    control.update(cov, vectorField(cov.size(), Zero));
                    control.locateWall(sp, tris, one, elemTris);
                    label nOct = 0, nDiff = 0, nControl = 0;
                    scalar maxDiff = 0;
                    forAll(octree, k)
                    {
                        nOct += (octree[k] >= 0);
                        nControl += (control.wallFraction()[k] >= 0);
                        if ((octree[k] >= 0) != (local[k] >= 0)) ++nDiff;
                        else maxDiff = max(maxDiff, mag(octree[k] - local[k]));
                    }
                    reduce(nOct, sumOp<label>());
                    reduce(nDiff, sumOp<label>());
                    reduce(nControl, sumOp<label>());
                    reduce(maxDiff, maxOp<scalar>());
                    Info<< "    " << when << ": walls located by the octree "
                        << nOct << ", by the covering element alone "
                        << nControl << " (negative control)" << endl;
                    check
                    (
                        "wall location element by element: faces differing"
                        " from the octree's",
                        nDiff, 0, 0, nDiff == 0 && nOct > 0
                    );
                    check
                    (
                        "negative control (covering element only) locates"
                        " fewer walls",
                        nControl, nOct, 0, nControl < nOct
                    );
                    check
                    (
                        "wall location element by element: largest"
                        " fraction difference",
                        maxDiff, 0, 1e-12, maxDiff <= 1e-12
                    );
                };
                checkNear(x, "initial position");

                const labelHashSet brute(bruteTouching(x));
                label nSame = 0;
                for (const label c : brute)
                {
                    if (covered.found(c)) ++nSame;
                }
                const label nBrute = returnReduce(brute.size(), sumOp<label>());
                const label nOct = returnReduce(covered.size(), sumOp<label>());
                reduce(nSame, sumOp<label>());
                const bool same = nSame == nBrute && nBrute == nOct;
                Info<< "    touching: brute force " << nBrute
                    << " cells, octree " << nOct << endl;
                check("touching: covered cells equal to brute force [%]",
                    100.0*nSame/max(max(nBrute, nOct), 1), 100, 0, same);
                check("touching: crossed cells covered [%]", pct, 100, 0,
                    nHit == nCrossed && nCrossed > 0);

                // Small motions (below the candidate lists' margin of a
                // quarter of the smallest cell: the lists are reused) and
                // one large one (rebuilt): still equal to brute force
                const scalar h = Foam::cbrt(gMin(mesh.V().field()));
                const vector small(0.02*h, 0.015*h, 0.01*h);
                const vector large(0.6*h, -0.4*h, 0.3*h);
                pointField xk(x);
                for (label k = 1; k <= 4; ++k)
                {
                    xk += (k < 4 ? small : large);
                    pairs.findNodeCells(xk);
                    pairs.findCoveredCells(xk, solid.elements());
                    checkNear(xk, k < 4 ? "moved by a small step" : "moved far");
                    const labelHashSet bk(bruteTouching(xk));
                    label nSameK = 0;
                    for (const label c : bk)
                    {
                        if (pairs.coveredCells().found(c)) ++nSameK;
                    }
                    const bool sameK =
                        returnReduce
                        (
                            nSameK == bk.size()
                         && bk.size() == pairs.coveredCells().size(),
                            andOp<bool>()
                        );
                    Info<< "    moved " << (k < 4 ? "by a small step" : "far")
                        << ": candidate lists built "
                        << pairs.nCandidateUpdates() << " times" << endl;
                    check
                    (
                        "touching after the motion: equal to brute force",
                        sameK ? 1 : 0, 1, 0, sameK
                    );
                    check
                    (
                        "candidate lists built (reused for small motion)",
                        pairs.nCandidateUpdates(), (k < 4 ? 1 : 2), 0,
                        pairs.nCandidateUpdates() == (k < 4 ? 1 : 2)
                    );
                }
            }
            else
            {
                Info<< "    centre (information, the thin-leaflet trap):"
                    << " crossed cells covered " << pct << " %" << endl;
            }
        }
    }
    else if (test == "coupling")
    {
        // The coupling object through a few steps of the rigid solid's
        // prescribed motion: pairs updated, transfers exact for linear
        // fields (default interpolation cellLinear)
        immersedCoupling coupling(mesh);
        const scalar p0 = 1.5;
        const vector gp(2, -3, 0.5);
        volScalarField p
        (
            IOobject("p", runTime.timeName(), mesh),
            mesh,
            dimensionedScalar(dimless, Zero),
            calculatedFvPatchField<scalar>::typeName
        );
        forAll(C, c)
        {
            p[c] = p0 + (gp & C[c]);
        }
        forAll(mesh.boundary(), patchi)
        {
            if (!mesh.boundary()[patchi].coupled())
            {
                p.boundaryFieldRef()[patchi] ==
                    p0 + (gp & mesh.boundary()[patchi].Cf());
            }
        }
        p.correctBoundaryConditions();

        Info<< "first search (octrees built): " << coupling.searchTime()
            << " s" << endl;
        const scalar t0 = coupling.searchTime();
        scalar ep = 0, ev = 0;
        label nCovered = 0;
        const scalar dt = runTime.deltaTValue();
        for (label k = 0; k < 5; ++k)
        {
            coupling.solid().advance(dt);
            coupling.updatePairs();
            const pointField& x = coupling.solid().points();
            const scalarField ps(coupling.fluidToSolid(p));
            forAll(x, i)
            {
                ep = max(ep, mag(ps[i] - p0 - (gp & x[i]))/p0);
            }
            // rigid motion: the velocity field is linear in space
            const vectorField vf
            (
                coupling.solidToFluid(coupling.solid().velocities())
            );
            const labelUList& cells = coupling.pairs().coveredCells();
            const dictionary& m = props.subDict("motion");
            const vector v(Function1<vector>::New("velocity", m)->value(0));
            const scalar w = Function1<scalar>::New("omega", m)->value(0);
            const vector axis(normalised(m.get<vector>("axis")));
            const point centre
            (
                m.get<point>("origin") + v*(coupling.solid().time())
            );
            forAll(vf, j)
            {
                if (!coupling.pairs().centreInside()[j])
                {
                    continue;   // touching: clamped weights, not exact
                }
                const vector exact(v + w*(axis ^ (C[cells[j]] - centre)));
                ev = max(ev, mag(vf[j] - exact)/mag(v));
            }
            nCovered += vf.size();
        }
        reduce(ep, maxOp<scalar>());
        reduce(ev, maxOp<scalar>());
        reduce(nCovered, sumOp<label>());
        Info<< "covered cells over 5 steps: " << nCovered << nl
            << "search time per step " << (coupling.searchTime() - t0)/5
            << " s, transfer time (5 steps) "
            << coupling.transferTime() << " s" << endl;
        check("coupling: fluid->solid p max rel. error", ep, 0, 1e-10, ep < 1e-10);
        check("coupling: solid->fluid v max rel. error", ev, 0, 1e-10,
            ev < 1e-10 && nCovered > 0);
    }
    else if (test == "enclosed")
    {
        // The enclosed fluid regions kept up to date where the covered
        // cells change (immersedBoundary::updateEnclosedFluid) against a
        // whole fill of a fresh object, step by step of the rigid motion
        // (a closed shell: the fluid inside is enclosed); p fixed on every
        // boundary (the fill's seeds)
        volScalarField p
        (
            IOobject("p", runTime.timeName(), mesh),
            mesh,
            dimensionedScalar(dimless, Zero),
            "fixedValue"
        );
        dictionary d;
        d.add("coverage", "touching");
        immersedPairs pairs(mesh, d);
        immersedBoundary boundary(mesh);
        const label nSteps(args.getOrDefault<label>("steps", 12));
        const scalar dt = runTime.deltaTValue();
        label nWrong = 0, nChanged = 0, nEnclosedMin = labelMax;
        boolList enclosed0;
        for (label k = 0; k <= nSteps; ++k)
        {
            if (k)
            {
                solid.advance(dt);
            }
            const pointField& x = solid.points();
            pairs.findNodeCells(x);
            pairs.findCoveredCells(x, solid.elements());
            const labelUList& cov = pairs.coveredCells();
            boundary.update(cov, vectorField(cov.size(), Zero));
            immersedBoundary fresh(mesh);
            fresh.update(cov, vectorField(cov.size(), Zero));

            // the same partition: region ids matched one to one
            Map<label> toFresh, fromFresh;
            label wrong = 0;
            boolList enclosed(mesh.nCells(), false);
            forAll(C, c)
            {
                const label a = boundary.region(c);
                const label b = fresh.region(c);
                enclosed[c] = b > 0;
                if ((a > 0) != (b > 0) || (a < 0) != (b < 0))
                {
                    ++wrong;
                }
                else if (a > 0)
                {
                    if (!toFresh.found(a)) toFresh.insert(a, b);
                    if (!fromFresh.found(b)) fromFresh.insert(b, a);
                    if (toFresh[a] != b || fromFresh[b] != a) ++wrong;
                }
            }
            if
            (
                boundary.nEnclosed() != fresh.nEnclosed()
             || boundary.nEnclosedRegions() != fresh.nEnclosedRegions()
            )
            {
                ++wrong;
            }
            nWrong += wrong;
            nEnclosedMin = min(nEnclosedMin, fresh.nEnclosed());
            if (k == 0)
            {
                enclosed0 = enclosed;
            }
            else
            {
                forAll(enclosed, c)
                {
                    nChanged += (enclosed[c] != enclosed0[c]);
                }
            }
            Info<< "    step " << k << ": covered " << cov.size()
                << ", enclosed cells " << fresh.nEnclosed() << " in "
                << fresh.nEnclosedRegions() << " regions; kept up to date "
                << boundary.nEnclosed() << " in "
                << boundary.nEnclosedRegions() << endl;
        }
        Info<< "whole fills " << boundary.nFills() << ", local updates "
            << boundary.nLocalUpdates() << " in " << nSteps << " steps; cells"
            << " whose enclosure changed since step 0, summed over the"
            << " steps: " << nChanged << endl;
        check("enclosed regions kept up to date: cells or counts differing"
            " from a whole fill", nWrong, 0, 0, nWrong == 0);
        check("the shell encloses fluid at every step (smallest count)",
            nEnclosedMin, 1, 0, nEnclosedMin > 0);
        check("the enclosed cells change with the motion (the comparison"
            " can fail)", nChanged, 1, 0, nChanged > 0);
        check("local updates used", boundary.nLocalUpdates(), 1, 0,
            boundary.nLocalUpdates() > 0);
    }
    else if (test == "cutCells")
    {
        // 1. The closed forms against sampling: random vertex values, the
        //    positive fraction of points drawn uniformly in the simplex
        //    (normalised exponentials); a crude estimate (the fraction of
        //    positive vertices) as the negative control
        {
            Random rnd(7);
            const label nSets = 200, nSamples = 20000;
            scalar errTri = 0, errTet = 0, errCrude = 0;
            for (label s = 0; s < nSets; ++s)
            {
                FixedList<scalar, 4> phi;
                for (scalar& v : phi) { v = 2*rnd.sample01<scalar>() - 1; }
                const FixedList<scalar, 3> phi3({phi[0], phi[1], phi[2]});
                label inTri = 0, inTet = 0;
                for (label k = 0; k < nSamples; ++k)
                {
                    FixedList<scalar, 4> w;
                    scalar sum = 0;
                    for (scalar& v : w)
                    {
                        v = -std::log(max(rnd.sample01<scalar>(), VSMALL));
                        sum += v;
                    }
                    const scalar sum3 = sum - w[3];
                    scalar v3 = 0, v4 = 0;
                    for (label j = 0; j < 3; ++j)
                    {
                        v3 += w[j]*phi[j]/sum3;
                        v4 += w[j]*phi[j]/sum;
                    }
                    v4 += w[3]*phi[3]/sum;
                    if (v3 > 0) { ++inTri; }
                    if (v4 > 0) { ++inTet; }
                }
                const scalar fTri = scalar(inTri)/nSamples;
                const scalar fTet = scalar(inTet)/nSamples;
                errTri = max(errTri,
                    mag(immersedCutCells::triangleFraction(phi3) - fTri));
                errTet = max(errTet,
                    mag(immersedCutCells::tetFraction(phi) - fTet));
                label nPos = 0;
                for (const scalar v : phi) { if (v > 0) { ++nPos; } }
                errCrude = max(errCrude, mag(nPos/4.0 - fTet));
            }
            // standard error of one estimate <= 0.5/sqrt(20000) = 0.0035
            check("triangle fraction against sampling (200 sets, largest"
                " difference)", errTri, 0, 0.02, errTri < 0.02);
            check("tetrahedron fraction against sampling", errTet, 0, 0.02,
                errTet < 0.02);
            check("negative control: positive vertices / 4 against sampling"
                " (must fail)", errCrude, 0, 0.02, errCrude > 0.02);

            // exact: in the reference tetrahedron x, y, z >= 0,
            // x + y + z <= 1 the part x > a is (1 - a)^3 of it, the part
            // x + y < b is b^2 (3 - 2b) of it (int_0^b 6 s (1 - s) ds);
            // in the reference triangle the part x > a is (1 - a)^2
            const scalar eTet1 =
                immersedCutCells::tetFraction({-0.3, 0.7, -0.3, -0.3});
            const scalar eTet2 =
                immersedCutCells::tetFraction({-0.3, 0.7, 0.7, -0.3});
            const scalar eTet3 =
                immersedCutCells::tetFraction({0.3, -0.7, -0.7, 0.3});
            const scalar eTri =
                immersedCutCells::triangleFraction({-0.3, 0.7, -0.3});
            check("tet, x > 0.3", eTet1, 0.343, 1e-12,
                mag(eTet1 - 0.343) < 1e-12);
            check("tet, x + y > 0.3", eTet2, 1 - 0.09*2.4, 1e-12,
                mag(eTet2 - (1 - 0.09*2.4)) < 1e-12);
            check("tet, x + y < 0.3", eTet3, 0.09*2.4, 1e-12,
                mag(eTet3 - 0.09*2.4) < 1e-12);
            check("triangle, x > 0.3", eTri, 0.49, 1e-12,
                mag(eTri - 0.49) < 1e-12);
        }

        // The wall inside each cut cell: its area vector closes the cell's
        // open face areas, A_w = -sum_f A_open,f (out of the cell)
        auto wallVectors = [&](const immersedCutCells& cut)
        {
            const labelList& cells = cut.cells();
            vectorField Aw(cells.size(), Zero);
            const labelUList& own = mesh.faceOwner();
            forAll(cells, i)
            {
                for (const label facei : mesh.cells()[cells[i]])
                {
                    const vector A = cut.openArea(facei);
                    Aw[i] -= own[facei] == cells[i] ? A : -A;
                }
            }
            return Aw;
        };
        // On a planar face (a triangle) the aperture is the open fraction:
        // a_f S_f is the open area vector
        auto planarApertureError = [&](const immersedCutCells& cut)
        {
            scalar err = 0;
            for (const label celli : cut.cells())
            {
                for (const label facei : mesh.cells()[celli])
                {
                    if (mesh.faces()[facei].size() == 3)
                    {
                        const vector& Sf = mesh.faceAreas()[facei];
                        err = max(err,
                            mag(cut.aperture(facei)*Sf - cut.openArea(facei))
                           /mag(Sf));
                    }
                }
            }
            return err;
        };
        labelList allCells(identity(mesh.nCells()));
        const scalarField V(mesh.V().field());

        // 2D (cutCells2D: 10 x 10 cells 0.1 wide, one 0.05 deep, empty
        // front and back): the slab below the line y = y0 + s (x - 0.5),
        // spanning the depth inset by 1e-3 of it (as the Turek-Hron flag),
        // is cut by its in-plane sides only, phi the distance to the line
        // at the mid-plane: exact. The cut cells have points up to 0.14
        // from the line, deeper inside than the slab's front and back
        // faces lie from the mid-plane (0.025): until 26 Nov 2026 these
        // faces were the nearest surface there and capped phi at -0.025
        // (the negative control: this test on that code measured the area
        // 0.466873 against 0.47, the wall length 1.0456 against 1.04403,
        // the wall vector 0.0075 off the normal and centre distances up to
        // 0.0277 off)
        if (mesh.nSolutionD() < vector::nComponents)
        {
            const scalar y0 = 0.47, s = 0.3;
            const boundBox& bb = mesh.bounds();
            const scalar dz = bb.span().z();
            const scalar za = bb.min().z() + 1e-3*dz;
            const scalar zb = bb.max().z() - 1e-3*dz;
            pointField pts(8);
            label k = 0;
            for (const scalar x : {-1.0, 2.0})
            for (const scalar z : {za, zb})
            {
                pts[k++] = point(x, -1, z);
                pts[k++] = point(x, y0 + s*(x - 0.5), z);
            }
            const triSurface surf(hexSurface(pts));
            const triSurfaceSearch search(surf);
            immersedCutCells cut(mesh);
            cut.update(search, allCells);

            const scalar area = sum((1 - cut.fraction())*V)/dz;
            const vectorField Aw(wallVectors(cut));
            const vector n = vector(-s, 1, 0)/std::sqrt(1 + s*s);
            scalar length = 0, offNormal = 0, errD = 0;
            label nCut = 0;
            forAll(Aw, i)
            {
                length += mag(Aw[i])/dz;
                offNormal = max(offNormal, mag(Aw[i] - (Aw[i] & n)*n)/dz);
                if (cut.fraction()[i] > 0 && cut.fraction()[i] < 1)
                {
                    ++nCut;
                    const point& c = mesh.C()[i];
                    const scalar d =
                        (c.y() - y0 - s*(c.x() - 0.5))*n.y();
                    errD = max(errD, mag(cut.centreDistance(i) - d));
                }
            }
            Info<< "2D slab: " << nCut << " cut cells" << endl;
            check("2D slab: solid area in the square", area, y0, 1e-9,
                mag(area - y0) < 1e-9);
            check("2D slab: wall length", length, std::sqrt(1 + s*s), 1e-9,
                mag(length - std::sqrt(1 + s*s)) < 1e-9);
            check("2D slab: wall vector off the line's normal (largest)",
                offNormal, 0, 1e-12, offNormal < 1e-12);
            check("2D slab: cut cells' centre distance to the line (largest"
                " error)", errD, 0, 1e-12, errD < 1e-12);
        }
        else
        {
            // 2. A tilted plane z = z0 + s (x - 0.5) (the top of a large prism)
            //    through the box [0,1]^3: phi is linear in the box, so the cut
            //    geometry is exact to round-off. Solid volume in the box z0, wall
            //    area sqrt(1 + s^2), the wall normal n of the plane in every cell
            {
                const scalar z0 = 0.47, s = 0.3;
                const triSurface surf(tiltedPrism(z0, s));
                const triSurfaceSearch search(surf);
                immersedCutCells cut(mesh);
                cut.update(search, allCells);

                const scalar Vs = sum((1 - cut.fraction())*V);
                const vectorField Aw(wallVectors(cut));
                const vector n = vector(-s, 0, 1)/std::sqrt(1 + s*s);
                scalar area = 0, offNormal = 0;
                label nCut = 0;
                forAll(Aw, i)
                {
                    area += mag(Aw[i]);
                    offNormal = max(offNormal, mag(Aw[i] - (Aw[i] & n)*n));
                    if (cut.fraction()[i] > 0 && cut.fraction()[i] < 1) { ++nCut; }
                }
                Info<< "tilted plane: " << nCut << " cut cells" << endl;
                const scalar eAp = planarApertureError(cut);
                check("plane: aperture x S_f against the open area on the"
                    " triangular faces", eAp, 0, 1e-12, eAp < 1e-12);
                check("plane: solid volume in the box", Vs, z0, 1e-9,
                    mag(Vs - z0) < 1e-9);
                check("plane: wall area", area, std::sqrt(1 + s*s), 1e-9,
                    mag(area - std::sqrt(1 + s*s)) < 1e-9);
                check("plane: wall vector off the plane's normal (largest)",
                    offNormal, 0, 1e-12, offNormal < 1e-12);
            }

            // 3. Spheres (icospheres, 5 subdivisions) of radius 0.2 and 0.4
            //    (2 and 4 fluid cells): the solid volume and wall area against
            //    those of the faceted surface itself. Linear phi on a curved
            //    surface is second order: the errors must fall with (h/R)^2
            //    (order >= 1.5 from the two radii) and be within 2 % at R = 4 h.
            //    For comparison: the staircase of the cells whose centre is
            //    inside
            {
                scalarField eV(2), eA(2);
                const scalarList radii({0.2, 0.4});
                forAll(radii, r)
                {
                    const point c(0.5, 0.5, 0.5);
                    scalar Vsphere;
                    const triSurface surf(icosphere(c, radii[r], 5, Vsphere));
                    scalar Asphere = 0;
                    forAll(surf, i) { Asphere += surf[i].mag(surf.points()); }
                    const triSurfaceSearch search(surf);
                    immersedCutCells cut(mesh);
                    cut.update(search, allCells);
                    const scalar Vs = sum((1 - cut.fraction())*V);
                    const scalar area = sum(mag(wallVectors(cut)));
                    scalar Vstair = 0;
                    forAll(allCells, i)
                    {
                        if (cut.centreDistance(allCells[i]) < 0)
                        {
                            Vstair += V[i];
                        }
                    }
                    eV[r] = mag(Vs/Vsphere - 1);
                    eA[r] = mag(area/Asphere - 1);
                    Info<< "sphere R = " << radii[r] << ": solid volume " << Vs
                        << " against the faceted " << Vsphere << " (4/3 pi R^3 "
                        << 4.0/3*constant::mathematical::pi*pow3(radii[r])
                        << "), relative error " << eV[r] << "; wall area " << area
                        << " against " << Asphere << ", relative error " << eA[r]
                        << "; staircase of centres inside: volume error "
                        << mag(Vstair/Vsphere - 1) << endl;
                }
                const scalar orderV = std::log(eV[0]/eV[1])/std::log(2.0);
                const scalar orderA = std::log(eA[0]/eA[1])/std::log(2.0);
                check("sphere: order of the volume error", orderV, 2, 0.5,
                    orderV > 1.5);
                check("sphere: order of the wall area error", orderA, 2, 0.5,
                    orderA > 1.5);
                check("sphere R = 4 h: volume (relative error)", eV[1], 0, 0.02,
                    eV[1] < 0.02);
                check("sphere R = 4 h: wall area (relative error)", eA[1], 0,
                    0.02, eA[1] < 0.02);
            }
        }
    }
    else if (test == "wallInterp")
    {
        // The tilted plane z = z0 + s (x - 0.5), the top of a large prism
        // (the solid below it); the fluid cells whose centre is above it
        // are the candidates. The solid moves at u_s (its surface points'
        // velocity); the fluid's velocity u = u_s + g(dist) (1, 0.5, 0),
        // dist the distance of the centre to the plane. For g linear
        // (g = dist) Fadlun's value u_t = u_s + (u_N - u_s) d/(d + s) is
        // the cell's own velocity wherever the outer neighbour N lies
        // (dist_N = d + s exactly), so the forcing K (u_t - u) and its
        // reaction vanish; for g = dist^2 they do not (negative control).
        const scalar z0 = 0.47, sl = 0.3;
        const triSurface surf(tiltedPrism(z0, sl));
        const triSurfaceSearch search(surf);
        const vector n = vector(-sl, 0, 1)/std::sqrt(1 + sl*sl);
        auto dist = [&](const point& x)
        {
            return (x - point(0.5, 0, z0)) & n;
        };
        DynamicList<label> candidates;
        forAll(C, celli)
        {
            if (dist(C[celli]) > 0)
            {
                candidates.append(celli);
            }
        }
        immersedWallInterpolation wall(mesh);
        wall.update(search, identity(surf.points().size()), candidates);
        const labelList& cells = wall.cells();
        const vector us(0.2, -0.1, 0.05);
        wall.setVelocity(vectorField(surf.points().size(), us));
        Info<< "tilted plane: " << candidates.size() << " cells above it, "
            << cells.size() << " forcing cells" << endl;
        check("forcing cells found", cells.size(), 1, 0, cells.size() > 0);

        const scalarField A(mesh.nCells(), 1.0);
        const scalar KmaxByA = 49;
        for (const label power : {1, 2})
        {
            volVectorField U
            (
                IOobject("U", runTime.timeName(), mesh),
                mesh,
                dimensionedVector(dimVelocity, Zero)
            );
            forAll(C, celli)
            {
                U[celli] = us + pow(dist(C[celli]), power)*vector(1, 0.5, 0);
            }
            U.correctBoundaryConditions();
            fvVectorMatrix eqn(U, dimVelocity*dimVolume/dimTime);
            eqn.diag() = A;
            wall.constrain(eqn, A, KmaxByA);
            // the forcing's residual per cell: (A + K) u_c - K w u_N
            // - K (1 - w) u_s - A u_c = K (u_c - u_t), relative to K |u_c|
            const scalarField& diag = eqn.diag();
            const scalarField& lower = eqn.lower();
            const scalarField& upper = eqn.upper();
            const labelUList& l = mesh.lduAddr().lowerAddr();
            const labelUList& u = mesh.lduAddr().upperAddr();
            vectorField r(mesh.nCells(), Zero);
            forAll(r, celli)
            {
                r[celli] = (diag[celli] - A[celli])*U[celli]
                  - eqn.source()[celli];
            }
            forAll(l, facei)
            {
                r[l[facei]] += upper[facei]*U[u[facei]];
                r[u[facei]] += lower[facei]*U[l[facei]];
            }
            scalar err = 0;
            scalar Kmin = GREAT, Kmax = 0;
            forAll(cells, i)
            {
                const scalar K = wall.penalty()[i];
                Kmin = min(Kmin, K);
                Kmax = max(Kmax, K);
                err = max(err, mag(r[cells[i]])/max(K*mag(U[cells[i]]), VSMALL));
            }
            vectorField nodeForce(surf.points().size(), Zero);
            const vector F(wall.addForce(U, 1, nodeForce));
            const scalar eF = mag(F)/max(sum(wall.penalty())*mag(us), VSMALL);
            const scalar eSpread = mag(sum(nodeForce) - F)/max(mag(F), VSMALL);
            Info<< "  u - u_s = dist^" << power << ": K from " << Kmin
                << " to " << Kmax << " A, reaction " << F << endl;
            if (power == 1)
            {
                check("linear: largest |K (u - u_t)|/(K |u|) of a forcing cell",
                    err, 0, 1e-12, err < 1e-12);
                check("linear: |reaction|/(sum K |u_s|)", eF, 0, 1e-12,
                    eF < 1e-12);
                check("penalty within (0, 49 A]", Kmax, KmaxByA, 0,
                    Kmin > 0 && Kmax <= KmaxByA*(1 + 1e-12));
            }
            else
            {
                check("negative control, quadratic: largest |K (u - u_t)|/"
                    "(K |u|) (must exceed 1e-3)", err, 1e-3, 0, err > 1e-3);
                check("quadratic: the reaction's spread to the nodes keeps"
                    " its total", eSpread, 0, 1e-12, eSpread < 1e-12);
            }
        }
    }
    else if (test == "wallPoints")
    {
        // cellTetTransfer's wall points (immersedElasticForce's wallPoints)
        // in the unit cube, every side a wall:
        // (A) points at a small distance d from the wall x = 0, each in
        // the tet of a wall face of its cell, sample u = x (0.3, 1, -0.5),
        // which vanishes on that wall: with noSlip the tet interpolates
        // between the cell centre and zero on the wall, exact for u
        // (u(x) = x/x_c u_c = w_0 u_c); with slip only the normal (x)
        // component is; with free neither (the wall points carry the
        // cells' mean: the negative control);
        // (B) random cell values and point forces: spread is gather's
        // transpose in the cells' mass inner product, sum_i F_i . v_i =
        // rho sum_c V_c s_c . u_c, for every condition (the noSlip gather
        // against the free spread is not: the control)
        const scalar rho = 1000.0;
        const scalar d = 1e-4;
        const vector c(0.3, 1, -0.5);
        Random rnd(1234);
        const label nNear = 60, nInside = 200;
        pointField x(nNear + nInside);
        forAll(x, i)
        {
            x[i] =
                i < nNear
              ? point(d, 0.15 + 0.7*rnd.sample01<scalar>(),
                    0.15 + 0.7*rnd.sample01<scalar>())
              : point(0.05 + 0.9*rnd.sample01<scalar>(),
                    0.05 + 0.9*rnd.sample01<scalar>(),
                    0.05 + 0.9*rnd.sample01<scalar>());
        }
        // each point in one rank's cell
        labelList cellOf(x.size(), -1);
        labelList owner(x.size(), -1);
        forAll(x, i)
        {
            cellOf[i] = mesh.findCell(x[i]);
            if (cellOf[i] >= 0)
            {
                owner[i] = Pstream::myProcNo();
            }
        }
        Pstream::listCombineGather(owner, maxEqOp<label>());
        Pstream::listCombineScatter(owner);
        // (A)'s points: in the tet of a wall face on x = 0 of their cell,
        // the foot of the perpendicular at least 10 d inside the triangle
        boolList nearWall(x.size(), false);
        forAll(x, i)
        {
            if (owner[i] != Pstream::myProcNo())
            {
                cellOf[i] = -1;
                continue;
            }
            if (i >= nNear)
            {
                continue;
            }
            for (const label facei : mesh.cells()[cellOf[i]])
            {
                if (mesh.isInternalFace(facei))
                {
                    continue;
                }
                const face& f = mesh.faces()[facei];
                const pointField& P = mesh.points();
                bool onWall = (f.size() == 3);
                for (const label pi : f)
                {
                    onWall = onWall && mag(P[pi].x()) < SMALL;
                }
                if (!onWall)
                {
                    continue;
                }
                // barycentric coordinates of (y, z) in the triangle
                const vector2D a(P[f[0]].y(), P[f[0]].z());
                const vector2D b(P[f[1]].y(), P[f[1]].z());
                const vector2D e(P[f[2]].y(), P[f[2]].z());
                const vector2D q(x[i].y(), x[i].z());
                const scalar det =
                    (b.x() - a.x())*(e.y() - a.y())
                  - (e.x() - a.x())*(b.y() - a.y());
                const scalar l1 =
                    ((q.x() - a.x())*(e.y() - a.y())
                  - (e.x() - a.x())*(q.y() - a.y()))/det;
                const scalar l2 =
                    ((b.x() - a.x())*(q.y() - a.y())
                  - (q.x() - a.x())*(b.y() - a.y()))/det;
                // 10 d from every edge (the edges are about 0.1 long)
                const scalar margin = 10*d/0.1;
                if (l1 > margin && l2 > margin && 1 - l1 - l2 > margin)
                {
                    nearWall[i] = true;
                }
            }
        }
        label nOwned = 0, nWallTets = 0;
        forAll(x, i)
        {
            nOwned += (owner[i] >= 0);
            nWallTets += nearWall[i];
        }
        reduce(nWallTets, sumOp<label>());
        check("points held by a rank", nOwned, x.size(), 0,
            nOwned == x.size());
        check("points near x = 0 in a wall face's tet (at least 20)",
            nWallTets, nNear, nNear - 20, nWallTets >= 20);

        const vectorField& C = mesh.C();
        vectorField uLinear(mesh.nCells());
        forAll(uLinear, celli)
        {
            uLinear[celli] = C[celli].x()*c;
        }
        vectorField uRandom(mesh.nCells());
        forAll(uRandom, celli)
        {
            // a smooth field, the same on any decomposition
            const point& y = C[celli];
            uRandom[celli] = vector
            (
                Foam::sin(7*y.x() + 3*y.y()), Foam::cos(5*y.y() - 2*y.z()),
                Foam::sin(4*y.z() + 6*y.x() + 1)
            );
        }
        vectorField F(x.size());
        forAll(F, i)
        {
            F[i] = vector
            (
                Foam::sin(11*x[i].x() + 2*x[i].z()),
                Foam::cos(3*x[i].y() + 5*x[i].x()),
                Foam::sin(9*x[i].z() - 4*x[i].y() + 0.5)
            );
        }

        typedef cellTetTransfer::wallCondition wallCondition;
        auto makeTransfer = [&](cellTetTransfer& t, const wallCondition w)
        {
            t.setSize(x.size());
            // every cell centre its own value (no sliver rule): (A)'s
            // tets interpolate the cell's own value
            t.setPointData(0);
            forAll(x, i)
            {
                t.setCell(i, cellOf[i]);
                if (cellOf[i] >= 0)
                {
                    t.setWeights(i, x[i]);
                }
            }
            return t.setWallPoints(w);
        };
        // the transpose: sum_i F_i . v_i against rho sum_c V_c s_c . u_c
        auto asymmetry = [&]
        (
            const cellTetTransfer& gatherWith,
            const cellTetTransfer& spreadWith
        )
        {
            const vectorField v(gatherWith.gather(uRandom));
            vectorField s;
            spreadWith.spread(F, rho, s);
            scalar solid = 0, scale = 0;
            forAll(F, i)
            {
                solid += F[i] & v[i];
                scale += mag(F[i])*mag(v[i]);
            }
            scalar fluid = 0;
            forAll(s, celli)
            {
                fluid += rho*mesh.V()[celli]*(s[celli] & uRandom[celli]);
            }
            reduce(fluid, sumOp<scalar>());
            return mag(solid - fluid)/scale;
        };

        cellTetTransfer freeT(mesh), slipT(mesh), noSlipT(mesh);
        const label nWall = makeTransfer(freeT, wallCondition::free);
        makeTransfer(slipT, wallCondition::slip);
        const label nWallPoints = makeTransfer(noSlipT, wallCondition::noSlip);
        // the cube's boundary points (gmsh: every boundary point on a wall)
        label nBoundary = 0;
        {
            const bitSet master(syncTools::getMasterPoints(mesh));
            const labelList& bp = mesh.boundaryMesh()["walls"].meshPoints();
            for (const label pi : bp)
            {
                nBoundary += master.test(pi);
            }
            reduce(nBoundary, sumOp<label>());
        }
        Info<< "wall points: " << nWallPoints << " (the walls' points "
            << nBoundary << "); free: " << nWall << endl;
        check("wall points counted once", nWallPoints, nBoundary, 0,
            nWallPoints == nBoundary && nWall == 0);

        // (A): the largest error on the near-wall points over d |c|
        auto nearError = [&](const cellTetTransfer& t, const bool normalOnly)
        {
            const vectorField v(t.gather(uLinear));
            scalar err = 0;
            forAll(x, i)
            {
                label held = nearWall[i];
                reduce(held, sumOp<label>());
                if (!held)
                {
                    continue;
                }
                const vector exact(x[i].x()*c);
                err = max
                (
                    err,
                    normalOnly
                  ? mag(v[i].x() - exact.x())
                  : mag(v[i] - exact)
                );
            }
            return err/(d*mag(c));
        };
        const scalar errNoSlip = nearError(noSlipT, false);
        const scalar errSlipNormal = nearError(slipT, true);
        const scalar errSlip = nearError(slipT, false);
        const scalar errFree = nearError(freeT, false);
        const scalar errFreeNormal = nearError(freeT, true);
        Info<< "(A) u = x c at " << d << " from the wall, error / (d |c|):"
            << endl;
        check("noSlip: u", errNoSlip, 0, 1e-8, errNoSlip < 1e-8);
        check("slip: u's normal component", errSlipNormal, 0, 1e-8,
            errSlipNormal < 1e-8);
        check("slip: u (tangential kept: must exceed 1)", errSlip, 0, 1,
            errSlip > 1);
        check("free: u (negative control: must exceed 1)", errFree, 0, 1,
            errFree > 1);
        check("free: u's normal component (control: must exceed 1)",
            errFreeNormal, 0, 1, errFreeNormal > 1);

        Info<< "(B) |sum F.v - rho sum V s.u| / sum |F||v|:" << endl;
        const scalar aFree = asymmetry(freeT, freeT);
        const scalar aSlip = asymmetry(slipT, slipT);
        const scalar aNoSlip = asymmetry(noSlipT, noSlipT);
        const scalar aControl = asymmetry(noSlipT, freeT);
        check("free: transpose", aFree, 0, 1e-12, aFree < 1e-12);
        check("slip: transpose", aSlip, 0, 1e-12, aSlip < 1e-12);
        check("noSlip: transpose", aNoSlip, 0, 1e-12, aNoSlip < 1e-12);
        check("noSlip gather, free spread (control: must exceed 1e-3)",
            aControl, 0, 1e-3, aControl > 1e-3);
    }
    else if (test == "outside")
    {
        immersedPairs pairs(mesh, couplingDict);
        const vector shift(args.get<vector>("shift"));
        pairs.findNodeCells(solid.points0() + shift);
        FatalErrorInFunction
            << "FAIL: no error for a solid outside the domain"
            << exit(FatalError);
    }
    else
    {
        FatalErrorInFunction
            << "Unknown -test " << test << exit(FatalError);
    }

    // argList's destructor ends the process with status 0 (UPstream::exit),
    // whatever main returns: a failed check must exit through FatalError
    if (!allPassed)
    {
        FatalErrorInFunction
            << "SOME FAILED: see the FAIL lines above" << exit(FatalError);
    }
    Info<< nl << "ALL PASS" << endl;
    return 0;
}


// ************************************************************************* //
