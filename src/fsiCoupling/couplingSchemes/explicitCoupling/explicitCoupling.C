/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "explicitCoupling.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace couplingSchemes
{
    defineTypeNameAndDebug(explicitCoupling, 0);
    addToRunTimeSelectionTable
    (
        couplingScheme,
        explicitCoupling,
        dictionary
    );
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::couplingSchemes::explicitCoupling::explicitCoupling
(
    const dictionary& dict,
    const string& owner,
    const Time& time
)
:
    couplingScheme(dict, owner, time)
{
    explicitCoupling::read(dict);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::couplingSchemes::explicitCoupling::read(const dictionary& dict)
{
    couplingScheme::read(dict);
    if (maxIterations_ != 1)
    {
        FatalIOErrorInFunction(dict)
            << owner_.c_str() << ": couplingScheme explicit takes one pass per step;"
            << " couplingIterations " << maxIterations_
            << " asks for more: remove it or choose"
            << " couplingScheme IQNILS" << exit(FatalIOError);
    }
}


bool Foam::couplingSchemes::explicitCoupling::update
(
    const vectorField&,
    const vectorField&,
    vectorField&
)
{
    return true;
}


// ************************************************************************* //
