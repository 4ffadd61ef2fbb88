#include "io/SolidRun.hpp"

#include "io/FibreFile.hpp"
#include "io/SurfaceFile.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <iomanip>
#include <limits>
#include <sstream>

namespace smoothedSolid {

namespace {

std::array<bool, 3> componentMask(const CaseFile& c, const CaseEntry& e, std::size_t i)
{
    if (i >= e.args.size()) return {true, true, true};
    std::array<bool, 3> m{false, false, false};
    for (char ch : e.args[i]) {
        if (ch < 'x' || ch > 'z') c.fail(e, "components must be letters of xyz");
        m[ch - 'x'] = true;
    }
    return m;
}

std::shared_ptr<Material> makeMaterial(const CaseFile& c, const CaseEntry& e)
{
    if (e.args.empty()) c.fail(e, "expected a material type");
    const std::string& type = e.args[0];
    try {
        if (type == "neoHookean") {
            return std::make_shared<NeoHookean>(c.named(e, "mu"), c.named(e, "K"),
                                                c.named(e, "rho"));
        }
        if (type == "mooneyRivlin") {
            const double c10 = c.named(e, "c10"), c01 = c.named(e, "c01");
            bool hasKappa = false;
            double kappa = c.named(e, "kappa", &hasKappa);
            if (!hasKappa) kappa = MooneyRivlin::kappaFromPoisson(c10, c01, c.named(e, "nu"));
            return std::make_shared<MooneyRivlin>(c10, c01, kappa, c.named(e, "rho"));
        }
        if (type == "holzapfelGasserOgden") {
            const double c10 = c.named(e, "c10");
            bool hasC01 = false, hasKappa = false;
            double c01 = c.named(e, "c01", &hasC01);
            if (!hasC01) c01 = 0;
            double kappa = c.named(e, "kappa", &hasKappa);
            if (!hasKappa) kappa = MooneyRivlin::kappaFromPoisson(c10, c01, c.named(e, "nu"));
            return std::make_shared<HolzapfelGasserOgden>(c10, c01, c.named(e, "k1"),
                                                          c.named(e, "k2"), kappa,
                                                          c.named(e, "rho"));
        }
        if (type == "stVenantKirchhoff") {
            const double mu = c.named(e, "mu");
            bool hasLambda = false;
            double lambda = c.named(e, "lambda", &hasLambda);
            if (!hasLambda) {
                const double nu = c.named(e, "nu");
                if (!(nu > 0 && nu < 0.5)) c.fail(e, "nu must lie in (0, 0.5)");
                lambda = 2 * mu * nu / (1 - 2 * nu);
            }
            return std::make_shared<StVenantKirchhoff>(mu, lambda, c.named(e, "rho"));
        }
    } catch (const Error& ex) {
        // messages of CaseFile::named() name the file and line already
        if (std::string(ex.what()).rfind(c.fileName() + ":", 0) == 0) throw;
        c.fail(e, ex.what());
    }
    c.fail(e, "unknown material '" + type +
                  "': use neoHookean, mooneyRivlin, stVenantKirchhoff or holzapfelGasserOgden");
}

// The 'fibres' entry: one unit direction per element (reference configuration)
//   fibres uniform (x y z)
//   fibres cylindrical origin (x y z) axis (x y z)
//   fibres file <path>          one direction per element, relative to the case
// cylindrical: e_theta = axis x r / |axis x r| at the element's centroid, r
// from the origin (right-handed about the axis); parentheses optional
std::vector<Vec3> fibreDirections(const CaseFile& c, const CaseEntry& e, const TetMesh& mesh)
{
    // the arguments without parentheses and commas
    CaseEntry a{e.keyword, {}, e.line};
    {
        std::string all;
        for (const auto& s : e.args) all += s + " ";
        for (char& ch : all) {
            if (ch == '(' || ch == ')' || ch == ',') ch = ' ';
        }
        std::istringstream is(all);
        std::string w;
        while (is >> w) a.args.push_back(w);
    }
    auto vec = [&](std::size_t i) { return Vec3(c.number(a, i), c.number(a, i + 1), c.number(a, i + 2)); };
    const char* usage =
        "expected 'uniform (x y z)', 'cylindrical origin (x y z) axis (x y z)' or 'file <path>'";
    if (a.args.empty()) c.fail(e, usage);
    const int ne = mesh.nElements();
    if (a.args[0] == "uniform") {
        if (a.args.size() != 4) c.fail(e, usage);
        const Vec3 d = vec(1);
        if (!(d.norm() > 0)) c.fail(e, "the fibre direction must not be zero");
        return std::vector<Vec3>(ne, d.normalized());
    }
    if (a.args[0] == "cylindrical") {
        if (a.args.size() != 9 || a.args[1] != "origin" || a.args[5] != "axis") c.fail(e, usage);
        const Vec3 o = vec(2), axis = vec(6);
        if (!(axis.norm() > 0)) c.fail(e, "the axis must not be zero");
        const Vec3 n = axis.normalized();
        const auto& X = mesh.coordinates();
        std::vector<Vec3> d(ne);
        for (int el = 0; el < ne; ++el) {
            const Tet& t = mesh.elements()[el];
            const Vec3 r = 0.25 * (X[t[0]] + X[t[1]] + X[t[2]] + X[t[3]]) - o;
            const Vec3 et = n.cross(r);
            if (!(et.norm() > 1e-9 * std::max(1.0, r.norm()))) {
                c.fail(e, "element " + std::to_string(el) +
                              " has its centroid on the axis, where the circumferential "
                              "direction is undefined: move the origin or the axis");
            }
            d[el] = et.normalized();
        }
        return d;
    }
    if (a.args[0] == "file") {
        // one line "x y z" per element, in the order of the mesh file's
        // tetrahedra; '#' starts a comment (e.g. the .circumferential file
        // written beside the valve leaflets by makeValveMeshes)
        if (e.args.size() != 2) c.fail(e, usage);
        std::filesystem::path p(e.args[1]);
        if (p.is_relative()) p = std::filesystem::path(c.directory()) / p;
        try {
            return readFibreDirections(p.string(), ne);
        } catch (const Error& ex) {
            c.fail(e, ex.what());
        }
    }
    c.fail(e, "unknown fibre layout '" + a.args[0] + "': " + usage);
}

TetMesh makeMesh(const CaseFile& c)
{
    const CaseEntry* m = c.find("mesh", true);
    const CaseEntry* b = c.find("box", true);
    const CaseEntry* h = c.find("hex", true);
    if ((m != nullptr) + (b != nullptr) + (h != nullptr) != 1) {
        throw Error(c.fileName() +
                    ": give exactly one of 'mesh <file.msh>', 'box ...' and 'hex ...'");
    }
    if (m) {
        if (m->args.size() != 1) c.fail(*m, "expected one file name");
        std::filesystem::path p(m->args[0]);
        if (p.is_relative()) p = std::filesystem::path(c.directory()) / p;
        return TetMesh::fromGmsh(p.string());
    }
    const CaseEntry& e = b ? *b : *h;
    const int nx = int(c.number(e, 0)), ny = int(c.number(e, 1)), nz = int(c.number(e, 2));
    if (b) {
        if (b->args.size() != 9) c.fail(*b, "expected nx ny nz x0 y0 z0 x1 y1 z1");
        const Vec3 lo(c.number(*b, 3), c.number(*b, 4), c.number(*b, 5));
        const Vec3 hi(c.number(*b, 6), c.number(*b, 7), c.number(*b, 8));
        return TetMesh::box(nx, ny, nz, [&](const Vec3& s) {
            return Vec3(lo + (hi - lo).cwiseProduct(s));
        });
    }
    if (h->args.size() != 27) c.fail(*h, "expected nx ny nz and 8 corner points");
    Vec3 P[8];
    for (int k = 0; k < 8; ++k) {
        P[k] = Vec3(c.number(*h, 3 + 3 * k), c.number(*h, 4 + 3 * k), c.number(*h, 5 + 3 * k));
    }
    // trilinear map of the unit cube, VTK hexahedron corner order
    return TetMesh::box(nx, ny, nz, [&](const Vec3& s) {
        const double x = s.x(), y = s.y(), z = s.z();
        return Vec3((1 - z) * ((1 - y) * ((1 - x) * P[0] + x * P[1]) + y * ((1 - x) * P[3] + x * P[2])) +
                    z * ((1 - y) * ((1 - x) * P[4] + x * P[5]) + y * ((1 - x) * P[7] + x * P[6])));
    });
}

}  // namespace

SolidRun::Ramp SolidRun::ramp(const CaseEntry& e, std::size_t first) const
{
    for (std::size_t i = first; i + 1 < e.args.size(); ++i) {
        if (e.args[i] == "ramp") {
            const double T = case_.number(e, i + 1);
            if (!(T > 0)) case_.fail(e, "ramp time must be positive");
            return [T](double t) { return std::min(1.0, t / T); };
        }
    }
    return [](double) { return 1.0; };
}

SolidRun::SolidRun(const std::string& caseFile) : case_(caseFile)
{
    TetMesh mesh = makeMesh(case_);
    SolidOptions opt;
    if (const auto* f = case_.find("formulation", true)) {
        if (f->args.size() != 1) case_.fail(*f, "expected one formulation");
        try {
            opt.formulation = formulationFromString(f->args[0]);
        } catch (const Error& ex) {
            case_.fail(*f, ex.what());
        }
    }
    if (const auto* s = case_.find("safety", true)) opt.safety = case_.number(*s, 0);
    if (const auto* d = case_.find("damping", true)) opt.damping = case_.number(*d, 0);
    if (const auto* b = case_.find("stiffnessDamping", true)) {
        opt.stiffnessDamping = case_.number(*b, 0);
        if (!(opt.stiffnessDamping >= 0)) {
            case_.fail(*b, "stiffnessDamping must be a non-negative time [s]");
        }
    }

    if (case_.find("planeStrain", true)) {
        std::vector<int> all(mesh.nNodes());
        for (int i = 0; i < mesh.nNodes(); ++i) all[i] = i;
        mesh.addNodeSet("__all", all);
    }
    solid_ = std::make_unique<ExplicitSolid>(std::move(mesh),
                                             makeMaterial(case_, *case_.find("material")), opt);
    ExplicitSolid& s = *solid_;

    auto guarded = [&](const CaseEntry& e, auto f) {
        try {
            f();
        } catch (const Error& ex) {
            case_.fail(e, ex.what());
        }
    };
    if (const auto* e = case_.find("fibres", true)) {
        if (!s.material().hasFibres()) {
            case_.fail(*e, "material " + s.material().name() +
                               " has no fibres: remove this entry or use holzapfelGasserOgden");
        }
        std::vector<Vec3> a = fibreDirections(case_, *e, s.mesh());
        guarded(*e, [&] { s.setFibreDirections(std::move(a)); });
    } else if (s.material().hasFibres()) {
        case_.fail(*case_.find("material"),
                   "material " + s.material().name() +
                       " needs fibre directions: add 'fibres cylindrical origin (x y z) axis "
                       "(x y z)' or 'fibres uniform (x y z)'");
    }
    for (const auto* e : case_.all("fix")) {
        if (e->args.empty()) case_.fail(*e, "expected a node set");
        guarded(*e, [&] { s.fix(e->args[0], componentMask(case_, *e, 1)); });
    }
    if (const auto* e = case_.find("planeStrain", true)) {
        s.fix("__all", componentMask(case_, *e, 0));
    }
    if (const auto* e = case_.find("bodyForce", true)) {
        gravity_ = Vec3(case_.number(*e, 0), case_.number(*e, 1), case_.number(*e, 2));
        gravityRamp_ = ramp(*e, 3);
    }
    for (const auto* e : case_.all("pressure")) {
        if (e->args.size() < 2) case_.fail(*e, "expected <faceSet> <p>");
        const double p = case_.number(*e, 1);
        const Ramp r = ramp(*e, 2);
        guarded(*e, [&] { s.addFollowerPressure(e->args[0], [p, r](double t) { return p * r(t); }); });
    }
    for (const auto* e : case_.all("traction")) {
        if (e->args.size() < 4) case_.fail(*e, "expected <faceSet> <tx> <ty> <tz>");
        const Vec3 tr(case_.number(*e, 1), case_.number(*e, 2), case_.number(*e, 3));
        Traction t{std::vector<Vec3>(s.mesh().nNodes(), Vec3::Zero()), ramp(*e, 4)};
        guarded(*e, [&] {
            const auto& X = s.mesh().coordinates();
            for (const Tri& f : s.mesh().faceSet(e->args[0])) {
                const double A = 0.5 * (X[f[1]] - X[f[0]]).cross(X[f[2]] - X[f[0]]).norm();
                for (int v : f) t.nodal[v] += tr * (A / 3.0);
            }
        });
        tractions_.push_back(std::move(t));
    }
    if (const auto* e = case_.find("contact", true)) {
        ContactOptions co;
        std::size_t i = 0;
        if (!e->args.empty() && e->args[0] == "self") co.selfContact = true, i = 1;
        for (; i < e->args.size(); i += 2) {
            const std::string& name = e->args[i];
            double* target = name == "dampingRatio"   ? &co.dampingRatio
                             : name == "stepFraction" ? &co.stepFraction
                             : name == "penaltyScale" ? &co.penaltyScale
                             : name == "depthFraction" ? &co.depthFraction
                             : name == "facingCosine"  ? &co.facingCosine
                                                      : nullptr;
            if (!target || i + 1 >= e->args.size()) {
                case_.fail(*e, "expected [self] then 'dampingRatio z', 'stepFraction f', "
                               "'penaltyScale b', 'depthFraction d' or 'facingCosine c' pairs, got '" +
                                   name + "'");
            }
            *target = case_.number(*e, i + 1);
        }
        guarded(*e, [&] { s.enableContact(co); });
    }
    // Rigid contact surfaces (walls): contactSurface <file> [flip], relative
    // to the case directory; contact (between parts) is enabled with the
    // defaults if no 'contact' entry did
    for (const auto* e : case_.all("contactSurface")) {
        const bool flip = e->args.size() == 2 && e->args[1] == "flip";
        if (e->args.empty() || e->args.size() > 2 || (e->args.size() == 2 && !flip)) {
            case_.fail(*e, "expected <surface file (.stl or .msh)> [flip]");
        }
        std::filesystem::path p(e->args[0]);
        if (p.is_relative()) p = std::filesystem::path(case_.directory()) / p;
        guarded(*e, [&] { s.addRigidSurface(readRigidSurface(p.string(), flip)); });
    }

    endTime_ = case_.number(*case_.find("endTime"), 0);
    writeInterval_ = case_.number(*case_.find("writeInterval"), 0);
    if (!(endTime_ > 0) || !(writeInterval_ > 0)) {
        throw Error(case_.fileName() + ": endTime and writeInterval must be positive");
    }
    // Probe sampling: 50 samples per write interval unless given (for
    // CSM3, 1 ms: about 900 samples per period of the flag)
    probeInterval_ = writeInterval_ / 50;
    if (const auto* e = case_.find("probeInterval", true)) {
        if (e->args.size() != 1) case_.fail(*e, "expected one time interval");
        probeInterval_ = case_.number(*e, 0);
        if (!(probeInterval_ > 0)) case_.fail(*e, "the probe interval must be positive");
    }
    if (const auto* e = case_.find("steadyTolerance", true)) steadyTol_ = case_.number(*e, 0);
    outputDir_ = "results";
    if (const auto* e = case_.find("output", true)) outputDir_ = e->args.at(0);
    if (std::filesystem::path(outputDir_).is_relative()) {
        outputDir_ = (std::filesystem::path(case_.directory()) / outputDir_).string();
    }
    vtu_ = std::make_unique<VtuSeries>(outputDir_, "solid");

    for (const auto* e : case_.all("probe")) {
        if (e->args.size() != 4) case_.fail(*e, "expected <name> <x> <y> <z>");
        const Vec3 p(case_.number(*e, 1), case_.number(*e, 2), case_.number(*e, 3));
        const auto& X = s.mesh().coordinates();
        Probe best{};
        double bestMin = -1e300;
        for (int el = 0; el < s.mesh().nElements(); ++el) {
            const Tet& t = s.mesh().elements()[el];
            Mat3 A;
            A.col(0) = X[t[1]] - X[t[0]];
            A.col(1) = X[t[2]] - X[t[0]];
            A.col(2) = X[t[3]] - X[t[0]];
            const Vec3 l = A.inverse() * (p - X[t[0]]);
            const std::array<double, 4> w{1 - l.sum(), l.x(), l.y(), l.z()};
            const double m = *std::min_element(w.begin(), w.end());
            if (m > bestMin) {
                bestMin = m;
                best = {t, w};
            }
        }
        if (bestMin < -1e-6) {
            case_.fail(*e, "the point lies outside the mesh");
        }
        probeNames_.push_back(e->args[0]);
        probes_.push_back(best);
    }
    probeFile_.open(outputDir_ + "/probes.dat");
    probeFile_ << "# time";
    for (const auto& n : probeNames_) {
        probeFile_ << "  " << n << "_ux " << n << "_uy " << n << "_uz";
    }
    probeFile_ << "\n" << std::setprecision(10);
}

void SolidRun::applyLoads(double t)
{
    ExplicitSolid& s = *solid_;
    auto& f = s.externalForce();
    std::fill(f.begin(), f.end(), Vec3::Zero());
    for (const Traction& tr : tractions_) {
        const double r = tr.s(t);
        for (std::size_t i = 0; i < f.size(); ++i) f[i] += r * tr.nodal[i];
    }
    if (gravityRamp_) s.setBodyForce(gravityRamp_(t) * gravity_);
}

void SolidRun::noteSubStep(double h)
{
    current_.minSubStep = std::min(current_.minSubStep, h);
    current_.maxSubStep = std::max(current_.maxSubStep, h);
}

void SolidRun::subStepStarted(double t)
{
    if (stepOpen_) noteSubStep(t - stepStart_);
    stepStart_ = t;
    stepOpen_ = true;
}

void SolidRun::chunkEnded()
{
    if (stepOpen_) noteSubStep(solid_->time() - stepStart_);
    stepOpen_ = false;
}

void SolidRun::writeProbes()
{
    lastProbeTime_ = solid_->time();
    probeFile_ << solid_->time();
    for (std::size_t i = 0; i < probes_.size(); ++i) {
        const Vec3 u = probeDisplacement(i);
        probeFile_ << ' ' << u.x() << ' ' << u.y() << ' ' << u.z();
    }
    probeFile_ << '\n';
}

Vec3 SolidRun::probeDisplacement(std::size_t i) const
{
    const Probe& p = probes_.at(i);
    Vec3 u = Vec3::Zero();
    for (int a = 0; a < 4; ++a) u += p.w[a] * solid_->displacement()[p.nodes[a]];
    return u;
}

long SolidRun::run(std::ostream& log)
{
    ExplicitSolid& s = *solid_;
    s.setLoadUpdate([this](double t) {
        applyLoads(t);
        subStepStarted(t);
    });
    const double dt0 = s.stableTimeStep();
    log << "smoothedSolidRun: " << s.mesh().nNodes() << " nodes, " << s.mesh().nElements()
        << " tets, " << toString(s.options().formulation) << ", " << s.material().name()
        << ", stable step dt = " << dt0 << " s, probes every " << probeInterval_ << " s"
        << std::endl;
    if (probeInterval_ < dt0) {
        log << "note: probeInterval " << probeInterval_ << " s is below the stable step: "
            << "it limits the sub-steps" << std::endl;
    }
    auto writeVtu = [&] {
        std::vector<double> cp = s.contactPressure();
        cp.resize(s.mesh().nNodes(), 0.0);
        vtu_->write(s, {{"contactPressure", cp}});
    };
    writeVtu();
    writeProbes();

    // Events at integer multiples of the intervals (no drift); events closer
    // than eps are one
    const double eps = 1e-9 * std::min(writeInterval_, probeInterval_);
    const long steps0 = s.steps();
    long nWrite = 1, nProbe = 1;
    std::vector<Vec3> last(probes_.size(), Vec3::Zero());
    long writeSteps = s.steps();  // at the previous write
    auto startInterval = [&] {
        current_ = {0, 0, std::numeric_limits<double>::infinity(), 0, 0};
        writeSteps = s.steps();
    };
    startInterval();
    intervals_.clear();
    stepOpen_ = false;
    while (s.time() < endTime_ - eps) {
        const double tWrite = nWrite * writeInterval_, tProbe = nProbe * probeInterval_;
        const double target = std::min({tWrite, tProbe, endTime_});
        s.advance(target - s.time());
        chunkEnded();
        if (tProbe <= target + eps) {
            ++nProbe;
            writeProbes();
        }
        if (!(tWrite <= target + eps)) continue;

        ++nWrite;
        writeVtu();
        current_.time = s.time();
        current_.subSteps = s.steps() - writeSteps;
        current_.stableStep = s.stableTimeStep();
        intervals_.push_back(current_);
        log << "t = " << s.time() << "  steps " << s.steps() - steps0 << " (+" << current_.subSteps
            << ", sub-step " << current_.minSubStep << " .. " << current_.maxSubStep << " s)"
            << "  kinetic energy " << s.kineticEnergy();
        startInterval();
        double change = 0, size = 0;
        for (std::size_t i = 0; i < probes_.size(); ++i) {
            const Vec3 u = probeDisplacement(i);
            log << "  " << probeNames_[i] << " (" << u.x() << ", " << u.y() << ", " << u.z()
                << ")";
            change = std::max(change, (u - last[i]).norm());
            size = std::max(size, u.norm());
            last[i] = u;
        }
        log << std::endl;
        if (steadyTol_ > 0 && size > 0 && change < steadyTol_ * size) {
            log << "steady: probe change " << change / size << " < " << steadyTol_ << "\n";
            break;
        }
    }
    // the final state ends the history (endTime, or steady between probe times)
    if (lastProbeTime_ != s.time()) writeProbes();
    probeFile_.flush();
    s.setLoadUpdate(nullptr);
    return s.steps() - steps0;
}

}  // namespace smoothedSolid
