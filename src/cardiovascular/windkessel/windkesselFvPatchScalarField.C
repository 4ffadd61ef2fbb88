/*---------------------------------------------------------------------------*\
    isfem: cardiovascular boundary conditions (libcardiovascular)
\*---------------------------------------------------------------------------*/

#include "windkesselFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"
#include "fvPatchFieldMapper.H"
#include "volFields.H"
#include "surfaceFields.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

const Foam::Enum<Foam::windkesselFvPatchScalarField::couplingType>
Foam::windkesselFvPatchScalarField::couplingTypeNames
({
    { couplingType::implicit, "implicit" },
    { couplingType::lagged, "lagged" },
});


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::windkesselFvPatchScalarField::check(const dictionary& dict) const
{
    const word where("patch " + patch().name() + " (windkessel): ");
    const auto bad = [&](const char* entry, const scalar v, const char* what)
    {
        FatalIOErrorInFunction(dict)
            << where.c_str() << entry << ' ' << v << ' ' << what
            << exit(FatalIOError);
    };
    if (par_.Rp < 0)
    {
        bad("Rp", par_.Rp, "is negative (0: the two-element Windkessel)");
    }
    if (par_.C <= 0)
    {
        bad("C", par_.C, "is not positive (a compliance in m3/Pa)");
    }
    if (par_.Rd <= 0)
    {
        bad("Rd", par_.Rd, "is not positive (a resistance in Pa s/m3)");
    }
    if (par_.rho <= 0)
    {
        bad("rho", par_.rho, "is not positive (omit it for a p in Pa)");
    }
    if (par_.tolerance <= 0)
    {
        bad("tolerance", par_.tolerance, "is not positive");
    }
    if (returnReduce(patch().size(), sumOp<label>()) == 0)
    {
        FatalIOErrorInFunction(dict)
            << where.c_str() << "the patch has no faces: a Windkessel needs"
            << " the flow through an outlet" << exit(FatalIOError);
    }
}


Foam::scalar Foam::windkesselFvPatchScalarField::flow() const
{
    if (!db().foundObject<surfaceScalarField>(par_.phiName))
    {
        return s_.Q0;
    }
    return gSum
    (
        patch().lookupPatchField<surfaceScalarField, scalar>(par_.phiName)
    );
}


Foam::scalar Foam::windkesselFvPatchScalarField::pC1(const scalar Q) const
{
    // the trapezoidal rule on C dp_C/dt = Q - (p_C - p_d)/Rd
    const scalar a = par_.C/s_.dt;
    const scalar b = 0.5/par_.Rd;
    return
        (s_.pC0*(a - b) + 0.5*(Q + s_.Q0) + (s_.pd0 + s_.pd1)*b)/(a + b);
}


Foam::scalar Foam::windkesselFvPatchScalarField::pOut(const scalar Q) const
{
    return pC1(Q) + par_.Rp*Q;
}


void Foam::windkesselFvPatchScalarField::startStep
(
    const label timeIndex,
    const scalar Q
)
{
    if (s_.timeIndex >= 0)
    {
        // the step before ended with the flow of its last solve
        s_.pC0 = pC1(Q);
        s_.Qm1 = s_.Q0;
        s_.dtm1 = s_.dt;
        s_.Q0 = Q;
    }
    else if (!s_.Q0Known)
    {
        s_.Q0 = Q;
        s_.Q0Known = true;
    }
    s_.timeIndex = timeIndex;
    setStepLength();
}


void Foam::windkesselFvPatchScalarField::setStepLength()
{
    const Time& runTime = db().time();
    s_.dt = runTime.deltaTValue();
    s_.pd0 = par_.pDistal->value(runTime.value() - s_.dt);
    s_.pd1 = par_.pDistal->value(runTime.value());
    s_.iter = 0;
    s_.c1 = -1;
    s_.c2 = -2;
}


Foam::label Foam::windkesselFvPatchScalarField::corrector() const
{
    const auto* phiHbyA =
        db().findObject<surfaceScalarField>("phiHbyA");
    return phiHbyA ? label(phiHbyA->eventNo()) : -1;
}


Foam::scalar Foam::windkesselFvPatchScalarField::iterate
(
    const scalar Q,
    const label corrector
)
{
    // the step's first: the flow of the step before (lagged), or for the
    // implicit coupling that flow extrapolated linearly over the step (a
    // residual of second order in the step; the step at most twice the one
    // before in the extrapolation)
    scalar Qstart = s_.Q0;
    if (par_.coupling == couplingType::implicit && s_.dtm1 > 0)
    {
        Qstart += (s_.Q0 - s_.Qm1)*min(s_.dt/s_.dtm1, scalar(2));
    }
    scalar p = pOut(Qstart);
    if (par_.coupling == couplingType::implicit && s_.iter > 0)
    {
        // the residual of the last solve: it was given p1 and gave Q
        const scalar r = s_.p1 - pOut(Q);
        // two solves of one corrector: Q is affine in p there, the
        // secant its slope (physically 1 + R dQ/dp >= 1)
        if (s_.c1 == s_.c2 && mag(s_.p1 - s_.p2) > SMALL*mag(s_.p1))
        {
            const scalar slope = (r - s_.r2)/(s_.p1 - s_.p2);
            if (slope > 0.5)
            {
                s_.slope = slope;
            }
        }
        p = s_.p1 - r/s_.slope;
        s_.p2 = s_.p1;
        s_.r2 = r;
        s_.c2 = s_.c1;
    }
    s_.p1 = p;
    s_.c1 = corrector;
    ++s_.iter;
    return p;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::windkesselFvPatchScalarField::parameters::parameters()
:
    Rp(0),
    C(0),
    Rd(0),
    pDistal(),
    rho(1),
    phiName("phi"),
    coupling(couplingType::implicit),
    tolerance(1e-8)
{}


Foam::windkesselFvPatchScalarField::parameters::parameters
(
    const dictionary& dict
)
:
    Rp(dict.get<scalar>("Rp")),
    C(dict.get<scalar>("C")),
    Rd(dict.get<scalar>("Rd")),
    pDistal(Function1<scalar>::New("pDistal", dict)),
    rho(dict.getOrDefault<scalar>("rho", 1)),
    phiName(dict.getOrDefault<word>("phi", "phi")),
    coupling
    (
        couplingTypeNames.getOrDefault
        (
            "coupling", dict, couplingType::implicit
        )
    ),
    tolerance(dict.getOrDefault<scalar>("tolerance", 1e-8))
{}


Foam::windkesselFvPatchScalarField::parameters::parameters
(
    const parameters& p
)
:
    Rp(p.Rp),
    C(p.C),
    Rd(p.Rd),
    pDistal(p.pDistal.clone()),
    rho(p.rho),
    phiName(p.phiName),
    coupling(p.coupling),
    tolerance(p.tolerance)
{}


Foam::windkesselFvPatchScalarField::windkesselFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedValueFvPatchScalarField(p, iF),
    par_(),
    s_()
{
    s_.startIndex = db().time().timeIndex();
}


Foam::windkesselFvPatchScalarField::windkesselFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const dictionary& dict
)
:
    fixedValueFvPatchScalarField(p, iF, dict),
    par_(dict),
    s_()
{
    s_.startIndex = db().time().timeIndex();
    // the state written with a field (a restart), or the start: the
    // compliance at the given pressure, or at rest at the distal one
    s_.pC0 = dict.getOrDefault<scalar>
    (
        "pC",
        par_.pDistal->value(db().time().value())
    );
    s_.Q0Known = dict.readIfPresent("Q", s_.Q0);
    dict.readIfPresent("slope", s_.slope);
    if (s_.Q0Known && dict.readIfPresent("deltaTPrevious", s_.dtm1))
    {
        s_.Qm1 = dict.get<scalar>("QPrevious");
    }
    check(dict);
}


Foam::windkesselFvPatchScalarField::windkesselFvPatchScalarField
(
    const windkesselFvPatchScalarField& ptf,
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    fixedValueFvPatchScalarField(ptf, p, iF, mapper),
    par_(ptf.par_),
    s_(ptf.s_)
{}


Foam::windkesselFvPatchScalarField::windkesselFvPatchScalarField
(
    const windkesselFvPatchScalarField& ptf
)
:
    windkesselFvPatchScalarField(ptf, ptf.internalField())
{}


Foam::windkesselFvPatchScalarField::windkesselFvPatchScalarField
(
    const windkesselFvPatchScalarField& ptf,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedValueFvPatchScalarField(ptf, iF),
    par_(ptf.par_),
    s_(ptf.s_)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::windkesselFvPatchScalarField::residual() const
{
    if (s_.timeIndex != db().time().timeIndex() || s_.iter == 0)
    {
        return 0;           // no solve of this step has used the outlet
    }
    const scalar pQ = pOut(flow());
    const scalar r = s_.p1 - pQ;
    const scalar scale = max(mag(s_.p1), mag(pQ));
    return scale > VSMALL ? mag(r)/scale : 0;
}


bool Foam::windkesselFvPatchScalarField::converged() const
{
    return par_.coupling == couplingType::lagged || residual() <= par_.tolerance;
}


Foam::scalar Foam::windkesselFvPatchScalarField::pC() const
{
    return s_.timeIndex < 0 ? s_.pC0 : pC1(flow());
}


void Foam::windkesselFvPatchScalarField::updateCoeffs()
{
    if (updated())
    {
        return;
    }
    const label timeIndex = db().time().timeIndex();
    const scalar Q = flow();
    scalar p = 0;
    if (timeIndex == s_.startIndex)
    {
        // before the first step: the state alone
        if (!s_.Q0Known && db().foundObject<surfaceScalarField>(par_.phiName))
        {
            s_.Q0 = Q;
            s_.Q0Known = true;
        }
        p = s_.pC0 + par_.Rp*s_.Q0;
    }
    else
    {
        if (timeIndex != s_.timeIndex)
        {
            startStep(timeIndex, Q);
        }
        else if (db().time().deltaTValue() != s_.dt)
        {
            // the step again from its start at another length (a coupling
            // refused it): the same start state, the new step's length
            setStepLength();
        }
        // a new iterate needs the flux of a new solve (or none yet)
        const label event =
            db().lookupObject<surfaceScalarField>(par_.phiName).eventNo();
        if (s_.iter == 0 || event != s_.phiEvent)
        {
            p = iterate(Q, corrector());
            s_.phiEvent = event;
        }
        else
        {
            p = s_.p1;
        }
    }
    operator==(p/par_.rho);
    fixedValueFvPatchScalarField::updateCoeffs();
}


bool Foam::windkesselFvPatchScalarField::found(const volScalarField& p)
{
    for (const fvPatchScalarField& pp : p.boundaryField())
    {
        if (isA<windkesselFvPatchScalarField>(pp))
        {
            return true;
        }
    }
    return false;
}


bool Foam::windkesselFvPatchScalarField::allConverged
(
    const volScalarField& p
)
{
    for (const fvPatchScalarField& pp : p.boundaryField())
    {
        const auto* w = isA<windkesselFvPatchScalarField>(pp);
        if (w && !w->converged())
        {
            return false;
        }
    }
    return true;
}


void Foam::windkesselFvPatchScalarField::report(const volScalarField& p)
{
    for (const fvPatchScalarField& pp : p.boundaryField())
    {
        const auto* w = isA<windkesselFvPatchScalarField>(pp);
        if (!w)
        {
            continue;
        }
        const scalar Q = w->flow();
        Info<< "windkessel " << w->patch().name() << ": p " << w->s_.p1
            << " Pa, Q " << Q << " m3/s, p_C " << w->pC() << " Pa, "
            << w->s_.iter << " pressure solves, residual " << w->residual()
            << endl;
        if (!w->converged())
        {
            WarningInFunction
                << "windkessel " << w->patch().name() << ": the outlet"
                << " pressure and the step's flow did not agree within "
                << w->par_.tolerance << " (residual " << w->residual() << ")"
                << " at time " << w->db().time().timeName()
                << "; raise nOutletIterations (CBS) or reduce the step"
                << endl;
        }
    }
}


void Foam::windkesselFvPatchScalarField::write(Ostream& os) const
{
    fvPatchScalarField::write(os);
    os.writeEntry("Rp", par_.Rp);
    os.writeEntry("C", par_.C);
    os.writeEntry("Rd", par_.Rd);
    par_.pDistal->writeData(os);
    if (par_.rho != 1)
    {
        os.writeEntry("rho", par_.rho);
    }
    os.writeEntry("coupling", couplingTypeNames[par_.coupling]);
    os.writeEntry("tolerance", par_.tolerance);
    os.writeEntryIfDifferent<word>("phi", "phi", par_.phiName);
    // the state at this time, for a restart
    os.writeEntry("pC", pC());
    if (s_.Q0Known || s_.timeIndex >= 0)
    {
        os.writeEntry("Q", s_.timeIndex < 0 ? s_.Q0 : flow());
    }
    os.writeEntry("slope", s_.slope);
    // the step that ended here: its starting flow and length (the first
    // iterate's extrapolation)
    const scalar QPrevious = s_.timeIndex < 0 ? s_.Qm1 : s_.Q0;
    const scalar deltaTPrevious = s_.timeIndex < 0 ? s_.dtm1 : s_.dt;
    if (deltaTPrevious > 0)
    {
        os.writeEntry("QPrevious", QPrevious);
        os.writeEntry("deltaTPrevious", deltaTPrevious);
    }
    writeEntry("value", os);
}


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
    makePatchTypeField
    (
        fvPatchScalarField,
        windkesselFvPatchScalarField
    );
}

// ************************************************************************* //
