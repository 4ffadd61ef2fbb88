/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedWallInterpolation.H"
#include "fvMatrices.H"
#include "triSurface.H"
#include "triangle.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedWallInterpolation::immersedWallInterpolation(const fvMesh& mesh)
:
    mesh_(mesh)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedWallInterpolation::clear()
{
    cells_.clear();
    distance_.clear();
    area_.clear();
    nodes_.clear();
    weights_.clear();
    velocity_.clear();
    penalty_.clear();
}


void Foam::immersedWallInterpolation::update
(
    const triSurfaceSearch& surface,
    const labelUList& surfacePoints,
    const labelUList& candidates
)
{
    const vectorField& C = mesh_.C();
    const vectorField& Sf = mesh_.faceAreas();
    const scalarField& V = mesh_.V();
    const triSurface& tris = surface.surface();
    const pointField& sp = tris.points();

    // nearest surface points within twice the cell's reach (the largest
    // distance of its points from its centre)
    const pointField samples(C, candidates);
    scalarField span(candidates.size(), 0);
    forAll(candidates, i)
    {
        for (const label pointi : mesh_.cellPoints()[candidates[i]])
        {
            span[i] = max(span[i], magSqr(mesh_.points()[pointi] - C[candidates[i]]));
        }
    }
    List<pointIndexHit> nearest;
    surface.findNearest(samples, 4*span, nearest);

    DynamicList<label> cells(candidates.size());
    DynamicList<scalar> distance(candidates.size());
    DynamicList<scalar> area(candidates.size());
    DynamicList<FixedList<label, 3>> nodes(candidates.size());
    DynamicList<FixedList<scalar, 3>> weights(candidates.size());
    forAll(candidates, i)
    {
        if (!nearest[i].hit())
        {
            continue;
        }
        const label celli = candidates[i];
        const labelledTri& t = tris[nearest[i].index()];
        const triPointRef tri(sp[t[0]], sp[t[1]], sp[t[2]]);
        const point& p = nearest[i].hitPoint();
        const vector r(C[celli] - p);
        const scalar d = mag(r);
        // n from the surface to the centre (the triangle's normal where
        // the centre is on the surface)
        const vector n
        (
            d > SMALL*sqrt(span[i]) ? r/d : tri.normal()/max(mag(tri.normal()), VSMALL)
        );
        scalar G = 0;
        for (const label facei : mesh_.cells()[celli])
        {
            G += 0.5*mag(Sf[facei] & n);
        }
        // forcing only within the cell's width along n, h_n = V/G
        if (G <= VSMALL || d >= V[celli]/G)
        {
            continue;
        }
        const barycentric2D b(tri.pointToBarycentric(p));
        FixedList<scalar, 3> w;
        scalar sum = 0;
        for (label k = 0; k < 3; ++k)
        {
            w[k] = min(max(b[k], 0.0), 1.0);
            sum += w[k];
        }
        FixedList<label, 3> nd;
        for (label k = 0; k < 3; ++k)
        {
            w[k] /= max(sum, VSMALL);
            nd[k] = surfacePoints[t[k]];
        }
        cells.append(celli);
        distance.append(d);
        area.append(G);
        nodes.append(nd);
        weights.append(w);
    }
    cells_.transfer(cells);
    distance_.transfer(distance);
    area_.transfer(area);
    nodes_.transfer(nodes);
    weights_.transfer(weights);
    velocity_.setSize(cells_.size(), Zero);
    penalty_.setSize(cells_.size(), 0);
}


void Foam::immersedWallInterpolation::setVelocity
(
    const vectorField& nodeVelocities
)
{
    forAll(cells_, i)
    {
        velocity_[i] = Zero;
        for (label k = 0; k < 3; ++k)
        {
            velocity_[i] += weights_[i][k]*nodeVelocities[nodes_[i][k]];
        }
    }
}


void Foam::immersedWallInterpolation::constrain
(
    fvMatrix<vector>& eqn,
    const scalarField& nu,
    const scalarField& Kmax
)
{
    scalarField& diag = eqn.diag();
    Field<vector>& source = eqn.source();
    const scalarField& V = mesh_.V();
    penalty_.setSize(cells_.size());
    forAll(cells_, i)
    {
        const label celli = cells_[i];
        // K = (h_n/d - 1) D_n, h_n = V/G, D_n = nu G/h_n = nu G^2/V
        // (class description; Fadlun et al. 2000's interpolation)
        const scalar G = area_[i];
        const scalar hn = V[celli]/G;
        const scalar Dn = nu[celli]*G*G/V[celli];
        const scalar K =
            distance_[i] > 0
          ? min((hn/distance_[i] - 1)*Dn, Kmax[celli])
          : Kmax[celli];
        penalty_[i] = K;
        diag[celli] += K;
        source[celli] += K*velocity_[i];
    }
}


Foam::vector Foam::immersedWallInterpolation::addForce
(
    const volVectorField& U,
    const scalar rho,
    vectorField& nodeForce
) const
{
    vector total(Zero);
    forAll(cells_, i)
    {
        const scalar K = i < penalty_.size() ? penalty_[i] : 0;
        const vector F(rho*K*(U[cells_[i]] - velocity_[i]));
        for (label k = 0; k < 3; ++k)
        {
            nodeForce[nodes_[i][k]] += weights_[i][k]*F;
        }
        total += F;
    }
    return total;
}


// ************************************************************************* //
