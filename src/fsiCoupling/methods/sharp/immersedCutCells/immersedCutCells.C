/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedCutCells.H"
#include "triSurfaceTools.H"

// * * * * * * * * * * * * * * * Static Functions  * * * * * * * * * * * * * //

template<class Type>
const Type& Foam::immersedCutCells::find
(
    const Map<Type>& values,
    const label key,
    const char* what,
    const char* of
)
{
    const auto iter = values.cfind(key);
    if (!iter.found())
    {
        FatalErrorInFunction
            << what << ' ' << key << " is not " << of << " of the cut cells"
            << " (immersedCutCells::update did not list it)"
            << abort(FatalError);
    }
    return *iter;
}


Foam::scalar Foam::immersedCutCells::triangleFraction
(
    const FixedList<scalar, 3>& phi
)
{
    label nPos = 0;
    for (const scalar v : phi)
    {
        if (v > 0) { ++nPos; }
    }
    if (nPos == 0) { return 0; }
    if (nPos == 3) { return 1; }

    // the vertex alone on its side (positive if nPos == 1, else negative):
    // the part on its side is a triangle similar to the whole, of area
    // fraction t_1 t_2, t_k = phi_a/(phi_a - phi_k) along its two edges
    const bool alonePositive = (nPos == 1);
    label a = 0;
    for (label k = 0; k < 3; ++k)
    {
        if ((phi[k] > 0) == alonePositive) { a = k; }
    }
    const scalar pa = phi[a];
    const scalar pb = phi[(a + 1) % 3];
    const scalar pc = phi[(a + 2) % 3];
    const scalar f = sqr(pa)/((pa - pb)*(pa - pc));
    return alonePositive ? f : 1 - f;
}


Foam::scalar Foam::immersedCutCells::tetFraction
(
    const FixedList<scalar, 4>& phi
)
{
    label nPos = 0;
    for (const scalar v : phi)
    {
        if (v > 0) { ++nPos; }
    }
    if (nPos == 0) { return 0; }
    if (nPos == 4) { return 1; }

    if (nPos != 2)
    {
        // one vertex alone on its side: a tetrahedron of volume fraction
        // t_1 t_2 t_3 along its three edges
        const bool alonePositive = (nPos == 1);
        label a = 0;
        for (label k = 0; k < 4; ++k)
        {
            if ((phi[k] > 0) == alonePositive) { a = k; }
        }
        const scalar pa = phi[a];
        scalar f = 1;
        for (label k = 0; k < 4; ++k)
        {
            if (k != a) { f *= pa/(pa - phi[k]); }
        }
        return alonePositive ? f : 1 - f;
    }

    // two of each sign: the positive part is a wedge with the positive
    // vertices i, j and the crossings on the edges to the negative k, l;
    // measured in the reference tetrahedron (volume 1/6) as three
    // tetrahedra (A0 A1 A2 B2), (A0 A1 B1 B2), (A0 B0 B1 B2) with
    // A = (x_i, x_ik, x_il), B = (x_j, x_jk, x_jl) (its faces are planar:
    // the decomposition is exact)
    static const FixedList<vector, 4> e
    ({
        vector(0, 0, 0), vector(1, 0, 0), vector(0, 1, 0), vector(0, 0, 1)
    });
    label pos[2], neg[2];
    label np = 0, nn = 0;
    for (label k = 0; k < 4; ++k)
    {
        if (phi[k] > 0) { pos[np++] = k; } else { neg[nn++] = k; }
    }
    auto crossing = [&](const label p, const label n)
    {
        const scalar t = phi[p]/(phi[p] - phi[n]);
        return e[p] + t*(e[n] - e[p]);
    };
    const vector A0 = e[pos[0]];
    const vector A1 = crossing(pos[0], neg[0]);
    const vector A2 = crossing(pos[0], neg[1]);
    const vector B0 = e[pos[1]];
    const vector B1 = crossing(pos[1], neg[0]);
    const vector B2 = crossing(pos[1], neg[1]);
    auto det = [](const vector& a, const vector& b, const vector& c,
                  const vector& d)
    {
        return mag((b - a) & ((c - a) ^ (d - a)));
    };
    // sum of |det| = 6 x volume = fraction of the reference volume 1/6
    return min
    (
        det(A0, A1, A2, B2) + det(A0, A1, B1, B2) + det(A0, B0, B1, B2),
        scalar(1)
    );
}


Foam::tmp<Foam::scalarField> Foam::immersedCutCells::signedDistance
(
    const triSurfaceSearch& surface,
    const triSurfaceSearch& distanceSurface,
    const pointField& samples,
    const scalarField& radiusSqr
)
{
    List<pointIndexHit> nearest;
    distanceSurface.findNearest(samples, radiusSqr, nearest);

    // The sign: where the nearest point was found, from the side of its
    // face, edge or point (triSurfaceTools::surfaceSide, what the octree's
    // volume type does after a nearest search of its own); elsewhere from
    // the octree (calcInside). The in-plane triangles of a 2D case are
    // the closed surface's own, with its orientation.
    boolList inside(samples.size(), false);
    DynamicList<label> misses;
    forAll(samples, i)
    {
        if (nearest[i].hit())
        {
            inside[i] =
                triSurfaceTools::surfaceSide
                (
                    distanceSurface.surface(),
                    samples[i],
                    nearest[i].index()
                )
             == triSurfaceTools::INSIDE;
        }
        else
        {
            misses.append(i);
        }
    }
    if (misses.size())
    {
        const boolList missInside
        (
            surface.calcInside(pointField(samples, misses))
        );
        forAll(misses, j)
        {
            inside[misses[j]] = missInside[j];
        }
    }

    tmp<scalarField> tphi(new scalarField(samples.size()));
    scalarField& phi = tphi.ref();
    forAll(samples, i)
    {
        // beyond the radius: the sign, with the radius as its magnitude
        // (update: only the samples of cells whole on one side of the
        // surface are searched no further, and those cells' fractions
        // and apertures depend on the sign alone)
        const scalar d =
            nearest[i].hit()
          ? mag(nearest[i].hitPoint() - samples[i])
          : Foam::sqrt(radiusSqr[i]);
        phi[i] = inside[i] ? -d : d;
    }
    return tphi;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedCutCells::immersedCutCells(const fvMesh& mesh)
:
    mesh_(mesh)
{}


// * * * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * //

Foam::vector Foam::immersedCutCells::faceOpenArea(const label facei) const
{
    const face& f = mesh_.faces()[facei];
    const pointField& pts = mesh_.points();
    const point& fc = mesh_.faceCentres()[facei];
    const scalar pc = facePhi_[facei];

    // the face's triangles as OpenFOAM's face area (face centre - edge)
    vector open(Zero);
    forAll(f, i)
    {
        const label a = f[i];
        const label b = f.nextLabel(i);
        open +=
            0.5*((pts[a] - fc) ^ (pts[b] - fc))
           *triangleFraction({pc, pointPhi_[a], pointPhi_[b]});
    }
    return open;
}


Foam::scalar Foam::immersedCutCells::cellFraction(const label celli) const
{
    const pointField& pts = mesh_.points();
    const point& cc = mesh_.cellCentres()[celli];
    const scalar pcc = cellPhi_[celli];

    scalar volume = 0, fluid = 0;
    for (const label facei : mesh_.cells()[celli])
    {
        const face& f = mesh_.faces()[facei];
        const point& fc = mesh_.faceCentres()[facei];
        const scalar pfc = facePhi_[facei];
        forAll(f, i)
        {
            const label a = f[i];
            const label b = f.nextLabel(i);
            const scalar V =
                mag((fc - cc) & ((pts[a] - cc) ^ (pts[b] - cc)))/6;
            volume += V;
            fluid += V*tetFraction({pcc, pfc, pointPhi_[a], pointPhi_[b]});
        }
    }
    return volume > VSMALL ? fluid/volume : 0;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::point Foam::immersedCutCells::onPlane(point x) const
{
    // in a 2D case (empty front and back): x moved to the mid-plane
    const Vector<label>& solD = mesh_.solutionD();
    const point mid(mesh_.bounds().midpoint());
    for (direction d = 0; d < vector::nComponents; ++d)
    {
        if (solD[d] < 0) { x[d] = mid[d]; }
    }
    return x;
}


Foam::autoPtr<Foam::triSurface> Foam::immersedCutCells::inPlaneSides
(
    const triSurface& tris
) const
{
    // a 2D case: the triangles whose normal is within 30 degrees of the
    // plane (a slab spanning the depth: its faces facing the empty
    // patches, dz/2 from the mid-plane, would otherwise be the nearest
    // surface of any sample deeper inside than that, and cap phi there)
    const Vector<label>& solD = mesh_.solutionD();
    const vectorField& n = tris.faceNormals();
    DynamicList<labelledTri> inPlane(tris.size());
    forAll(tris, facei)
    {
        scalar out = 0;
        for (direction d = 0; d < vector::nComponents; ++d)
        {
            if (solD[d] < 0) { out += sqr(n[facei][d]); }
        }
        if (out < 0.25)
        {
            inPlane.append(tris[facei]);
        }
    }
    return autoPtr<triSurface>
    (
        new triSurface(List<labelledTri>(inPlane), tris.points())
    );
}


void Foam::immersedCutCells::sampleNearCells
(
    const triSurfaceSearch& surface,
    const triSurfaceSearch& distance,
    const pointField& centres,
    const scalarField& reachSqr,
    const scalarField& centrePhi,
    DynamicList<label>& faceLabels
)
{
    // The samples of the cells near the surface: their points, face
    // centres and centres (each once), each searched within the largest
    // 2 r of the near cells it belongs to
    const pointField& pts = mesh_.points();
    Map<label> pointSample, faceSample;
    DynamicList<label> pointLabels, nearCells;
    DynamicList<scalar> pointR2, faceR2;
    auto add = [](Map<label>& index, DynamicList<label>& labels,
                  DynamicList<scalar>& r2, const label key, const scalar r)
    {
        const auto iter = index.cfind(key);
        if (iter.found())
        {
            r2[*iter] = max(r2[*iter], r);
        }
        else
        {
            index.insert(key, labels.size());
            labels.append(key);
            r2.append(r);
        }
    };
    forAll(cells_, i)
    {
        if (mag(centrePhi[i]) >= Foam::sqrt(reachSqr[i]))
        {
            continue;   // whole on one side
        }
        nearCells.append(i);
        const scalar r2 = 4*reachSqr[i];
        for (const label facei : mesh_.cells()[cells_[i]])
        {
            add(faceSample, faceLabels, faceR2, facei, r2);
            for (const label pointi : mesh_.faces()[facei])
            {
                add(pointSample, pointLabels, pointR2, pointi, r2);
            }
        }
    }
    pointField samples
    (
        pointLabels.size() + faceLabels.size() + nearCells.size()
    );
    scalarField radiusSqr(samples.size());
    label k = 0;
    forAll(pointLabels, j)
    {
        radiusSqr[k] = pointR2[j];
        samples[k++] = onPlane(pts[pointLabels[j]]);
    }
    forAll(faceLabels, j)
    {
        radiusSqr[k] = faceR2[j];
        samples[k++] = onPlane(mesh_.faceCentres()[faceLabels[j]]);
    }
    for (const label i : nearCells)
    {
        radiusSqr[k] = 4*reachSqr[i];
        samples[k++] = centres[i];
    }
    const scalarField phi
    (
        signedDistance(surface, distance, samples, radiusSqr)
    );
    k = 0;
    for (const label pointi : pointLabels) { pointPhi_.set(pointi, phi[k++]); }
    for (const label facei : faceLabels) { facePhi_.set(facei, phi[k++]); }
    for (const label i : nearCells) { cellPhi_.set(cells_[i], phi[k++]); }
}


void Foam::immersedCutCells::fillFarCells
(
    const scalarField& centrePhi,
    DynamicList<label>& faceLabels
)
{
    // The cells whole on one side: phi of the centre's sign, the reach as
    // its magnitude, where no near cell gave an exact value
    forAll(cells_, i)
    {
        const label celli = cells_[i];
        if (cellPhi_.found(celli))
        {
            continue;
        }
        const scalar p = centrePhi[i];
        cellPhi_.set(celli, p);
        for (const label facei : mesh_.cells()[celli])
        {
            if (facePhi_.insert(facei, p))
            {
                faceLabels.append(facei);
            }
            for (const label pointi : mesh_.faces()[facei])
            {
                pointPhi_.insert(pointi, p);
            }
        }
    }
}


void Foam::immersedCutCells::update
(
    const triSurfaceSearch& surface,
    const labelUList& cells
)
{
    cells_ = cells;
    pointPhi_.clear();
    facePhi_.clear();
    cellPhi_.clear();
    aperture_.clear();
    openArea_.clear();

    // a 2D case (empty front and back): the samples on the mid-plane, and
    // the distance to the solid's in-plane surface only (the sign still
    // comes from the whole closed surface)
    const bool twoD = mesh_.nSolutionD() < vector::nComponents;
    autoPtr<triSurface> sides;
    autoPtr<triSurfaceSearch> sideSearch;
    if (twoD)
    {
        sides = inPlaneSides(surface.surface());
        sideSearch.reset(new triSurfaceSearch(sides()));
    }
    const triSurfaceSearch& distance = twoD ? sideSearch() : surface;

    // Which cells the surface passes near: a cell whose centre has no
    // surface point within its reach r (the largest distance of its
    // points from its centre, in the plane in 2D) lies whole on one side,
    // its fraction 0 or 1 and its faces' apertures too, whatever the
    // magnitude of phi. The samples of the other cells are searched
    // within 2 r, which holds their nearest surface point (within r of
    // the centre, so within 2 r of any point of the cell): exact. Most
    // covered cells of a thick solid are far from its surface, and the
    // unbounded search of their samples was most of the cost (Turek-Hron
    // FSI1, N = 24, -refine 2: a quarter of the coupled run).
    const pointField& pts = mesh_.points();
    const vectorField& Cc = mesh_.cellCentres();
    const labelListList& cellPoints = mesh_.cellPoints();
    scalarField reachSqr(cells_.size(), 0);
    pointField centres(cells_.size());
    forAll(cells_, i)
    {
        const label celli = cells_[i];
        centres[i] = onPlane(Cc[celli]);
        for (const label pointi : cellPoints[celli])
        {
            reachSqr[i] =
                max(reachSqr[i], magSqr(onPlane(pts[pointi]) - centres[i]));
        }
        reachSqr[i] *= 1 + 1e-6;
    }
    const scalarField centrePhi
    (
        signedDistance(surface, distance, centres, reachSqr)
    );

    DynamicList<label> faceLabels;
    sampleNearCells(surface, distance, centres, reachSqr, centrePhi, faceLabels);
    fillFarCells(centrePhi, faceLabels);

    for (const label facei : faceLabels)
    {
        const vector open(faceOpenArea(facei));
        const vector& Sf = mesh_.faceAreas()[facei];
        openArea_.set(facei, open);
        aperture_.set
        (
            facei,
            min(max((open & Sf)/max(magSqr(Sf), VSMALL), scalar(0)), scalar(1))
        );
    }
    fraction_.setSize(cells_.size());
    forAll(cells_, i)
    {
        fraction_[i] = cellFraction(cells_[i]);
    }
}


Foam::scalar Foam::immersedCutCells::aperture(const label facei) const
{
    return find(aperture_, facei, "face", "a face");
}


Foam::vector Foam::immersedCutCells::openArea(const label facei) const
{
    return find(openArea_, facei, "face", "a face");
}


Foam::scalar Foam::immersedCutCells::centreDistance(const label celli) const
{
    return find(cellPhi_, celli, "cell", "one");
}


// ************************************************************************* //
