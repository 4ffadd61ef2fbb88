/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "interpolationCellLinear.H"
#include "gradScheme.H"
#include "IStringStream.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

template<class Type>
Foam::interpolationCellLinear<Type>::interpolationCellLinear
(
    const GeometricField<Type, fvPatchField, volMesh>& psi,
    const string& gradScheme
)
:
    interpolation<Type>(psi)
{
    IStringStream is(gradScheme);
    tgrad_ = fv::gradScheme<Type>::New(psi.mesh(), is)().calcGrad
    (
        psi,
        "cellLinearGrad(" + psi.name() + ')'
    );
}


template<class Type>
Foam::interpolationCellLinear<Type>::interpolationCellLinear
(
    const GeometricField<Type, fvPatchField, volMesh>& psi
)
:
    interpolationCellLinear<Type>(psi, "leastSquares")
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

template<class Type>
Type Foam::interpolationCellLinear<Type>::interpolate
(
    const vector& position,
    const label celli,
    const label facei
) const
{
    return
        this->psi_[celli]
      + ((position - this->pMesh_.cellCentres()[celli]) & tgrad_()[celli]);
}


// ************************************************************************* //
