/*---------------------------------------------------------------------------*\
  isfem: immersed smoothed finite element method for FSI (OpenFOAM side)
\*---------------------------------------------------------------------------*/

#include "cbsProjectionFluid.H"
#include "Function1.H"
#include "OStringStream.H"
#include "fvCFD.H"
#include "constrainHbyA.H"
#include "processorFvPatch.H"
#include "constrainPressure.H"
#include "adjustPhi.H"
#include "windkesselFvPatchScalarField.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(cbsProjectionFluid, 0);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::cbsProjectionFluid::cbsProjectionFluid(fvMesh& mesh)
:
    mesh_(mesh),
    control_(mesh, "CBS"),
    p_
    (
        IOobject
        (
            "p",
            mesh.time().timeName(),
            mesh,
            IOobject::MUST_READ,
            IOobject::AUTO_WRITE
        ),
        mesh
    ),
    U_
    (
        IOobject
        (
            "U",
            mesh.time().timeName(),
            mesh,
            IOobject::MUST_READ,
            IOobject::AUTO_WRITE
        ),
        mesh
    ),
    phi_
    (
        IOobject
        (
            "phi",
            mesh.time().timeName(),
            mesh,
            IOobject::READ_IF_PRESENT,
            IOobject::AUTO_WRITE
        ),
        fvc::flux(U_)
    ),
    laminarTransport_(U_, phi_),
    turbulence_(),
    fvOptions_(fv::options::New(mesh)),
    immersed_(fv::immersedMethod::all(fvOptions_)),
    pRefCell_(0),
    pRefValue_(0),
    cumulativeContErr_(0),
    balancedFlux_(),
    windkesselOutlets_(windkesselFvPatchScalarField::found(p_)),
    nOutletIterations_
    (
        control_.dict().getOrDefault<label>("nOutletIterations", 10)
    ),
    startIndex_(-1),
    startDeltaT_(0)
{
    Info<< "Fluid: CBS-equivalent projection (Steps I-III), "
        << "viscosity model "
        << laminarTransport_.lookupOrDefault<word>
           (
               "transportModel",
               "Newtonian"
           )
        << nl;

    // constant/turbulenceProperties, as pimpleFoam reads it; the laminar
    // Stokes model is the transport model's viscosity alone: without it
    // the step is the same as without the file
    IOobject turbulenceHeader
    (
        turbulenceModel::propertiesName,
        mesh.time().constant(),
        mesh,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    if (turbulenceHeader.typeHeaderOk<IOdictionary>(true))
    {
        turbulence_ =
            incompressible::turbulenceModel::New(U_, phi_, laminarTransport_);
        if (turbulence_->type() == "Stokes")
        {
            turbulence_.clear();
        }
        else
        {
            turbulence_->validate();
            Info<< "Turbulence model " << turbulence_->type() << nl;
        }
    }

    // the fields a step's end corrects besides U, phi and p: the viscosity
    // (generalised Newtonian models) and the turbulence model's
    for (const char* name : {"nu", "nut", "k", "epsilon", "omega", "nuTilda"})
    {
        const word field(IOobject::groupName(name, U_.group()));
        if (mesh_.foundObject<volScalarField>(field))
        {
            startScalarNames_.append(field);
        }
    }
    startScalars_.setSize(startScalarNames_.size());

    setRefCell(p_, control_.dict(), pRefCell_, pRefValue_);
    mesh_.setFluxRequired(p_.name());
    for (fv::immersedMethod& m : immersed_)
    {
        m.setPressureReference(pRefCell_);
    }

    if (!fvOptions_.optionList::size())
    {
        Info<< "No fvOptions momentum sources" << nl;
    }
    Info<< endl;
}


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

// A field's values: the internal field, then each patch's
template<class Type, template<class> class PatchField, class GeoMesh>
void storeValues
(
    const Foam::GeometricField<Type, PatchField, GeoMesh>& f,
    Foam::List<Foam::Field<Type>>& values
)
{
    const auto& bf = f.boundaryField();
    values.setSize(bf.size() + 1);
    values[0] = f.primitiveField();
    forAll(bf, patchi)
    {
        values[patchi + 1] = bf[patchi];
    }
}


template<class Type, template<class> class PatchField, class GeoMesh>
void restoreValues
(
    Foam::GeometricField<Type, PatchField, GeoMesh>& f,
    const Foam::List<Foam::Field<Type>>& values
)
{
    f.primitiveFieldRef() = values[0];
    auto& bf = f.boundaryFieldRef();
    forAll(bf, patchi)
    {
        bf[patchi] == values[patchi + 1];
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::cbsProjectionFluid::stepStart()
{
    // A step solved again at another length (an immersed method refused
    // it: an element inverted, or a node outran the solid's stable step)
    // starts from the state the step started from, as the step taken at
    // that length in the first place would. The refused solve's flux,
    // pressure and eddy viscosity would otherwise carry its velocities
    // into the new solve's convection, pressure predictor and stress:
    // after a refused step whose nodes' velocity had jumped by tens of
    // m/s the next momentum matrix was no longer diagonally dominant and
    // its solve diverged. The coupling iterations of one step (the sharp
    // method's) keep its length: each solves the step from its start too,
    // the method putting U, p and phi back before it
    // (fv::immersedForcing::restoreFluid).
    if (immersed_.empty())
    {
        return;
    }
    const Time& runTime = mesh_.time();
    const scalar dt = runTime.deltaTValue();
    if (runTime.timeIndex() != startIndex_)
    {
        startIndex_ = runTime.timeIndex();
        startDeltaT_ = dt;
        storeValues(U_, startU_);
        storeValues(phi_, startPhi_);
        storeValues(p_, startP_);
        forAll(startScalarNames_, i)
        {
            storeValues
            (
                mesh_.lookupObject<volScalarField>(startScalarNames_[i]),
                startScalars_[i]
            );
        }
        return;
    }
    if (dt == startDeltaT_)
    {
        return;
    }
    startDeltaT_ = dt;
    restoreValues(U_, startU_);
    restoreValues(phi_, startPhi_);
    restoreValues(p_, startP_);
    forAll(startScalarNames_, i)
    {
        restoreValues
        (
            mesh_.lookupObjectRef<volScalarField>(startScalarNames_[i]),
            startScalars_[i]
        );
    }
    Info<< "Fluid: the step solved again from its start at deltaT " << dt
        << " s (U, phi, p";
    for (const word& name : startScalarNames_)
    {
        Info<< ", " << name;
    }
    Info<< " as at its start)" << endl;
}


Foam::tmp<Foam::fvVectorMatrix>
Foam::cbsProjectionFluid::intermediateMomentum()
{
    // Step I (paper Eq. 37): transient + convection + viscous stress
    // (laminar deviatoric stress of Eq. 11 for incompressible flow, with the
    // transpose part for non-uniform viscosity) = momentum sources.
    // A turbulence model: its effective stress, as pimpleFoam's
    tmp<fvVectorMatrix> tUEqn;
    if (turbulence_.valid())
    {
        tUEqn =
        (
            fvm::ddt(U_)
          + fvm::div(phi_, U_)
          + turbulence_->divDevReff(U_)
         ==
            fvOptions_(U_)
        );
    }
    else
    {
        const volScalarField nu(laminarTransport_.nu());
        tUEqn =
        (
            fvm::ddt(U_)
          + fvm::div(phi_, U_)
          - fvm::laplacian(nu, U_)
          - fvc::div(nu*dev2(T(fvc::grad(U_))))
         ==
            fvOptions_(U_)
        );
    }
    fvVectorMatrix& UEqn = tUEqn.ref();

    UEqn.relax();
    fvOptions_.constrain(UEqn);

    // Step I solved for U (implicit convection and viscosity). Without it
    // the intermediate velocity is H/A of the Step I matrix with U^n
    // (explicit neighbours): fine for steady states, but its transient is
    // slowed where the viscous number nu dt/h^2 is not small.
    if (control_.momentumPredictor())
    {
        // Only the pressure gradient of the last step: not the new one
        Foam::solve(UEqn == -pressureGradient());
        fvOptions_.correct(U_);
    }

    return tUEqn;
}


Foam::tmp<Foam::surfaceScalarField> Foam::cbsProjectionFluid::balance
(
    const volVectorField::Internal& fb,
    const volScalarField& rAU,
    const surfaceScalarField& rAUf,
    volVectorField& HbyA
)
{
    // A balanced body force (fv::immersedMethod::balancedForce, the
    // carried leaflets' stress): handed to the face fluxes, where a static
    // pressure jump balances it exactly, and to the cells by the
    // reconstruction of the face balance (as buoyancy in
    // buoyantPimpleFoam); not through H/A. The flux is the adjoint of the
    // reconstruction (balancedForceFlux.H)
    HbyA.primitiveFieldRef() -= rAU.primitiveField()*fb.field();

    // the processor faces take the changed cells of the other side (the
    // flux of HbyA on them uses the neighbour's value as received at the
    // last evaluation: without this the two sides' fluxes differ by the
    // force's part and mass is not conserved across ranks). Only these:
    // HbyA.correctBoundaryConditions() would also evaluate the inlet and
    // outlet patches, whose values constrainHbyA set (serial coarse valve:
    // the inlet and outlet flows then differ by 4 %)
    volVectorField::Boundary& HbyAbf = HbyA.boundaryFieldRef();
    forAll(HbyAbf, patchi)
    {
        if (isA<processorFvPatch>(mesh_.boundary()[patchi]))
        {
            HbyAbf[patchi].initEvaluate(Pstream::defaultCommsType);
        }
    }
    forAll(HbyAbf, patchi)
    {
        if (isA<processorFvPatch>(mesh_.boundary()[patchi]))
        {
            HbyAbf[patchi].evaluate(Pstream::defaultCommsType);
        }
    }
    volVectorField f
    (
        IOobject("fBalanced", mesh_.time().timeName(), mesh_),
        mesh_,
        dimensionedVector(fb.dimensions(), Zero),
        zeroGradientFvPatchVectorField::typeName
    );
    f.primitiveFieldRef() = fb.field();
    f.correctBoundaryConditions();
    if (!balancedFlux_.valid())
    {
        balancedFlux_.reset(new balancedForceFlux(mesh_));
    }
    // zero through the boundary: the walls take it
    return rAUf*balancedFlux_->flux(f);
}


void Foam::cbsProjectionFluid::solvePressure
(
    const surfaceScalarField& phiHbyA,
    const volScalarField& rAU,
    const surfaceScalarField& rAUf,
    const volVectorField& HbyA,
    const surfaceScalarField* phiF
)
{
    while (control_.correctNonOrthogonal())
    {
        fvScalarMatrix pEqn
        (
            immersed_.size()
          ? fvm::laplacian(rAUf, p_) == fvc::div(phiHbyA)
          : fvm::laplacian(rAU, p_) == fvc::div(phiHbyA)
        );

        pEqn.setReference(pRefCell_, pRefValue_);
        for (const fv::immersedMethod& m : immersed_)
        {
            m.constrainPressure(pEqn, p_);
        }
        pEqn.solve(mesh_.solver(p_.select(control_.finalInnerIter())));

        if (control_.finalNonOrthogonalIter())
        {
            // Step III, face part: divergence-free flux
            phi_ = phiHbyA - pEqn.flux();
            if (phiF)
            {
                // the cells: the reconstructed face balance
                U_ = HbyA
                  + rAU
                   *balancedFlux_->reconstruct((*phiF - pEqn.flux())/rAUf);
            }
        }
    }
}


void Foam::cbsProjectionFluid::projection(fvVectorMatrix& UEqn)
{
    const volScalarField rAU(1.0/UEqn.A());

    // Intermediate velocity without pressure gradient and its
    // momentum-interpolated (Rhie-Chow) face flux
    volVectorField HbyA(constrainHbyA(rAU*UEqn.H(), U_, p_));
    surfaceScalarField rAUf("rAUf", fvc::interpolate(rAU));

    const volVectorField::Internal* fb = balancedForce();
    tmp<surfaceScalarField> tphiF;
    if (fb)
    {
        tphiF = balance(*fb, rAU, rAUf, HbyA);
    }
    surfaceScalarField phiHbyA
    (
        "phiHbyA",
        fvc::flux(HbyA)
      + rAUf*fvc::ddtCorr(U_, phi_)
    );
    if (fb)
    {
        phiHbyA += tphiF();
    }

    // Immersed solids: the flux on the faces they hold and no pressure
    // flux through them (fv::immersedMethod; the sharp method's covered
    // cells, immersedBoundary.H)
    for (const fv::immersedMethod& m : immersed_)
    {
        m.constrainFlux(phiHbyA, rAUf);
    }

    if (p_.needReference())
    {
        adjustPhi(phiHbyA, U_, p_);
    }

    // Pressure boundary conditions consistent with the flux
    constrainPressure(p_, U_, phiHbyA, rAU);

    // Step II (paper Eq. 38): pressure Poisson equation, solved again
    // while a windkessel outlet's pressure and the flow it gives disagree
    // (windkesselFvPatchScalarField: Newton steps on the outlet pressure,
    // one per solve)
    for (label outletIter = 1; ; ++outletIter)
    {
        solvePressure(phiHbyA, rAU, rAUf, HbyA, fb ? &tphiF() : nullptr);
        if
        (
            !windkesselOutlets_
         || outletIter >= nOutletIterations_
         || windkesselFvPatchScalarField::allConverged(p_)
        )
        {
            break;
        }
    }

    continuityErrors();

    // Step III (paper Eq. 39): velocity correction. With a sharp immersed
    // solid the covered cells' pressure is set for output and grad p taken
    // with the wall pressure, from one evaluation of the wall values
    if (!fb)
    {
        U_ = HbyA - rAU*correctedPressureGradient();
    }
    U_.correctBoundaryConditions();
    fvOptions_.correct(U_);
}


const Foam::volVectorField::Internal*
Foam::cbsProjectionFluid::balancedForce() const
{
    const volVectorField::Internal* fb = nullptr;
    for (const fv::immersedMethod& m : immersed_)
    {
        const volVectorField::Internal* f = m.balancedForce();
        if (f && fb)
        {
            FatalErrorInFunction
                << "Two fvOptions give a balanced force (" << m.name()
                << " among them): one carried immersed solid per mesh is"
                << " supported; put all its parts in one constant/"
                << "solidProperties mesh" << exit(FatalError);
        }
        fb = f ? f : fb;
    }
    return fb;
}


Foam::tmp<Foam::volVectorField>
Foam::cbsProjectionFluid::pressureGradient() const
{
    // grad p of Step I: the immersed method's (with its wall pressure),
    // else Gauss
    tmp<volVectorField> tgradp;
    for (const fv::immersedMethod& m : immersed_)
    {
        tmp<volVectorField> g(m.pressureGradient(p_));
        if (g.valid() && tgradp.valid())
        {
            FatalErrorInFunction
                << "Two fvOptions hold the wall pressure (" << m.name()
                << " among them): one sharp immersed solid per mesh is"
                << " supported; put all its parts in one constant/"
                << "solidProperties mesh" << exit(FatalError);
        }
        if (g.valid())
        {
            tgradp = g;
        }
    }
    if (tgradp.valid())
    {
        return tgradp;
    }
    return fvc::grad(p_);
}


Foam::tmp<Foam::volVectorField>
Foam::cbsProjectionFluid::correctedPressureGradient()
{
    // grad p of Step III: as pressureGradient(), the immersed method also
    // setting the pressure of the cells out of the pressure equation
    for (const fv::immersedMethod& m : immersed_)
    {
        tmp<volVectorField> g(m.correctPressure(p_));
        if (g.valid())
        {
            return g;
        }
    }
    return fvc::grad(p_);
}


void Foam::cbsProjectionFluid::continuityErrors()
{
    const scalar dt = mesh_.time().deltaTValue();
    const volScalarField contErr(fvc::div(phi_));

    const scalar sumLocalContErr =
        dt*mag(contErr)().weightedAverage(mesh_.V()).value();
    const scalar globalContErr =
        dt*contErr.weightedAverage(mesh_.V()).value();
    cumulativeContErr_ += globalContErr;

    Info<< "time step continuity errors : sum local = " << sumLocalContErr
        << ", global = " << globalContErr
        << ", cumulative = " << cumulativeContErr_ << endl;
}


void Foam::cbsProjectionFluid::checkFinite() const
{
    const scalar magU = gSumMag(U_.primitiveField());
    const scalar magP = gSumMag(p_.primitiveField());

    if (!std::isfinite(magU) || !std::isfinite(magP))
    {
        FatalErrorInFunction
            << "The solution is no longer finite at time "
            << mesh_.time().timeName() << " (sum |U| = " << magU
            << ", sum |p| = " << magP << ")." << nl
            << "    Nothing of this time step is written; the last written"
            << " time directory is the last good state." << nl
            << "    Reduce deltaT or maxCo in system/controlDict, or check"
            << " the boundary conditions and momentum sources, then restart"
            << " from the last written time (startFrom latestTime)."
            << exit(FatalError);
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::cbsProjectionFluid::courantNumber() const
{
    scalar CoNum = 0;
    if (mesh_.nInternalFaces())
    {
        const scalarField sumPhi
        (
            fvc::surfaceSum(mag(phi_))().primitiveField()
        );
        CoNum = 0.5*gMax(sumPhi/mesh_.V().field())
            *mesh_.time().deltaTValue();
    }
    return CoNum;
}


Foam::scalar Foam::cbsProjectionFluid::diffusionNumber() const
{
    // Di = 0.5 dt max_P sum_f nu_f |S_f| deltaCoeff_f / V_P: the viscous
    // counterpart of courantNumber() (boundary faces count with their
    // deltaCoeffs, the centre-to-face distance; empty patches have none)
    const volScalarField nu
    (
        turbulence_.valid() ? turbulence_->nuEff() : laminarTransport_.nu()
    );
    const scalarField sumD
    (
        fvc::surfaceSum
        (
            mesh_.magSf()*mesh_.deltaCoeffs()*fvc::interpolate(nu)
        )().primitiveField()
    );
    return 0.5*gMax(sumD/mesh_.V().field())*mesh_.time().deltaTValue();
}


Foam::scalar Foam::cbsProjectionFluid::diffusionLimit
(
    const scalar DiNum
) const
{
    const dictionary& controlDict = mesh_.time().controlDict();
    if (!controlDict.found("maxDi"))
    {
        return 1;
    }
    const scalar maxDi = controlDict.get<scalar>("maxDi");
    if (maxDi <= 0)
    {
        FatalIOErrorInFunction(controlDict)
            << "maxDi " << maxDi << " in " << controlDict.name()
            << " must be positive (the largest cell diffusion number,"
            << " 0.5 dt sum_f nu |S_f|/|d_f| / V; 1 keeps nu dt/h^2 at 0.5"
            << " in 2D), or remove the entry" << exit(FatalIOError);
    }
    return min(1.0, maxDi/(DiNum + VSMALL));
}


Foam::scalar Foam::cbsProjectionFluid::maxDeltaT() const
{
    // controlDict maxDeltaT: a number, or a Function1 of time (a table,
    // e.g. a smaller step once a closed valve's leaflets stiffen), read
    // afresh so that runTimeModifiable edits take effect
    const Time& runTime = mesh_.time();
    const dictionary& controlDict = runTime.controlDict();
    const entry* e = controlDict.findEntry("maxDeltaT", keyType::LITERAL);
    if (!e)
    {
        return GREAT;
    }
    // made again only when the entry's text changes (a tableFile is not
    // read from disk every step)
    OStringStream text;
    text << *e;
    if (!maxDeltaT_.valid() || text.str() != maxDeltaTEntry_)
    {
        maxDeltaT_ = Function1<scalar>::New("maxDeltaT", controlDict);
        maxDeltaTEntry_ = text.str();
    }
    const scalar dt = maxDeltaT_->value(runTime.value());
    if (!(dt > 0))
    {
        FatalIOErrorInFunction(controlDict)
            << "maxDeltaT is " << dt << " at t = " << runTime.value()
            << " in " << controlDict.name() << ": it must be positive"
            << " (a number or a Function1 of time, e.g. table ((0 1e-5)"
            << " (0.04 5e-6)))" << exit(FatalIOError);
    }
    return dt;
}


void Foam::cbsProjectionFluid::setInitialDeltaT()
{
    const Time& runTime = mesh_.time();
    const dictionary& controlDict = runTime.controlDict();

    if (controlDict.lookupOrDefault("adjustTimeStep", false))
    {
        const scalar maxCo = controlDict.get<scalar>("maxCo");
        const scalar CoNum = courantNumber();
        if (CoNum > SMALL)
        {
            const_cast<Time&>(runTime).setDeltaT
            (
                min
                (
                    maxCo*runTime.deltaTValue()/CoNum,
                    min(runTime.deltaTValue(), maxDeltaT())
                )
            );
        }
        if (controlDict.found("maxDi"))
        {
            const_cast<Time&>(runTime).setDeltaT
            (
                diffusionLimit(diffusionNumber())*runTime.deltaTValue()
            );
        }
    }
}


void Foam::cbsProjectionFluid::adjustDeltaT()
{
    Time& runTime = const_cast<Time&>(mesh_.time());
    const dictionary& controlDict = runTime.controlDict();

    const scalar CoNum = courantNumber();
    Info<< "Courant Number max: " << CoNum << endl;

    if (controlDict.lookupOrDefault("adjustTimeStep", false))
    {
        const scalar maxCo = controlDict.get<scalar>("maxCo");
        const scalar maxDeltaT = this->maxDeltaT();

        // Same damping of increases as OpenFOAM's setDeltaT.H
        const scalar maxDeltaTFact = maxCo/(CoNum + SMALL);
        const scalar deltaTFact =
            min(min(maxDeltaTFact, 1.0 + 0.1*maxDeltaTFact), 1.2);

        runTime.setDeltaT(min(deltaTFact*runTime.deltaTValue(), maxDeltaT));
        if (controlDict.found("maxDi"))
        {
            const scalar DiNum = diffusionNumber();
            const scalar factor = diffusionLimit(DiNum);
            runTime.setDeltaT(factor*runTime.deltaTValue());
            Info<< "Diffusion Number max: " << factor*DiNum << endl;
        }
        Info<< "deltaT = " << runTime.deltaTValue() << endl;
    }
}


void Foam::cbsProjectionFluid::solve()
{
    stepStart();

    // Step I
    tmp<fvVectorMatrix> tUEqn(intermediateMomentum());

    // Steps II and III (repeated nCorrectors times, 1 = plain projection)
    while (control_.correct())
    {
        projection(tUEqn.ref());
    }
    if (windkesselOutlets_)
    {
        windkesselFvPatchScalarField::report(p_);
    }

    laminarTransport_.correct();
    if (turbulence_.valid())
    {
        turbulence_->correct();
    }

    checkFinite();
}


// ************************************************************************* //
