/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "interpolationCellLinear.H"
#include "fvMesh.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
    makeInterpolationType(interpolationCellLinear, scalar);
    makeInterpolationType(interpolationCellLinear, vector);
}

// ************************************************************************* //
