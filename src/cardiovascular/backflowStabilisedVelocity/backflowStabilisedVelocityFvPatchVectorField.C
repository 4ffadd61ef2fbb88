/*---------------------------------------------------------------------------*\
    isfem: cardiovascular boundary conditions (libcardiovascular)
\*---------------------------------------------------------------------------*/

#include "backflowStabilisedVelocityFvPatchVectorField.H"
#include "addToRunTimeSelectionTable.H"
#include "fvPatchFieldMapper.H"
#include "volFields.H"
#include "surfaceFields.H"
#include "turbulenceModel.H"
#include "transportModel.H"

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::backflowStabilisedVelocityFvPatchVectorField::check
(
    const dictionary& dict
) const
{
    if (beta_ < 0)
    {
        FatalIOErrorInFunction(dict)
            << "patch " << patch().name() << " (" << typeName << "): beta "
            << beta_ << " is negative (0: zero gradient; 1/2 and above:"
            << " no kinetic energy carried in by backflow)"
            << exit(FatalIOError);
    }
}


Foam::tmp<Foam::scalarField>
Foam::backflowStabilisedVelocityFvPatchVectorField::nuEff() const
{
    const label patchi = patch().index();
    const word turbulenceName
    (
        IOobject::groupName
        (
            turbulenceModel::propertiesName,
            internalField().group()
        )
    );
    if (db().foundObject<turbulenceModel>(turbulenceName))
    {
        return db().lookupObject<turbulenceModel>(turbulenceName)
            .nuEff(patchi);
    }
    if (db().foundObject<transportModel>("transportProperties"))
    {
        return db().lookupObject<transportModel>("transportProperties")
            .nu(patchi);
    }
    if (db().foundObject<IOdictionary>("transportProperties"))
    {
        const IOdictionary& dict =
            db().lookupObject<IOdictionary>("transportProperties");
        if (dict.found("nu"))
        {
            return tmp<scalarField>::New
            (
                patch().size(),
                dimensionedScalar("nu", dimViscosity, dict).value()
            );
        }
    }
    FatalErrorInFunction
        << "patch " << patch().name() << " (" << typeName << ") of "
        << internalField().name() << ": no viscosity to be found (no "
        << turbulenceName << ", no transport model, no entry nu in"
        << " constant/transportProperties); the stabilisation needs nu"
        << exit(FatalError);
    return nullptr;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::backflowStabilisedVelocityFvPatchVectorField::
backflowStabilisedVelocityFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF
)
:
    mixedFvPatchVectorField(p, iF),
    beta_(1),
    phiName_("phi")
{
    refValue() = Zero;
    refGrad() = Zero;
    valueFraction() = 0;
}


Foam::backflowStabilisedVelocityFvPatchVectorField::
backflowStabilisedVelocityFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const dictionary& dict
)
:
    mixedFvPatchVectorField(p, iF),
    beta_(dict.getOrDefault<scalar>("beta", 1)),
    phiName_(dict.getOrDefault<word>("phi", "phi"))
{
    check(dict);
    patchType() = dict.getOrDefault<word>("patchType", word::null);
    refValue() = Zero;
    refGrad() = Zero;
    // a restart continues with the fraction it was written with (the next
    // assembly computes it again from the flux)
    valueFraction() = 0;
    if (dict.found("valueFraction"))
    {
        valueFraction() = scalarField("valueFraction", dict, p.size());
    }
    if (dict.found("value"))
    {
        fvPatchVectorField::operator=
        (
            vectorField("value", dict, p.size())
        );
    }
    else
    {
        fvPatchVectorField::operator=(patchInternalField());
    }
}


Foam::backflowStabilisedVelocityFvPatchVectorField::
backflowStabilisedVelocityFvPatchVectorField
(
    const backflowStabilisedVelocityFvPatchVectorField& ptf,
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    mixedFvPatchVectorField(ptf, p, iF, mapper),
    beta_(ptf.beta_),
    phiName_(ptf.phiName_)
{}


Foam::backflowStabilisedVelocityFvPatchVectorField::
backflowStabilisedVelocityFvPatchVectorField
(
    const backflowStabilisedVelocityFvPatchVectorField& ptf
)
:
    mixedFvPatchVectorField(ptf),
    beta_(ptf.beta_),
    phiName_(ptf.phiName_)
{}


Foam::backflowStabilisedVelocityFvPatchVectorField::
backflowStabilisedVelocityFvPatchVectorField
(
    const backflowStabilisedVelocityFvPatchVectorField& ptf,
    const DimensionedField<vector, volMesh>& iF
)
:
    mixedFvPatchVectorField(ptf, iF),
    beta_(ptf.beta_),
    phiName_(ptf.phiName_)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::backflowStabilisedVelocityFvPatchVectorField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    const scalarField& phip =
        patch().lookupPatchField<surfaceScalarField, scalar>(phiName_);

    // beta |(U.n)_-|: the backflow's normal velocity (flux over area)
    const scalarField backflow(beta_*max(-phip/patch().magSf(), scalar(0)));

    // w = beta |(U.n)_-| / (beta |(U.n)_-| + nuEff delta); zero where the
    // flow leaves (backflow 0), also for a zero viscosity
    const scalarField nuDelta(nuEff()*patch().deltaCoeffs());
    valueFraction() = backflow/max(backflow + nuDelta, VSMALL);

    if (debug)
    {
        const scalarField inflow(max(-phip, scalar(0)));
        Info<< typeName << ' ' << patch().name() << ": "
            << gSum(pos(inflow))
            << " faces of backflow, flux in " << gSum(inflow)
            << ", largest w " << gMax(valueFraction()) << endl;
    }

    mixedFvPatchVectorField::updateCoeffs();
}


void Foam::backflowStabilisedVelocityFvPatchVectorField::write
(
    Ostream& os
) const
{
    fvPatchVectorField::write(os);
    os.writeEntry("beta", beta_);
    os.writeEntryIfDifferent<word>("phi", "phi", phiName_);
    valueFraction().writeEntry("valueFraction", os);
    writeEntry("value", os);
}


// * * * * * * * * * * * * * * * Member Operators  * * * * * * * * * * * * //

void Foam::backflowStabilisedVelocityFvPatchVectorField::operator=
(
    const fvPatchField<vector>& ptf
)
{
    fvPatchVectorField::operator=((1 - valueFraction())*ptf);
}


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
    makePatchTypeField
    (
        fvPatchVectorField,
        backflowStabilisedVelocityFvPatchVectorField
    );
}

// ************************************************************************* //
