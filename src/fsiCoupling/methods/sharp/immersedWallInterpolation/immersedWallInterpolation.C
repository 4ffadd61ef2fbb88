/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedWallInterpolation.H"
#include "fvMatrices.H"
#include "triSurface.H"
#include "triangle.H"
#include "volFields.H"

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
    face_.clear();
    weight_.clear();
    velocity_.clear();
    penalty_.clear();
}


Foam::scalarField Foam::immersedWallInterpolation::reachSqr
(
    const labelUList& cells
) const
{
    // the largest squared distance of each cell's points from its centre
    const vectorField& C = mesh_.C();
    scalarField span(cells.size(), 0);
    forAll(cells, i)
    {
        for (const label pointi : mesh_.cellPoints()[cells[i]])
        {
            span[i] = max(span[i], magSqr(mesh_.points()[pointi] - C[cells[i]]));
        }
    }
    return span;
}


Foam::label Foam::immersedWallInterpolation::outerNeighbour
(
    const label celli,
    const vector& n,
    PtrList<vectorField>& deltas,
    scalar& s
) const
{
    // the outer neighbour N: the face neighbour whose centre lies most
    // nearly along n (a coupled face's neighbour across it: fvPatch::delta
    // is the vector between the two cells' centres there, made as needed
    // in deltas); its face, -1 if none; s: the centres' distance along n
    const vectorField& C = mesh_.C();
    const labelUList& own = mesh_.faceOwner();
    const labelUList& nei = mesh_.faceNeighbour();
    const polyBoundaryMesh& patches = mesh_.boundaryMesh();
    label best = -1;
    scalar bestCos = 0;
    s = 0;
    for (const label facei : mesh_.cells()[celli])
    {
        vector delta;
        if (mesh_.isInternalFace(facei))
        {
            const label other = own[facei] == celli ? nei[facei] : own[facei];
            delta = C[other] - C[celli];
        }
        else
        {
            const label patchi = patches.whichPatch(facei);
            if (!patches[patchi].coupled())
            {
                continue;
            }
            if (!deltas.set(patchi))
            {
                deltas.set(patchi, mesh_.boundary()[patchi].delta().ptr());
            }
            delta = deltas[patchi][facei - patches[patchi].start()];
        }
        const scalar sf = delta & n;
        const scalar c = sf/max(mag(delta), VSMALL);
        if (sf > 0 && c > bestCos)
        {
            best = facei;
            bestCos = c;
            s = sf;
        }
    }
    return best;
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
    const scalarField span(reachSqr(candidates));
    List<pointIndexHit> nearest;
    surface.findNearest(samples, 4*span, nearest);

    DynamicList<label> cells(candidates.size());
    DynamicList<scalar> distance(candidates.size());
    DynamicList<scalar> area(candidates.size());
    DynamicList<FixedList<label, 3>> nodes(candidates.size());
    DynamicList<FixedList<scalar, 3>> weights(candidates.size());
    DynamicList<label> faces(candidates.size());
    DynamicList<scalar> weightN(candidates.size());
    // the coupled patches' cell-to-cell vectors (fvPatch::delta), as needed
    PtrList<vectorField> deltas(mesh_.boundaryMesh().size());
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
        // the nearest point's weights on its triangle's solid nodes
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
        scalar s = 0;
        const label best = outerNeighbour(celli, n, deltas, s);
        faces.append(best);
        weightN.append(best >= 0 ? d/(d + s) : 0);
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
    face_.transfer(faces);
    weight_.transfer(weightN);
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
    const scalarField& A,
    const scalar KmaxByA
)
{
    penalty_.setSize(cells_.size());
    if (cells_.empty())
    {
        return;
    }
    scalarField& diag = eqn.diag();
    Field<vector>& source = eqn.source();
    // the coefficient of u_N in the row of c alone: the matrix made
    // asymmetric (a symmetric one shares upper for both rows; the
    // momentum matrix with convection is asymmetric already)
    scalarField& lower = eqn.lower();
    scalarField& upper = eqn.upper();
    const labelUList& own = mesh_.faceOwner();
    const polyBoundaryMesh& patches = mesh_.boundaryMesh();
    const scalarField& V = mesh_.V();
    forAll(cells_, i)
    {
        const label celli = cells_[i];
        // K = (h_n/d - 1) A, h_n = V/G (class description)
        const scalar hn = V[celli]/area_[i];
        const scalar Kmax = KmaxByA*A[celli];
        const scalar K =
            distance_[i] > 0
          ? min((hn/distance_[i] - 1)*A[celli], Kmax)
          : Kmax;
        penalty_[i] = K;
        diag[celli] += K;
        // K u_t = K (1 - w) u_s + K w u_N: u_N implicit
        const scalar w = weight_[i];
        source[celli] += K*(1 - w)*velocity_[i];
        const label facei = face_[i];
        if (facei < 0 || w <= 0)
        {
            continue;
        }
        if (mesh_.isInternalFace(facei))
        {
            if (own[facei] == celli)
            {
                upper[facei] -= K*w;
            }
            else
            {
                lower[facei] -= K*w;
            }
        }
        else
        {
            // a coupled face: the solver and fvMatrix::H take
            // -boundaryCoeffs u_N into the row (lduMatrix interfaces)
            const label patchi = patches.whichPatch(facei);
            eqn.boundaryCoeffs()[patchi][facei - patches[patchi].start()]
                += vector::one*K*w;
        }
    }
}


Foam::tmp<Foam::vectorField> Foam::immersedWallInterpolation::target
(
    const volVectorField& U
) const
{
    const labelUList& own = mesh_.faceOwner();
    const labelUList& nei = mesh_.faceNeighbour();
    const polyBoundaryMesh& patches = mesh_.boundaryMesh();
    // the neighbours' values across the coupled patches
    PtrList<vectorField> nbr(patches.size());
    forAll(patches, patchi)
    {
        if (patches[patchi].coupled())
        {
            nbr.set
            (
                patchi,
                U.boundaryField()[patchi].patchNeighbourField().ptr()
            );
        }
    }
    auto tu = tmp<vectorField>::New(velocity_);
    vectorField& ut = tu.ref();
    forAll(cells_, i)
    {
        const label facei = face_[i];
        if (facei < 0)
        {
            continue;
        }
        vector uN;
        if (mesh_.isInternalFace(facei))
        {
            uN = U[own[facei] == cells_[i] ? nei[facei] : own[facei]];
        }
        else
        {
            const label patchi = patches.whichPatch(facei);
            uN = nbr[patchi][facei - patches[patchi].start()];
        }
        ut[i] = (1 - weight_[i])*velocity_[i] + weight_[i]*uN;
    }
    return tu;
}


Foam::vector Foam::immersedWallInterpolation::addForce
(
    const volVectorField& U,
    const scalar rho,
    vectorField& nodeForce
) const
{
    vector total(Zero);
    const vectorField ut(target(U));
    forAll(cells_, i)
    {
        const scalar K = i < penalty_.size() ? penalty_[i] : 0;
        const vector F(rho*K*(U[cells_[i]] - ut[i]));
        for (label k = 0; k < 3; ++k)
        {
            nodeForce[nodes_[i][k]] += weights_[i][k]*F;
        }
        total += F;
    }
    return total;
}


// ************************************************************************* //
