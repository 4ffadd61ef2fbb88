/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "coveredRows.H"
#include "fvMatrices.H"
#include "volFields.H"
#include "syncTools.H"

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::coveredRows::keep
(
    const fvMatrix<vector>& M,
    const labelUList& cells
)
{
    const fvMesh& mesh = M.psi().mesh();
    const cellList& meshCells = mesh.cells();
    const labelUList& own = mesh.owner();
    const labelUList& nei = mesh.neighbour();
    const polyBoundaryMesh& pbm = mesh.boundaryMesh();
    const label nInternal = mesh.nInternalFaces();
    const scalarField& diag = M.diag();
    const scalarField& upper = M.upper();
    const scalarField& lower = M.lower();

    cells_ = cells;
    diag_.setSize(cells.size());
    source_.setSize(cells.size());
    offsets_.setSize(cells.size() + 1);
    DynamicList<label> nbrCell(6*cells.size());
    DynamicList<scalar> coeff(6*cells.size());
    DynamicList<label> coupledFace;
    DynamicList<label> coupledCell;
    DynamicList<vector> coupledInternal;
    DynamicList<vector> coupledBoundary;

    forAll(cells, i)
    {
        const label celli = cells[i];
        offsets_[i] = nbrCell.size();
        diag_[i] = vector::uniform(diag[celli]);
        source_[i] = M.source()[celli];
        for (const label facei : meshCells[celli])
        {
            if (facei < nInternal)
            {
                if (own[facei] == celli)
                {
                    nbrCell.append(nei[facei]);
                    coeff.append(upper[facei]);
                }
                else
                {
                    nbrCell.append(own[facei]);
                    coeff.append(lower[facei]);
                }
                continue;
            }
            const label patchi = pbm.whichPatch(facei);
            const Field<vector>& ic = M.internalCoeffs()[patchi];
            if (ic.empty())
            {
                continue;   // empty patches
            }
            const label patchFacei = facei - pbm[patchi].start();
            const vector& bc = M.boundaryCoeffs()[patchi][patchFacei];
            if (M.psi().boundaryField()[patchi].coupled())
            {
                coupledFace.append(facei - nInternal);
                coupledCell.append(i);
                coupledInternal.append(ic[patchFacei]);
                coupledBoundary.append(bc);
            }
            else
            {
                diag_[i] += ic[patchFacei];
                source_[i] += bc;
            }
        }
    }
    offsets_.last() = nbrCell.size();
    nbrCell_.transfer(nbrCell);
    coeff_.transfer(coeff);
    coupledFace_.transfer(coupledFace);
    coupledCell_.transfer(coupledCell);
    coupledInternal_.transfer(coupledInternal);
    coupledBoundary_.transfer(coupledBoundary);
}


Foam::vector Foam::coveredRows::residualSum(const volVectorField& U) const
{
    vector sum(Zero);
    forAll(cells_, i)
    {
        const vector& u = U[cells_[i]];
        vector r(cmptMultiply(diag_[i], u) - source_[i]);
        for (label k = offsets_[i]; k < offsets_[i + 1]; ++k)
        {
            r += coeff_[k]*U[nbrCell_[k]];
        }
        sum += r;
    }

    // Coupled faces: a_c^b u_c - b^b u_across (fvMatrix::addBoundarySource)
    vectorField across;
    syncTools::swapBoundaryCellList(U.mesh(), U.primitiveField(), across);
    forAll(coupledFace_, k)
    {
        sum +=
            cmptMultiply(coupledInternal_[k], U[cells_[coupledCell_[k]]])
          - cmptMultiply(coupledBoundary_[k], across[coupledFace_[k]]);
    }
    return sum;
}


// ************************************************************************* //
