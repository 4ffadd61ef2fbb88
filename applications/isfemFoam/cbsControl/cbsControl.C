/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (isfemFoam)
\*---------------------------------------------------------------------------*/

#include "cbsControl.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::cbsControl::cbsControl(fvMesh& mesh, const word& dictName)
:
    pisoControl(mesh, dictName),
    nCorrFirst_(nCorrPISO_),
    nNonOrthFirst_(nNonOrthCorr_),
    nCorrRepeated_(nCorrPISO_),
    nNonOrthRepeated_(nNonOrthCorr_),
    repeated_(false)
{
    read();
}


// * * * * * * * * * * * * * Protected Member Functions  * * * * * * * * * * //

bool Foam::cbsControl::read()
{
    pisoControl::read();
    nCorrFirst_ = nCorrPISO_;
    nNonOrthFirst_ = nNonOrthCorr_;
    const dictionary& d = dict();
    nCorrRepeated_ = d.getOrDefault<label>("nCorrectorsRepeated", nCorrFirst_);
    nNonOrthRepeated_ =
        d.getOrDefault<label>
        (
            "nNonOrthogonalCorrectorsRepeated",
            nNonOrthFirst_
        );
    if (nCorrRepeated_ < 1 || nNonOrthRepeated_ < 0)
    {
        FatalIOErrorInFunction(d)
            << "nCorrectorsRepeated " << nCorrRepeated_
            << " must be at least 1 and nNonOrthogonalCorrectorsRepeated "
            << nNonOrthRepeated_ << " at least 0" << exit(FatalIOError);
    }
    setRepeated(repeated_);
    return true;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::cbsControl::setRepeated(const bool repeated)
{
    repeated_ = repeated;
    nCorrPISO_ = repeated ? nCorrRepeated_ : nCorrFirst_;
    nNonOrthCorr_ = repeated ? nNonOrthRepeated_ : nNonOrthFirst_;
}


// ************************************************************************* //
