/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "couplingScheme.H"
#include "Time.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(couplingScheme, 0);
    defineRunTimeSelectionTable(couplingScheme, dictionary);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::couplingScheme::couplingScheme
(
    const dictionary& dict,
    const string& owner,
    const Time& time
)
:
    owner_(owner),
    time_(time),
    maxIterations_(1),
    tolerance_(1e-3),
    iteration_(0),
    residual_(0)
{
    couplingScheme::read(dict);
}


// * * * * * * * * * * * * * * * * * Selectors * * * * * * * * * * * * * * * //

Foam::word Foam::couplingScheme::selectedType(const dictionary& dict)
{
    return dict.getOrDefault<word>
    (
        "couplingScheme",
        dict.getOrDefault<label>("couplingIterations", 1) > 1
      ? "IQNILS"
      : "explicit"
    );
}


Foam::autoPtr<Foam::couplingScheme> Foam::couplingScheme::New
(
    const dictionary& dict,
    const string& owner,
    const Time& time
)
{
    const word schemeType(selectedType(dict));

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(schemeType);
    if (!cstrIter.found())
    {
        FatalIOErrorInFunction(dict)
            << owner.c_str() << ": unknown couplingScheme " << schemeType
            << "; valid choices: "
            << dictionaryConstructorTablePtr_->sortedToc()
            << exit(FatalIOError);
    }
    return autoPtr<couplingScheme>(cstrIter()(dict, owner, time));
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::couplingScheme::read(const dictionary& dict)
{
    maxIterations_ = dict.getOrDefault<label>("couplingIterations", 1);
    tolerance_ = dict.getOrDefault<scalar>("couplingTolerance", 1e-3);
    if (maxIterations_ < 1 || tolerance_ <= 0)
    {
        FatalIOErrorInFunction(dict)
            << owner_.c_str() << ": couplingIterations " << maxIterations_
            << " and couplingTolerance " << tolerance_
            << " must be positive" << exit(FatalIOError);
    }
}


Foam::tmp<Foam::vectorField> Foam::couplingScheme::lastIterate() const
{
    FatalErrorInFunction
        << owner_.c_str() << ": the " << type() << " coupling scheme keeps no"
        << " iterate" << abort(FatalError);
    return nullptr;
}


void Foam::couplingScheme::dropHistory()
{}


void Foam::couplingScheme::writeState(const fileName&) const
{}


void Foam::couplingScheme::readState(const fileName&, const label)
{}


// ************************************************************************* //
