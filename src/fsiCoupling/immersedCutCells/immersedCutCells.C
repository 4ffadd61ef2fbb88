/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedCutCells.H"

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
    const pointField& samples
)
{
    List<pointIndexHit> nearest;
    surface.findNearest(samples, scalarField(samples.size(), GREAT), nearest);
    const boolList inside(surface.calcInside(samples));

    tmp<scalarField> tphi(new scalarField(samples.size()));
    scalarField& phi = tphi.ref();
    forAll(samples, i)
    {
        const scalar d =
            nearest[i].hit() ? mag(nearest[i].hitPoint() - samples[i]) : GREAT;
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

    // the samples: points, face centres, cell centres (each once)
    DynamicList<point> samples;
    DynamicList<label> pointLabels, faceLabels;
    for (const label celli : cells_)
    {
        for (const label facei : mesh_.cells()[celli])
        {
            if (facePhi_.insert(facei, 0))
            {
                faceLabels.append(facei);
                for (const label pointi : mesh_.faces()[facei])
                {
                    if (pointPhi_.insert(pointi, 0))
                    {
                        pointLabels.append(pointi);
                    }
                }
            }
        }
    }
    samples.append(UIndirectList<point>(mesh_.points(), pointLabels)());
    samples.append(UIndirectList<point>(mesh_.faceCentres(), faceLabels)());
    samples.append(UIndirectList<point>(mesh_.cellCentres(), cells_)());

    // a 2D case (empty front and back): the samples on the mid-plane, so
    // that the solid's surfaces facing the empty patches (a slab spanning
    // the depth) do not count
    const Vector<label>& solD = mesh_.solutionD();
    const point mid(mesh_.bounds().midpoint());
    for (direction d = 0; d < vector::nComponents; ++d)
    {
        if (solD[d] < 0)
        {
            for (point& x : samples)
            {
                x[d] = mid[d];
            }
        }
    }
    const scalarField phi(signedDistance(surface, pointField(samples)));
    label k = 0;
    for (const label pointi : pointLabels) { pointPhi_.set(pointi, phi[k++]); }
    for (const label facei : faceLabels) { facePhi_.set(facei, phi[k++]); }
    for (const label celli : cells_) { cellPhi_.set(celli, phi[k++]); }

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
