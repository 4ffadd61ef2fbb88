/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
-------------------------------------------------------------------------------
    immersedBoundary: the semi-implicit coupling, the covered cells' inertia
    in the pressure equation (see fv::immersedForcing, entry coupling).

    The explicit (Dirichlet-Neumann) coupling hands the fluid the solid's
    velocity and the solid the fluid's force of the last step; the pressure
    answers the solid's acceleration with an added-mass force that the
    solid only feels one step later, and the scheme diverges whatever dt
    once the added mass exceeds the solid's (Causin, Gerbeau & Nobile,
    CMAME 194:4506, 2005): a leaflet in blood, the Turek-Hron flag. The
    semi-implicit scheme of Fernandez, Gerbeau & Grandmont (IJNME 69:794,
    2007) couples only the pressure implicitly with the solid's inertia,
    viscous and elastic terms staying explicit. Here: the solid's
    predictor (its sub-cycled step) feels the pressure p^n of the last
    step; each covered cell C enters the pressure equation as a body of
    mass m_C (the solid's and the fluid's that moves with it), whose
    velocity answers the pressure as
        u_C = u~_C - (dt rho_f V_C/m_C) grad(p^{n+1} - p^n),
    i.e. 1/A = dt rho_f V_C/m_C (p kinematic), and the solid is corrected
    by the force of the increment p^{n+1} - p^n. One pressure solve, as
    the explicit scheme.
\*---------------------------------------------------------------------------*/

#include "immersedBoundary.H"
#include "syncTools.H"
#include "emptyPolyPatch.H"

// * * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

// 1/A of the two half-cells in series across a face: their densities add
// over their lengths, rho_f = (d_P rho_P + d_N rho_N)/d, so 1/A_f is the
// harmonic mean. w is OpenFOAM's linear weight of the owner P (d_N/d).
inline Foam::scalar harmonic
(
    const Foam::scalar w,
    const Foam::scalar a,
    const Foam::scalar b
)
{
    if (a <= 0 || b <= 0)
    {
        return 0;
    }
    return 1.0/((1 - w)/a + w/b);
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedBoundary::setInertia(const scalarField& inertia)
{
    if (inertia.size() != coveredCells_.size())
    {
        FatalErrorInFunction
            << inertia.size() << " inertia values for "
            << coveredCells_.size() << " covered cells"
            << abort(FatalError);
    }
    inertia_ = inertia;
    inertial_ = true;
}


void Foam::immersedBoundary::inertialProjection
(
    surfaceScalarField& phiHbyA,
    surfaceScalarField& rAUf,
    const volScalarField& rAU,
    const volScalarField& p0
) const
{
    if (!inertial_)
    {
        return;
    }
    const scalar dt = mesh_.time().deltaTValue();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const scalarField& w = mesh_.weights();
    const surfaceScalarField& delta = mesh_.nonOrthDeltaCoeffs();
    const scalarField& magSf = mesh_.magSf();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInternal = mesh_.nInternalFaces();

    // 1/A per cell: the fluid's, the covered cells' from their inertia
    scalarField rA(rAU.primitiveField());
    forAll(coveredCells_, i)
    {
        rA[coveredCells_[i]] = dt*inertia_[i];
    }
    scalarField rAnbr;
    scalarField p0nbr;
    syncTools::swapBoundaryCellList(mesh_, rA, rAnbr);
    syncTools::swapBoundaryCellList(mesh_, p0.primitiveField(), p0nbr);

    // the net solid flux out of each covered cell, before the pressure
    // flux of p0 is added (constrainPressure leaves it out of its row)
    solidDivergence_.setSize(coveredCells_.size());
    solidDivergence_ = Zero;
    forAll(coveredCells_, i)
    {
        const label celli = coveredCells_[i];
        for (const label facei : mesh_.cells()[celli])
        {
            scalar phif = 0;
            if (facei < nInternal)
            {
                phif = phiHbyA[facei];
            }
            else
            {
                const label patchi = pbm.whichPatch(facei);
                const fvsPatchScalarField& pp =
                    phiHbyA.boundaryField()[patchi];
                if (pp.size())
                {
                    phif = pp[facei - pbm[patchi].start()];
                }
            }
            solidDivergence_[i] +=
                (facei >= nInternal || own[facei] == celli) ? phif : -phif;
        }
    }

    immersedRAUf_.setSize(nFaces());
    scalarField& rI = rAUf.primitiveFieldRef();
    scalarField& phiI = phiHbyA.primitiveFieldRef();
    forAll(internalFaces_, j)
    {
        const label facei = internalFaces_[j];
        const label o = own[facei];
        const label n = nei[facei];
        rI[facei] = harmonic(w[facei], rA[o], rA[n]);
        immersedRAUf_[j] = rI[facei];
        phiI[facei] +=
            rI[facei]*delta[facei]*(p0[n] - p0[o])*magSf[facei];
    }
    auto& rB = rAUf.boundaryFieldRef();
    auto& phiB = phiHbyA.boundaryFieldRef();
    forAll(boundaryFaces_, j)
    {
        const label facei = boundaryFaces_[j];
        const label patchi = pbm.whichPatch(facei);
        const label i = facei - pbm[patchi].start();
        const label b = facei - nInternal;
        const label o = mesh_.faceOwner()[facei];
        const scalar wf = mesh_.weights().boundaryField()[patchi][i];
        const scalar r = harmonic(wf, rA[o], rAnbr[b]);
        rB[patchi][i] = r;
        immersedRAUf_[internalFaces_.size() + j] = r;
        phiB[patchi][i] +=
            r*delta.boundaryField()[patchi][i]*(p0nbr[b] - p0[o])
           *mesh_.magSf().boundaryField()[patchi][i];
    }
}


Foam::tmp<Foam::vectorField> Foam::immersedBoundary::pressureForce
(
    const volScalarField& p,
    const scalar rhoFluid
) const
{
    tmp<vectorField> tF(new vectorField(coveredCells_.size(), Zero));
    if (!inertial_)
    {
        return tF;
    }
    vectorField& F = tF.ref();
    const scalar dt = mesh_.time().deltaTValue();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const vectorField& Sf = mesh_.faceAreas();
    const scalarField magSf(mag(mesh_.faceAreas()));
    const surfaceScalarField& delta = mesh_.nonOrthDeltaCoeffs();
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    const label nInternal = mesh_.nInternalFaces();
    const scalarField& V = mesh_.V();

    scalarField pnbr;
    syncTools::swapBoundaryCellList(mesh_, p.primitiveField(), pnbr);

    // T = sum_f S_f S_f/|S_f| and b = sum_f S_f beta_f snGrad(p)_f per
    // covered cell (fvc::reconstruct of the pressure flux over 1/A_C)
    symmTensorField T(coveredCells_.size(), Zero);
    vectorField b(coveredCells_.size(), Zero);

    forAll(internalFaces_, j)
    {
        const label facei = internalFaces_[j];
        const label o = own[facei];
        const label n = nei[facei];
        const scalar g = delta[facei]*(p[n] - p[o]);
        const symmTensor SS(sqr(Sf[facei])/magSf[facei]);
        for (const label c : {o, n})
        {
            const label i = coveredIndex_[c];
            if (i < 0)
            {
                continue;
            }
            const scalar rC = dt*inertia_[i];
            const scalar beta = rC > 0 ? immersedRAUf_[j]/rC : 0;
            T[i] += SS;
            b[i] += Sf[facei]*beta*g;
        }
    }
    forAll(boundaryFaces_, j)
    {
        const label facei = boundaryFaces_[j];
        const label i = coveredIndex_[mesh_.faceOwner()[facei]];
        if (i < 0)
        {
            continue;
        }
        const label patchi = pbm.whichPatch(facei);
        const label k = facei - pbm[patchi].start();
        const label o = mesh_.faceOwner()[facei];
        const scalar g =
            delta.boundaryField()[patchi][k]*(pnbr[facei - nInternal] - p[o]);
        const scalar rC = dt*inertia_[i];
        const scalar beta =
            rC > 0 ? immersedRAUf_[internalFaces_.size() + j]/rC : 0;
        T[i] += sqr(Sf[facei])/magSf[facei];
        b[i] += Sf[facei]*beta*g;
    }

    // The covered cells' other boundary faces (walls, inlets, outlets;
    // not coupled): no pressure flux of the cell through them, they only
    // shape T. Empty directions (2D) get a unit entry.
    const Vector<label>& solD = mesh_.solutionD();
    forAll(coveredCells_, i)
    {
        const label celli = coveredCells_[i];
        for (const label facei : mesh_.cells()[celli])
        {
            if (facei < nInternal)
            {
                continue;
            }
            const label patchi = pbm.whichPatch(facei);
            if (pbm[patchi].coupled() || isA<emptyPolyPatch>(pbm[patchi]))
            {
                continue;
            }
            T[i] += sqr(Sf[facei])/magSf[facei];
        }
        symmTensor Ti(T[i]);
        if (solD[vector::X] == -1) { Ti.xx() += 1; }
        if (solD[vector::Y] == -1) { Ti.yy() += 1; }
        if (solD[vector::Z] == -1) { Ti.zz() += 1; }
        if (inertia_[i] > 0 && mag(det(Ti)) > VSMALL)
        {
            F[i] = -rhoFluid*V[celli]*(inv(Ti) & b[i]);
        }
    }
    return tF;
}


// ************************************************************************* //
