/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "balancedForceFlux.H"
#include "extrapolatedCalculatedFvPatchFields.H"
#include "zeroGradientFvPatchFields.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::balancedForceFlux::balancedForceFlux(const fvMesh& mesh)
:
    mesh_(mesh),
    Dinv_(mesh.nCells()),
    VDinvT_(mesh.nCells()),
    weights_(mesh.magSf()*mesh.nonOrthDeltaCoeffs())
{
    // D_c = sum_f (x_f - x_c) S_f^T over all faces of the cell (= V_c I
    // where the faces are planar: tets)
    const vectorField& C = mesh_.C().primitiveField();
    const surfaceVectorField& Cf = mesh_.Cf();
    const surfaceVectorField& Sf = mesh_.Sf();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    tensorField D(mesh_.nCells(), Zero);
    forAll(own, facei)
    {
        D[own[facei]] += (Cf[facei] - C[own[facei]])*Sf[facei];
        D[nei[facei]] -= (Cf[facei] - C[nei[facei]])*Sf[facei];
    }
    forAll(mesh_.boundary(), patchi)
    {
        const vectorField& pCf = Cf.boundaryField()[patchi];
        const vectorField& pSf = Sf.boundaryField()[patchi];
        const labelUList& fc = mesh_.boundary()[patchi].faceCells();
        forAll(fc, i)
        {
            D[fc[i]] += (pCf[i] - C[fc[i]])*pSf[i];
        }
    }
    Dinv_ = inv(D);
    VDinvT_ = mesh_.V().field()*Dinv_.T();

    weights_.rename("balancedForceFluxWeights");
    // no force through uncoupled boundary faces: the walls take it
    for (auto& pw : weights_.boundaryFieldRef())
    {
        if (!pw.coupled())
        {
            pw = 0;
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::surfaceScalarField>
Foam::balancedForceFlux::flux(const volVectorField& f) const
{
    // phi_f = w_f ((x_f - x_o).g_o + (x_n - x_f).g_n), g_c = V_c D_c^-T f_c
    volVectorField gf
    (
        IOobject
        (
            f.name() + "Balanced",
            mesh_.time().timeName(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            false
        ),
        mesh_,
        dimensionedVector(f.dimensions(), Zero),
        zeroGradientFvPatchVectorField::typeName
    );
    gf.primitiveFieldRef() = VDinvT_ & f.primitiveField();
    gf.correctBoundaryConditions();
    const volVectorField& g = gf;
    const vectorField& C = mesh_.C().primitiveField();
    const surfaceVectorField& Cf = mesh_.Cf();
    tmp<surfaceScalarField> tphi
    (
        new surfaceScalarField
        (
            IOobject
            (
                "flux(" + f.name() + ')',
                mesh_.time().timeName(),
                mesh_,
                IOobject::NO_READ,
                IOobject::NO_WRITE,
                false
            ),
            mesh_,
            dimensionedScalar(f.dimensions()*dimArea, Zero)
        )
    );
    surfaceScalarField& phi = tphi.ref();
    phi.setOriented();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    forAll(own, facei)
    {
        const label o = own[facei], n = nei[facei];
        phi[facei] = weights_[facei]
           *(((Cf[facei] - C[o]) & g[o]) + ((C[n] - Cf[facei]) & g[n]));
    }
    forAll(mesh_.boundary(), patchi)
    {
        fvsPatchScalarField& pphi = phi.boundaryFieldRef()[patchi];
        const fvPatchVectorField& pf = g.boundaryField()[patchi];
        if (pf.coupled())
        {
            // the neighbour's half: its centre relative to this face
            const fvPatch& pp = mesh_.boundary()[patchi];
            const vectorField fi(pf.patchInternalField());
            const vectorField fn(pf.patchNeighbourField());
            const vectorField& pCf = Cf.boundaryField()[patchi];
            const vectorField delta(pp.delta());    // x_n - x_o
            const labelUList& fc = pp.faceCells();
            const scalarField& pw = weights_.boundaryField()[patchi];
            forAll(pphi, i)
            {
                const vector xo(C[fc[i]]);
                pphi[i] = pw[i]
                   *(
                        ((pCf[i] - xo) & fi[i])
                      + ((xo + delta[i] - pCf[i]) & fn[i])
                    );
            }
        }
        else
        {
            pphi = 0;
        }
    }
    return tphi;
}


Foam::tmp<Foam::volVectorField>
Foam::balancedForceFlux::reconstruct(const surfaceScalarField& phi) const
{
    // u_c = D_c^-1 sum_f (x_f - x_c) phi_f (phi_f out of the cell)
    const vectorField& C = mesh_.C().primitiveField();
    const surfaceVectorField& Cf = mesh_.Cf();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    vectorField b(mesh_.nCells(), Zero);
    forAll(own, facei)
    {
        b[own[facei]] += (Cf[facei] - C[own[facei]])*phi[facei];
        b[nei[facei]] -= (Cf[facei] - C[nei[facei]])*phi[facei];
    }
    forAll(mesh_.boundary(), patchi)
    {
        const fvsPatchScalarField& pphi = phi.boundaryField()[patchi];
        if (pphi.empty())
        {
            continue;
        }
        const vectorField& pCf = Cf.boundaryField()[patchi];
        const labelUList& fc = mesh_.boundary()[patchi].faceCells();
        forAll(fc, i)
        {
            b[fc[i]] += (pCf[i] - C[fc[i]])*pphi[i];
        }
    }
    tmp<volVectorField> tu
    (
        new volVectorField
        (
            IOobject
            (
                "reconstruct(" + phi.name() + ')',
                mesh_.time().timeName(),
                mesh_,
                IOobject::NO_READ,
                IOobject::NO_WRITE,
                false
            ),
            mesh_,
            dimensionedVector(phi.dimensions()/dimArea, Zero),
            extrapolatedCalculatedFvPatchVectorField::typeName
        )
    );
    tu.ref().primitiveFieldRef() = Dinv_ & b;
    tu.ref().correctBoundaryConditions();
    return tu;
}


// ************************************************************************* //
