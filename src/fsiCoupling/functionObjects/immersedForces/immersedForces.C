/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

#include "immersedForces.H"
#include "immersedMethod.H"
#include "fvOptions.H"
#include "volFields.H"
#include "singlePhaseTransportModel.H"
#include "turbulenceModel.H"
#include "OSspecific.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(immersedForces, 0);
    addToRunTimeSelectionTable(functionObject, immersedForces, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::UPtrList<const Foam::fv::immersedMethod>
Foam::functionObjects::immersedForces::methods() const
{
    UPtrList<const fv::immersedMethod> methods;
    if (!mesh_.foundObject<fv::options>("fvOptions"))
    {
        return methods;
    }
    const fv::optionList& opts =
        mesh_.lookupObject<fv::options>("fvOptions");
    forAll(opts, i)
    {
        const fv::immersedMethod* m =
            dynamic_cast<const fv::immersedMethod*>(&opts[i]);
        if (m)
        {
            methods.append(m);
        }
    }
    return methods;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::functionObjects::immersedForces::immersedForces
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    fvMeshFunctionObject(name, runTime, dict),
    patches_(),
    rhoFluid_(0),
    solid_(true),
    UName_("U"),
    pName_("p"),
    total_(Zero),
    patchForce_(Zero),
    solidForce_(Zero)
{
    read(dict);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::functionObjects::immersedForces::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    const wordRes names(dict.get<wordRes>("patches"));
    patches_ = mesh_.boundaryMesh().patchSet(names).sortedToc();
    if (names.size() && patches_.empty())
    {
        FatalIOErrorInFunction(dict)
            << "No patch of " << mesh_.boundaryMesh().names()
            << " matches 'patches' " << names << " in " << dict.name()
            << exit(FatalIOError);
    }
    rhoFluid_ = dict.get<scalar>("rhoFluid");
    if (rhoFluid_ <= 0)
    {
        FatalIOErrorInFunction(dict)
            << "rhoFluid " << rhoFluid_ << " in " << dict.name()
            << " is not positive" << exit(FatalIOError);
    }
    solid_ = dict.getOrDefault<bool>("solid", true);
    UName_ = dict.getOrDefault<word>("U", "U");
    pName_ = dict.getOrDefault<word>("p", "p");
    return true;
}


bool Foam::functionObjects::immersedForces::execute()
{
    const volVectorField& U = lookupObject<volVectorField>(UName_);
    const volScalarField& p = lookupObject<volScalarField>(pName_);
    // The viscous traction with the turbulence model's effective viscosity
    // when the solver has one (nu + nut: with wall functions nut holds the
    // wall's shear stress), else the transport model's nu
    const turbulenceModel* turbulence =
        findObject<turbulenceModel>(turbulenceModel::propertiesName);
    const tmp<volScalarField> tnu
    (
        turbulence
      ? turbulence->nuEff()
      : lookupObject<singlePhaseTransportModel>("transportProperties").nu()
    );
    const UPtrList<const fv::immersedMethod> methods(this->methods());
    const auto covered = [&methods](const label celli)
    {
        for (const fv::immersedMethod& m : methods)
        {
            if (m.covers(celli))
            {
                return true;
            }
        }
        return false;
    };

    patchForce_ = Zero;
    for (const label patchi : patches_)
    {
        const fvPatch& fp = mesh_.boundary()[patchi];
        const vectorField& Sf = fp.Sf();
        const scalarField& magSf = fp.magSf();
        const scalarField& pp = p.boundaryField()[patchi];
        const vectorField dUdn(U.boundaryField()[patchi].snGrad());
        const scalarField& nu = tnu().boundaryField()[patchi];
        const labelUList& cells = fp.faceCells();
        forAll(Sf, facei)
        {
            if (covered(cells[facei]))
            {
                continue;
            }
            patchForce_ +=
                rhoFluid_*(pp[facei]*Sf[facei] - nu[facei]*dUdn[facei]*magSf[facei]);
        }
    }
    reduce(patchForce_, sumOp<vector>());
    solidForce_ = Zero;
    if (solid_)
    {
        for (const fv::immersedMethod& m : methods)
        {
            solidForce_ += m.fluidForceOnSolid();
        }
    }
    total_ = patchForce_ + solidForce_;
    Log << type() << ' ' << name() << ": force " << total_ << " (patches "
        << patchForce_ << ", immersed solid " << solidForce_ << ")" << endl;
    return true;
}


bool Foam::functionObjects::immersedForces::write()
{
    if (!Pstream::master())
    {
        return true;
    }
    const Time& runTime = time_;
    if (!file_.valid())
    {
        const fileName dir
        (
            (Pstream::parRun() ? runTime.path()/".." : runTime.path())
           /"postProcessing"/name()/runTime.timeName(runTime.startTime().value())
        );
        mkDir(dir);
        file_.reset(new OFstream(dir/"forces.dat"));
        file_()
            << "# immersedForces " << name() << ": force of the fluid [N] on"
            << " patches";
        for (const label patchi : patches_)
        {
            file_() << ' ' << mesh_.boundaryMesh()[patchi].name();
        }
        file_()
            << " (faces of covered"
            << " cells left out) and on the immersed solid" << nl
            << "# time Fx Fy Fz patchFx patchFy patchFz solidFx solidFy"
            << " solidFz" << endl;
    }
    OFstream& os = file_();
    os.precision(10);
    os  << runTime.value() << ' '
        << total_.x() << ' ' << total_.y() << ' ' << total_.z() << ' '
        << patchForce_.x() << ' ' << patchForce_.y() << ' '
        << patchForce_.z() << ' '
        << solidForce_.x() << ' ' << solidForce_.y() << ' '
        << solidForce_.z() << endl;
    return true;
}


// ************************************************************************* //
