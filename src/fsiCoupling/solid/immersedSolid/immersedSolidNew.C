/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedSolid.H"

// * * * * * * * * * * * * * * * * Selectors * * * * * * * * * * * * * * * //

Foam::autoPtr<Foam::immersedSolid> Foam::immersedSolid::New
(
    const Time& runTime
)
{
    const IOdictionary dict
    (
        IOobject
        (
            "solidProperties",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );
    return New(runTime, dict);
}


Foam::autoPtr<Foam::immersedSolid> Foam::immersedSolid::New
(
    const Time& runTime,
    const IOdictionary& dict
)
{
    const word solidType(dict.get<word>("type"));

    Info<< "Selecting immersed solid " << solidType << endl;

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(solidType);

    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            dict,
            "immersedSolid",
            solidType,
            *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }

    return autoPtr<immersedSolid>(cstrIter()(runTime, dict));
}


// ************************************************************************* //
