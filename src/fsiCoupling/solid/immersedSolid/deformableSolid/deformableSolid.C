/*---------------------------------------------------------------------------*\
    isfem: immersed smoothed finite element method (fsiCoupling)
\*---------------------------------------------------------------------------*/

// The solid library first (Eigen), then OpenFOAM
#include "dynamics/ExplicitSolid.hpp"
#include "io/FibreFile.hpp"
#include "io/SurfaceFile.hpp"
#include "io/VtuWriter.hpp"
#include "material/Material.hpp"
#include "mesh/TetMesh.hpp"
#include "smoothing/SmoothingDomains.hpp"

#include "deformableSolid.H"
#include "addToRunTimeSelectionTable.H"
#include "Switch.H"
#include "OFstream.H"
#include "IFstream.H"

#include <sstream>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace immersedSolids
{
    defineTypeNameAndDebug(deformable, 0);
    addToRunTimeSelectionTable(immersedSolid, deformable, dictionary);
}
}


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

smoothedSolid::Vec3 toVec3(const vector& v)
{
    return smoothedSolid::Vec3(v.x(), v.y(), v.z());
}

// Component mask from a word of letters x, y, z
std::array<bool, 3> componentMask
(
    const word& w,
    const dictionary& dict,
    const word& key
)
{
    std::array<bool, 3> m{{false, false, false}};
    for (const char c : w)
    {
        if (c < 'x' || c > 'z')
        {
            FatalIOErrorInFunction(dict)
                << "Entry '" << key << "' in " << dict.name()
                << ": components must be letters of xyz, got '" << w << "'"
                << exit(FatalIOError);
        }
        m[c - 'x'] = true;
    }
    return m;
}

// Run the solid library's own checks, reporting an error against the
// entry key of dictionary d
template<class Action>
void guarded(const dictionary& d, const word& key, Action f)
{
    try
    {
        f();
    }
    catch (const smoothedSolid::Error& err)
    {
        FatalIOErrorInFunction(d)
            << "Entry '" << key << "' in " << d.name() << ": "
            << err.what() << exit(FatalIOError);
    }
}

// FatalIOError for a keyword outside 'allowed'
void checkKeys(const dictionary& dict, const wordList& allowed)
{
    for (const entry& e : dict)
    {
        if (!allowed.found(e.keyword()))
        {
            FatalIOErrorInFunction(dict)
                << "Unknown keyword '" << e.keyword() << "' in "
                << dict.name() << nl
                << "    Valid keywords: " << flatOutput(allowed)
                << exit(FatalIOError);
        }
    }
}

// The material of the sub-dictionary 'material' (smoothedSolid's case-file
// 'material' entry as keywords)
std::shared_ptr<smoothedSolid::Material> makeMaterial(const dictionary& d)
{
    using namespace smoothedSolid;
    const word type(d.get<word>("type"));

    // kappa given, or from nu (Eq. 27)
    auto kappa = [&](scalar c10, scalar c01)
    {
        if (d.found("kappa"))
        {
            return d.get<scalar>("kappa");
        }
        return MooneyRivlin::kappaFromPoisson(c10, c01, d.get<scalar>("nu"));
    };

    try
    {
        if (type == "neoHookean")
        {
            checkKeys(d, {"type", "mu", "K", "rho"});
            return std::make_shared<NeoHookean>
            (
                d.get<scalar>("mu"), d.get<scalar>("K"), d.get<scalar>("rho")
            );
        }
        if (type == "mooneyRivlin")
        {
            checkKeys(d, {"type", "c10", "c01", "kappa", "nu", "rho"});
            const scalar c10 = d.get<scalar>("c10");
            const scalar c01 = d.get<scalar>("c01");
            return std::make_shared<MooneyRivlin>
            (
                c10, c01, kappa(c10, c01), d.get<scalar>("rho")
            );
        }
        if (type == "holzapfelGasserOgden")
        {
            checkKeys
            (
                d,
                {"type", "c10", "c01", "k1", "k2", "kappa", "nu", "rho"}
            );
            const scalar c10 = d.get<scalar>("c10");
            const scalar c01 = d.getOrDefault<scalar>("c01", 0);
            return std::make_shared<HolzapfelGasserOgden>
            (
                c10, c01, d.get<scalar>("k1"), d.get<scalar>("k2"),
                kappa(c10, c01), d.get<scalar>("rho")
            );
        }
        if (type == "stVenantKirchhoff")
        {
            checkKeys(d, {"type", "mu", "lambda", "nu", "rho"});
            const scalar mu = d.get<scalar>("mu");
            scalar lambda = 0;
            if (d.found("lambda"))
            {
                lambda = d.get<scalar>("lambda");
            }
            else
            {
                const scalar nu = d.get<scalar>("nu");
                if (!(nu > 0 && nu < 0.5))
                {
                    FatalIOErrorInFunction(d)
                        << "Entry 'nu' in " << d.name()
                        << " must lie in (0, 0.5)" << exit(FatalIOError);
                }
                lambda = 2*mu*nu/(1 - 2*nu);
            }
            return std::make_shared<StVenantKirchhoff>
            (
                mu, lambda, d.get<scalar>("rho")
            );
        }
    }
    catch (const smoothedSolid::Error& err)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'material' in " << d.name() << ": " << err.what()
            << exit(FatalIOError);
    }

    FatalIOErrorInFunction(d)
        << "Unknown material type '" << type << "' in " << d.name() << nl
        << "    Valid types: (neoHookean mooneyRivlin stVenantKirchhoff"
        << " holzapfelGasserOgden)"
        << exit(FatalIOError);
    return nullptr;
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::immersedSolids::deformable::fromSolid()
{
    const std::vector<smoothedSolid::Vec3> x = solid_->currentCoordinates();
    const std::vector<smoothedSolid::Vec3>& v = solid_->velocity();
    forAll(points_, i)
    {
        points_[i] = point(x[i](0), x[i](1), x[i](2));
        velocities_[i] = vector(v[i](0), v[i](1), v[i](2));
    }
}


smoothedSolid::SolidOptions
Foam::immersedSolids::deformable::readOptions() const
{
    smoothedSolid::SolidOptions opt;
    {
        const word f(dict_.getOrDefault<word>("formulation", "selective"));
        guarded(dict_, "formulation", [&]
        {
            opt.formulation = smoothedSolid::formulationFromString(f);
        });
    }
    opt.safety = dict_.getOrDefault<scalar>("safety", opt.safety);
    opt.damping = dict_.getOrDefault<scalar>("damping", opt.damping);
    // stiffness-proportional damping beta [s] (smoothedSolid SolidOptions)
    opt.stiffnessDamping =
        dict_.getOrDefault<scalar>("stiffnessDamping", opt.stiffnessDamping);
    if (!(opt.stiffnessDamping >= 0))
    {
        FatalIOErrorInFunction(dict_)
            << "Entry 'stiffnessDamping' in " << dict_.name() << " is "
            << opt.stiffnessDamping << ": give a non-negative time [s] (the"
            << " damping ratio of a mode of angular frequency omega is"
            << " stiffnessDamping omega/2; 0 switches it off)"
            << exit(FatalIOError);
    }

    return opt;
}


void Foam::immersedSolids::deformable::readFibres()
{
    smoothedSolid::ExplicitSolid& s = *solid_;
    // Fibres
    if (dict_.found("fibres"))
    {
        const dictionary& f = dict_.subDict("fibres");
        if (!s.material().hasFibres())
        {
            FatalIOErrorInFunction(f)
                << "Entry 'fibres' in " << dict_.name() << ": material "
                << s.material().name() << " has no fibres: remove this entry"
                << " or use holzapfelGasserOgden" << exit(FatalIOError);
        }
        const word layout(f.get<word>("type"));
        std::vector<smoothedSolid::Vec3> a(nElements());
        if (layout == "uniform")
        {
            checkKeys(f, {"type", "direction"});
            const vector d(f.get<vector>("direction"));
            for (auto& ai : a) { ai = toVec3(d); }
        }
        else if (layout == "cylindrical")
        {
            checkKeys(f, {"type", "origin", "axis"});
            const point o(f.get<point>("origin"));
            const vector n(normalised(f.get<vector>("axis")));
            forAll(elements_, e)
            {
                const solidTet& t = elements_[e];
                const vector r =
                    0.25*(points0_[t[0]] + points0_[t[1]]
                        + points0_[t[2]] + points0_[t[3]]) - o;
                const vector et(n ^ r);
                if (mag(et) < 1e-9*max(1.0, mag(r)))
                {
                    FatalIOErrorInFunction(f)
                        << "Entry 'fibres' in " << dict_.name()
                        << ": element " << e << " has its centroid on the"
                        << " axis, where the circumferential direction is"
                        << " undefined" << exit(FatalIOError);
                }
                a[e] = toVec3(et/mag(et));
            }
        }
        else if (layout == "file")
        {
            // one direction per element in the mesh's order (e.g. the
            // .circumferential file of makeValveMeshes), relative to the case
            checkKeys(f, {"type", "file"});
            fileName name(f.get<fileName>("file"));
            name.expand();
            if (!name.isAbsolute())
            {
                name = runTime_.globalPath()/name;
            }
            guarded(f, "fibres", [&]
            {
                a = smoothedSolid::readFibreDirections(name, nElements());
            });
        }
        else
        {
            FatalIOErrorInFunction(f)
                << "Unknown fibre layout '" << layout << "' in " << f.name()
                << nl << "    Valid types: (uniform cylindrical file)"
                << exit(FatalIOError);
        }
        guarded(f, "fibres", [&] { s.setFibreDirections(std::move(a)); });
    }
    else if (s.material().hasFibres())
    {
        FatalIOErrorInFunction(dict_)
            << "Entry 'fibres' missing in " << dict_.name() << ": material "
            << s.material().name() << " needs fibre directions"
            << exit(FatalIOError);
    }

}


void Foam::immersedSolids::deformable::readConstraints()
{
    smoothedSolid::ExplicitSolid& s = *solid_;
    // Fixed node sets
    if (dict_.found("fixed"))
    {
        const dictionary& f = dict_.subDict("fixed");
        for (const entry& e : f)
        {
            nodeSet(e.keyword(), f, e.keyword());
            const std::array<bool, 3> m =
                componentMask(f.get<word>(e.keyword()), f, e.keyword());
            guarded(f, e.keyword(), [&] { s.fix(e.keyword(), m); });
        }
    }

    // Prescribed velocities of node sets
    if (dict_.found("prescribedMotion"))
    {
        const dictionary& pm = dict_.subDict("prescribedMotion");
        for (const entry& e : pm)
        {
            const dictionary& d = e.dict();
            checkKeys(d, {"velocity", "components"});
            nodeSet(e.keyword(), pm, e.keyword());
            const std::array<bool, 3> m = componentMask
            (
                d.getOrDefault<word>("components", "xyz"), d, "components"
            );
            prescribed_.append(Function1<vector>::New("velocity", d));
            const Function1<vector>* v = &prescribed_.last();
            guarded(pm, e.keyword(), [&]
            {
                s.prescribeVelocity
                (
                    e.keyword(),
                    [v](double t, const smoothedSolid::Vec3&)
                    {
                        return toVec3(v->value(t));
                    },
                    m
                );
            });
        }
    }
}


void Foam::immersedSolids::deformable::readLoadsAndContact()
{
    smoothedSolid::ExplicitSolid& s = *solid_;
    if (dict_.found("bodyForce"))
    {
        s.setBodyForce(toVec3(dict_.get<vector>("bodyForce")));
    }

    // Contact (paper Eq. 43)
    if (dict_.found("contact"))
    {
        const dictionary& c = dict_.subDict("contact");
        checkKeys
        (
            c,
            {
                "self", "dampingRatio", "stepFraction", "penaltyScale",
                "depthFraction", "kinematic", "volumeLimit"
            }
        );
        smoothedSolid::ContactOptions co;
        co.selfContact = c.getOrDefault<Switch>("self", false);
        co.dampingRatio = c.getOrDefault<scalar>("dampingRatio", co.dampingRatio);
        co.stepFraction = c.getOrDefault<scalar>("stepFraction", co.stepFraction);
        co.penaltyScale = c.getOrDefault<scalar>("penaltyScale", co.penaltyScale);
        co.depthFraction =
            c.getOrDefault<scalar>("depthFraction", co.depthFraction);
        co.kinematic = c.getOrDefault<Switch>("kinematic", co.kinematic);
        co.volumeLimit =
            c.getOrDefault<scalar>("volumeLimit", co.volumeLimit);
        if (co.volumeLimit > 0 && !co.kinematic)
        {
            FatalIOErrorInFunction(c)
                << "Entry 'contact' in " << dict_.name() << ": volumeLimit "
                << co.volumeLimit << " limits the motion of a solid the"
                << " fluid carries (immersedElasticForce); set 'kinematic"
                << " yes' as well, or remove volumeLimit"
                << exit(FatalIOError);
        }
        guarded(dict_, "contact", [&] { s.enableContact(co); });
    }
    if (dict_.found("contactSurfaces"))
    {
        const dictionary& cs = dict_.subDict("contactSurfaces");
        for (const entry& e : cs)
        {
            const dictionary& d = e.dict();
            checkKeys(d, {"file", "flip"});
            fileName f(d.get<fileName>("file"));
            f.expand();
            if (!f.isAbsolute())
            {
                f = runTime_.globalPath()/f;
            }
            const bool flip = d.getOrDefault<Switch>("flip", false);
            guarded(cs, e.keyword(), [&]
            {
                s.addRigidSurface(smoothedSolid::readRigidSurface(f, flip));
            });
        }
    }
}


void Foam::immersedSolids::deformable::readOutput()
{
    if (dict_.found("output"))
    {
        const dictionary& o = dict_.subDict("output");
        checkKeys(o, {"directory", "probes"});
        fileName dir(o.getOrDefault<fileName>("directory", "VTK/solid"));
        if (!dir.isAbsolute())
        {
            dir = runTime_.globalPath()/dir;
        }
        guarded(o, "directory", [&]
        {
            vtu_.reset(new smoothedSolid::VtuSeries(dir, "solid"));
            // a restarted run continues the collection (later data sets,
            // from a run that went further, are dropped)
            if (Pstream::master())
            {
                vtu_->resume(runTime_.value());
            }
        });
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::immersedSolids::deformable::deformable
(
    const Time& runTime,
    const IOdictionary& dict
)
:
    immersedSolid(runTime, dict),
    lastSubSteps_(0),
    stiffnessU_(),
    stiffnessF_(),
    stiffnessHMin_(-1),
    stored_(),
    storedVelocities_(),
    storedTime_(0)
{
    checkKeywords
    (
        dict_,
        {
            "type", "mesh", "formulation", "material", "fibres", "fixed",
            "prescribedMotion", "safety", "damping", "stiffnessDamping",
            "bodyForce", "contact",
            "contactSurfaces", "output"
        }
    );

    const smoothedSolid::SolidOptions opt(readOptions());
    const dictionary& matDict = dict_.subDict("material");
    std::shared_ptr<smoothedSolid::Material> material = makeMaterial(matDict);

    guarded(dict_, "mesh", [&]
    {
        solid_.reset
        (
            new smoothedSolid::ExplicitSolid
            (
                smoothedSolid::TetMesh::fromGmsh(meshFile()),
                material,
                opt
            )
        );
    });

    readFibres();
    readConstraints();
    readLoadsAndContact();
    readOutput();

    fromSolid();
}


// * * * * * * * * * * * * * * * * Destructor  * * * * * * * * * * * * * * * //

Foam::immersedSolids::deformable::~deformable()
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::immersedSolids::deformable::advance(const scalar dt)
{
    string why;
    if (!tryAdvance(dt, why))
    {
        FatalErrorInFunction
            << "The immersed solid failed at time " << time_ << ": "
            << why.c_str() << exit(FatalError);
    }
}


bool Foam::immersedSolids::deformable::tryAdvance
(
    const scalar dt,
    string& why
)
{
    std::vector<smoothedSolid::Vec3>& f = solid_->externalForce();
    forAll(externalForce_, i)
    {
        f[i] = toVec3(externalForce_[i]);
    }
    try
    {
        lastSubSteps_ = solid_->advance(dt);
    }
    catch (const smoothedSolid::Error& err)
    {
        why = err.what();
        return false;
    }
    time_ += dt;
    // the velocity the fluid sees: the mean over the step, (x^{n+1} -
    // x^n)/dt, consistent with the solid's displacement (the faces' flux
    // sweeps the volume the solid moved through) and blind to the
    // solid's vibrations faster than the fluid step, which the
    // half-step velocity of the last sub-step would hand to the fluid
    // at a random phase
    const pointField x0(points_);
    fromSolid();
    velocities_ = (points_ - x0)/dt;
    return true;
}


void Foam::immersedSolids::deformable::setState
(
    const pointField&,
    const vectorField&
)
{
    FatalErrorInFunction
        << "A deformable immersed solid's configuration follows from its"
        << " dynamics; it cannot be set directly"
        << exit(FatalError);
}


void Foam::immersedSolids::deformable::storeState()
{
    std::ostringstream os(std::ios::binary);
    solid_->saveState(os, "the solid's snapshot");
    stored_ = os.str();
    storedVelocities_ = velocities_;
    storedTime_ = time_;
}


void Foam::immersedSolids::deformable::restoreState()
{
    if (stored_.empty())
    {
        FatalErrorInFunction
            << "No stored state to go back to" << exit(FatalError);
    }
    std::istringstream is(stored_, std::ios::binary);
    solid_->loadState(is, "the solid's snapshot");
    time_ = storedTime_;
    fromSolid();
    velocities_ = storedVelocities_;
}


Foam::tmp<Foam::scalarField>
Foam::immersedSolids::deformable::lumpedMass() const
{
    const std::vector<double>& m = solid_->lumpedMass();
    auto tmass = tmp<scalarField>::New(label(m.size()));
    forAll(tmass(), i)
    {
        tmass.ref()[i] = m[i];
    }
    return tmass;
}


Foam::tmp<Foam::vectorField>
Foam::immersedSolids::deformable::freeComponents() const
{
    const std::vector<smoothedSolid::Vec3> f = solid_->freeComponents();
    auto tfree = tmp<vectorField>::New(label(f.size()));
    forAll(tfree(), i)
    {
        tfree.ref()[i] = vector(f[i](0), f[i](1), f[i](2));
    }
    return tfree;
}


bool Foam::immersedSolids::deformable::interactionForce
(
    const scalar dt,
    vectorField& f,
    string& why
)
{
    std::vector<smoothedSolid::Vec3>& fe = solid_->externalForce();
    forAll(externalForce_, i)
    {
        fe[i] = toVec3(externalForce_[i]);
    }
    try
    {
        const std::vector<smoothedSolid::Vec3> fs =
            solid_->interactionForce(dt);
        f.setSize(fs.size());
        forAll(f, i)
        {
            f[i] = vector(fs[i](0), fs[i](1), fs[i](2));
        }
    }
    catch (const smoothedSolid::Error& err)
    {
        why = err.what();
        return false;
    }
    return true;
}


Foam::scalar Foam::immersedSolids::deformable::stiffnessDamping() const
{
    return solid_->options().stiffnessDamping;
}


void Foam::immersedSolids::deformable::setStiffnessDamping(const scalar beta)
{
    try
    {
        solid_->setStiffnessDamping(beta);
    }
    catch (const smoothedSolid::Error& err)
    {
        FatalIOErrorInFunction(dict_)
            << err.what() << exit(FatalIOError);
    }
}


bool Foam::immersedSolids::deformable::stiffnessAction
(
    const vectorField& w,
    vectorField& dF,
    string& why
) const
{
    const std::vector<smoothedSolid::Vec3>& u = solid_->displacement();
    const std::vector<smoothedSolid::Vec3> free = solid_->freeComponents();
    if (label(u.size()) != w.size())
    {
        why = "stiffnessAction: " + Foam::name(w.size())
            + " nodal motions for a solid of " + Foam::name(label(u.size()))
            + " nodes";
        return false;
    }
    dF.setSize(w.size());
    const scalar wMax = max(mag(w));
    if (!(wMax > 0))
    {
        dF = Zero;
        return true;
    }
    // K_T w = (f_int(u) - f_int(u + eps w))/eps + O(eps |w|^2 f_int''):
    // a forward difference (Nocedal & Wright, Numerical Optimization, 2nd
    // ed., Sect. 8.1), f_int(u) computed once for all the actions at one
    // displacement (a step's GMRES solve applies K_T to 5-15 directions);
    // the solid is the same on every rank: no reduction. eps |w| = 1e-5
    // of the smallest element height: the truncation, relative to K_T w,
    // is about eps |w| over the length on which the stiffness changes (at
    // least an element's height), 1e-5, the round-off about 1e-16/1e-5;
    // both far below the implicit force's tolerance (1e-2). The central
    // difference, at twice the cost, agreed within 8e-6 of the largest
    // nodal |K_T w| on the coarse valve (in ejection and in diastole)
    const smoothedSolid::TetMesh& mesh = solid_->mesh();
    if (stiffnessHMin_ < 0)
    {
        scalar hMin = GREAT;
        for (int e = 0; e < mesh.nElements(); ++e)
        {
            hMin = min(hMin, mesh.elementHeight(e));
        }
        stiffnessHMin_ = hMin;
    }
    const scalar eps = 1e-5*stiffnessHMin_/wMax;
    try
    {
        bool same = (stiffnessU_.size() == 3*u.size());
        for (std::size_t i = 0; same && i < u.size(); ++i)
        {
            same =
                stiffnessU_[3*i] == u[i](0)
             && stiffnessU_[3*i + 1] == u[i](1)
             && stiffnessU_[3*i + 2] == u[i](2);
        }
        if (!same)
        {
            const std::vector<smoothedSolid::Vec3> f0 =
                solid_->internalForce(u);
            stiffnessU_.resize(3*u.size());
            stiffnessF_.resize(3*u.size());
            for (std::size_t i = 0; i < u.size(); ++i)
            {
                for (int c = 0; c < 3; ++c)
                {
                    stiffnessU_[3*i + c] = u[i](c);
                    stiffnessF_[3*i + c] = f0[i](c);
                }
            }
        }
        std::vector<smoothedSolid::Vec3> up(u);
        forAll(w, i)
        {
            up[i] += eps*toVec3(w[i]).cwiseProduct(free[i]);
        }
        const std::vector<smoothedSolid::Vec3> fp = solid_->internalForce(up);
        forAll(dF, i)
        {
            const smoothedSolid::Vec3 f0
            (
                stiffnessF_[3*i], stiffnessF_[3*i + 1], stiffnessF_[3*i + 2]
            );
            const smoothedSolid::Vec3 k =
                ((f0 - fp[i])/eps).cwiseProduct(free[i]);
            dF[i] = vector(k(0), k(1), k(2));
        }
    }
    catch (const smoothedSolid::Error& err)
    {
        why = err.what();
        return false;
    }
    return true;
}


bool Foam::immersedSolids::deformable::tryMoveWith
(
    vectorField& v,
    const scalar dt,
    string& why
)
{
    std::vector<smoothedSolid::Vec3> d(v.size());
    forAll(v, i)
    {
        d[i] = toVec3(v[i]);
    }
    try
    {
        const smoothedSolid::KinematicContact k =
            solid_->constrainCarriedVelocity(d, dt);
        if (k.held || k.volumeHeld)
        {
            forAll(v, i)
            {
                v[i] = vector(d[i](0), d[i](1), d[i](2));
            }
            Info<< "deformable solid: contact held " << k.held << " of "
                << k.pairs << " pairs (smallest gap " << 1e3*k.minGap
                << " mm)";
            if (k.elements)
            {
                Info<< ", the volume limit " << k.volumeHeld << " of "
                    << k.elements << " elements (smallest J "
                    << k.minVolumeRatio << ")";
            }
            Info<< "; largest velocity change " << k.maxChange
                << " m/s; " << k.sweeps << " sweeps" << endl;
        }
        solid_->moveWith(d, dt);
    }
    catch (const smoothedSolid::Error& err)
    {
        why = err.what();
        return false;
    }
    time_ += dt;
    fromSolid();
    return true;
}


void Foam::immersedSolids::deformable::write(const bool force) const
{
    if (vtu_ && (force || runTime_.writeTime()) && Pstream::master())
    {
        try
        {
            std::vector<double> cp = solid_->contactPressure();
            cp.resize(points_.size(), 0.0);
            vtu_->write
            (
                *solid_, {{"contactPressure", cp}},
                runTime_.timeName(), runTime_.value()
            );
        }
        catch (const smoothedSolid::Error& err)
        {
            FatalErrorInFunction
                << "Entry 'output' in " << dict_.name() << ": "
                << err.what() << exit(FatalError);
        }
    }
}


void Foam::immersedSolids::deformable::writeState(const fileName& dir) const
{
    // the external force held for the next step goes with the state
    std::vector<smoothedSolid::Vec3>& f = solid_->externalForce();
    forAll(externalForce_, i)
    {
        f[i] = toVec3(externalForce_[i]);
    }
    mkDir(dir);
    try
    {
        solid_->saveState(dir/"state");
    }
    catch (const smoothedSolid::Error& err)
    {
        FatalErrorInFunction
            << "Cannot save the immersed solid's state in " << dir << ": "
            << err.what() << exit(FatalError);
    }
    // the velocity the fluid saw (the mean over the last step, advance())
    {
        OFstream os(dir/"velocity");
        os.precision(17);
        os << velocities_;
        if (!os.good())
        {
            FatalErrorInFunction
                << "Cannot write " << os.name() << exit(FatalError);
        }
    }
    try
    {
    }
    catch (const smoothedSolid::Error& err)
    {
        FatalErrorInFunction
            << "Cannot save the immersed solid's state in " << dir << ": "
            << err.what() << exit(FatalError);
    }
}


bool Foam::immersedSolids::deformable::readState(const fileName& dir)
{
    const fileName file(dir/"state");
    if (!isFile(file))
    {
        return false;
    }
    try
    {
        solid_->loadState(file);
    }
    catch (const smoothedSolid::Error& err)
    {
        FatalErrorInFunction
            << "Cannot restart the immersed solid from " << file << ": "
            << err.what() << nl
            << "    The file must come from the same solid mesh, material"
            << " and formulation (constant/solidProperties); remove the"
            << " time directory or start from an earlier one"
            << exit(FatalError);
    }
    time_ = solid_->time();
    const std::vector<smoothedSolid::Vec3>& f = solid_->externalForce();
    externalForce_.setSize(points_.size());
    forAll(externalForce_, i)
    {
        externalForce_[i] = vector(f[i](0), f[i](1), f[i](2));
    }
    fromSolid();
    const fileName vFile(dir/"velocity");
    if (isFile(vFile))
    {
        IFstream is(vFile);
        vectorField v(is);
        if (v.size() != velocities_.size())
        {
            FatalIOErrorInFunction(is)
                << vFile << " has " << v.size() << " velocities for "
                << velocities_.size() << " solid nodes: it belongs to"
                << " another solid mesh" << exit(FatalIOError);
        }
        velocities_ = v;
    }
    return true;
}


// ************************************************************************* //
