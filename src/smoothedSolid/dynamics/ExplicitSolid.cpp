#include "dynamics/ExplicitSolid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>

namespace smoothedSolid {

ExplicitSolid::ExplicitSolid(TetMesh mesh, std::shared_ptr<const Material> material,
                             SolidOptions options)
    : mesh_(std::move(mesh)), material_(std::move(material)), options_(options)
{
    if (!material_) throw Error("ExplicitSolid: no material");
    if (!(options_.safety > 0 && options_.safety <= 1)) {
        throw Error("ExplicitSolid: safety factor must lie in (0, 1]");
    }
    switch (options_.formulation) {
        case Formulation::FEM_T4: main_ = elementDomains(mesh_); break;
        case Formulation::NS_FEM: main_ = nodeDomains(mesh_); break;
        case Formulation::FS_FEM: main_ = faceDomains(mesh_); break;
        case Formulation::Selective:
            main_ = faceDomains(mesh_);
            volumetric_ = nodeDomains(mesh_);
            break;
    }

    const int n = mesh_.nNodes();
    mass_.assign(n, 0.0);
    hMin_ = std::numeric_limits<double>::max();
    for (int e = 0; e < mesh_.nElements(); ++e) {
        const double m = 0.25 * material_->density() * mesh_.elementVolume(e);
        for (int v : mesh_.elements()[e]) mass_[v] += m;
        hMin_ = std::min(hMin_, mesh_.elementHeight(e));
    }
    u_.assign(n, Vec3::Zero());
    vHalf_.assign(n, Vec3::Zero());
    fext_.assign(n, Vec3::Zero());
    work_.assign(n, Vec3::Zero());
}

// ---------------------------------------------------------------------------

void ExplicitSolid::fix(const std::string& nodeSet, std::array<bool, 3> components)
{
    prescribeDisplacement(
        nodeSet, [](double, const Vec3&) { return Vec3::Zero(); }, components);
}

void ExplicitSolid::prescribeDisplacement(const std::string& nodeSet, VectorFunction u,
                                          std::array<bool, 3> components)
{
    constraints_.push_back({mesh_.nodeSet(nodeSet), components, std::move(u), false});
}

void ExplicitSolid::prescribeVelocity(const std::string& nodeSet, VectorFunction v,
                                      std::array<bool, 3> components)
{
    constraints_.push_back({mesh_.nodeSet(nodeSet), components, std::move(v), true});
}

void ExplicitSolid::addFollowerPressure(const std::string& faceSet, ScalarFunction p)
{
    pressures_.push_back({mesh_.faceSet(faceSet), std::move(p)});
}

// ---------------------------------------------------------------------------

double ExplicitSolid::stableTimeStep() const
{
    const double c = std::sqrt(material_->waveModulus() / material_->density());
    const double dt = options_.safety * hMin_ / c;
    return contact_ ? dt * contact_->stableTimeStepFactor(hMin_ / c) : dt;
}

void ExplicitSolid::enableContact(ContactOptions options)
{
    std::vector<RigidSurface> keep;
    if (contact_) keep = contact_->rigidSurfaces();
    contact_ = std::make_unique<PenaltyContact>(mesh_, material_->waveModulus(), mass_, options);
    for (auto& s : keep) contact_->addRigidSurface(std::move(s));
    contactPressure_.assign(mesh_.nNodes(), 0.0);
}

void ExplicitSolid::addRigidSurface(RigidSurface surface)
{
    if (!contact_) enableContact();
    contact_->addRigidSurface(std::move(surface));
}

std::vector<Vec3> ExplicitSolid::internalForce(const std::vector<Vec3>& u) const
{
    std::vector<Vec3> f(mesh_.nNodes(), Vec3::Zero());
    const Material& m = *material_;
    auto jacobianOk = [&](const Mat3& F, int d, const char* kind) {
        if (!(F.determinant() > 0)) {
            throw Error("inverted material in " + std::string(kind) + " smoothing domain " +
                        std::to_string(d) + " at t = " + std::to_string(t_) +
                        " (det F = " + std::to_string(F.determinant()) +
                        "): the time step or the load is too large");
        }
    };
    if (options_.formulation == Formulation::Selective) {
        // Sect. 3.2: deviatoric stress on face-based domains, volumetric
        // stress on node-based domains
        for (int d = 0; d < main_.size(); ++d) {
            const Mat3 F = main_.deformationGradient(d, u);
            jacobianOk(F, d, "face");
            main_.addInternalForce(d, m.stressDeviatoric(F), f);
        }
        for (int d = 0; d < volumetric_.size(); ++d) {
            const Mat3 F = volumetric_.deformationGradient(d, u);
            jacobianOk(F, d, "node");
            volumetric_.addInternalForce(d, m.stressVolumetric(F), f);
        }
    } else {
        for (int d = 0; d < main_.size(); ++d) {
            const Mat3 F = main_.deformationGradient(d, u);
            jacobianOk(F, d, "smoothing");
            main_.addInternalForce(d, m.firstPK(F), f);
        }
    }
    return f;
}

double ExplicitSolid::strainEnergy(const std::vector<Vec3>& u) const
{
    const Material& m = *material_;
    double W = 0;
    if (options_.formulation == Formulation::Selective) {
        for (int d = 0; d < main_.size(); ++d) {
            W += main_.volume[d] * m.energyDeviatoric(main_.deformationGradient(d, u));
        }
        for (int d = 0; d < volumetric_.size(); ++d) {
            W += volumetric_.volume[d] *
                 m.energyVolumetric(volumetric_.deformationGradient(d, u));
        }
    } else {
        for (int d = 0; d < main_.size(); ++d) {
            W += main_.volume[d] * m.energy(main_.deformationGradient(d, u));
        }
    }
    return W;
}

double ExplicitSolid::kineticEnergy() const
{
    double K = 0;
    for (int i = 0; i < mesh_.nNodes(); ++i) K += 0.5 * mass_[i] * vHalf_[i].squaredNorm();
    return K;
}

void ExplicitSolid::setInitialVelocity(const VectorFunction& v0)
{
    if (nSteps_ > 0) throw Error("setInitialVelocity: the solid has already been advanced");
    for (int i = 0; i < mesh_.nNodes(); ++i) vHalf_[i] = v0(0.0, mesh_.coordinates()[i]);
}

std::vector<Vec3> ExplicitSolid::currentCoordinates() const
{
    std::vector<Vec3> x(mesh_.coordinates());
    for (int i = 0; i < mesh_.nNodes(); ++i) x[i] += u_[i];
    return x;
}

// f = f_ext - f_int at the current state (Eq. 42)
void ExplicitSolid::accelerationForces(std::vector<Vec3>& f)
{
    f = internalForce(u_);
    for (int i = 0; i < mesh_.nNodes(); ++i) f[i] = fext_[i] + mass_[i] * bodyForce_ - f[i];

    if (!pressures_.empty()) {
        const auto& X = mesh_.coordinates();
        for (const Pressure& pr : pressures_) {
            const double p = pr.p(t_);
            for (const Tri& t : pr.faces) {
                const Vec3 x0 = X[t[0]] + u_[t[0]];
                const Vec3 x1 = X[t[1]] + u_[t[1]];
                const Vec3 x2 = X[t[2]] + u_[t[2]];
                const Vec3 nA = 0.5 * (x1 - x0).cross(x2 - x0);  // outward, |.| = area
                const Vec3 fn = (-p / 3.0) * nA;
                f[t[0]] += fn;
                f[t[1]] += fn;
                f[t[2]] += fn;
            }
        }
    }

    if (contact_) {
        maxPenetration_ = contact_->addForces(mesh_, currentCoordinates(), f, contactPressure_);
    }
}

void ExplicitSolid::applyConstraints(double dt)
{
    const auto& X = mesh_.coordinates();
    for (const Constraint& c : constraints_) {
        for (int i : c.nodes) {
            Vec3 v;
            if (c.isVelocity) {
                v = c.value(t_ + 0.5 * dt, X[i]);
            } else {
                v = (c.value(t_ + dt, X[i]) - u_[i]) / dt;
            }
            for (int k = 0; k < 3; ++k) {
                if (c.components[k]) vHalf_[i][k] = v[k];
            }
        }
    }
}

// Central difference with half-step velocities (Belytschko et al., Box 6.1):
//   a^n       = M^-1 (f_ext^n - f_int(u^n)) - c v^n
//   v^{n+1/2} = v^{n-1/2} + (dt_{n-1/2} + dt_{n+1/2})/2 a^n
//   u^{n+1}   = u^n + dt_{n+1/2} v^{n+1/2}
// The damping term is taken at v^n = (v^{n-1/2} + v^{n+1/2})/2.
void ExplicitSolid::step(double dt)
{
    if (!(dt > 0) || !std::isfinite(dt)) {
        throw Error("ExplicitSolid::step: time step must be positive");
    }
    accelerationForces(work_);

    const double dtAvg = 0.5 * (dtLast_ + dt);
    const double c = 0.5 * options_.damping * dtAvg;
    const double a = (1.0 - c) / (1.0 + c);
    const double b = dtAvg / (1.0 + c);
    for (int i = 0; i < mesh_.nNodes(); ++i) {
        vHalf_[i] = a * vHalf_[i] + (b / mass_[i]) * work_[i];
    }
    applyConstraints(dt);
    for (int i = 0; i < mesh_.nNodes(); ++i) u_[i] += dt * vHalf_[i];

    t_ += dt;
    dtLast_ = dt;
    ++nSteps_;
}

int ExplicitSolid::advance(double dt)
{
    if (dt <= 0) return 0;
    const int n = static_cast<int>(std::ceil(dt / stableTimeStep() - 1e-12));
    const double sub = dt / n;
    for (int k = 0; k < n; ++k) step(sub);
    return n;
}

}  // namespace smoothedSolid

// ---------------------------------------------------------------------------

namespace smoothedSolid {

void ExplicitSolid::elementStress(std::vector<Mat3>& sigma, std::vector<double>& J) const
{
    const int ne = mesh_.nElements();
    sigma.assign(ne, Mat3::Zero());
    J.assign(ne, 0.0);
    const Material& m = *material_;
    const auto& elemFaces = mesh_.elementFaces();

    // Cauchy part of a stress function evaluated with the domain's F
    auto cauchyOf = [](const Mat3& P, const Mat3& F) {
        return Mat3(P * F.transpose() / F.determinant());
    };
    auto perDomain = [&](const SmoothingDomains& sd, auto stress) {
        std::vector<Mat3> s(sd.size());
        std::vector<double> j(sd.size());
        for (int d = 0; d < sd.size(); ++d) {
            const Mat3 F = sd.deformationGradient(d, u_);
            s[d] = cauchyOf(stress(F), F);
            j[d] = F.determinant();
        }
        return std::make_pair(s, j);
    };
    auto dev = [&](const Mat3& F) { return m.stressDeviatoric(F); };
    auto vol = [&](const Mat3& F) { return m.stressVolumetric(F); };
    auto full = [&](const Mat3& F) { return m.firstPK(F); };

    switch (options_.formulation) {
        case Formulation::FEM_T4: {
            const auto [s, j] = perDomain(main_, full);
            sigma = s;
            J = j;
            break;
        }
        case Formulation::FS_FEM: {
            const auto [s, j] = perDomain(main_, full);
            for (int e = 0; e < ne; ++e) {
                for (int f : elemFaces[e]) {
                    sigma[e] += 0.25 * s[f];
                    J[e] += 0.25 * j[f];
                }
            }
            break;
        }
        case Formulation::NS_FEM: {
            const auto [s, j] = perDomain(main_, full);
            for (int e = 0; e < ne; ++e) {
                for (int v : mesh_.elements()[e]) {
                    sigma[e] += 0.25 * s[v];
                    J[e] += 0.25 * j[v];
                }
            }
            break;
        }
        case Formulation::Selective: {
            const auto [sf, jf] = perDomain(main_, dev);
            const auto [sn, jn] = perDomain(volumetric_, vol);
            for (int e = 0; e < ne; ++e) {
                for (int f : elemFaces[e]) sigma[e] += 0.25 * sf[f];
                for (int v : mesh_.elements()[e]) {
                    sigma[e] += 0.25 * sn[v];
                    J[e] += 0.25 * jn[v];
                }
            }
            break;
        }
    }
}

namespace {
constexpr char kStateMagic[] = "smoothedSolid-state-1";
}

void ExplicitSolid::saveState(const std::string& fileName) const
{
    std::ofstream os(fileName, std::ios::binary);
    if (!os) throw Error("cannot write state file '" + fileName + "'");
    const std::int64_t n = mesh_.nNodes();
    os.write(kStateMagic, sizeof kStateMagic);
    os.write(reinterpret_cast<const char*>(&n), sizeof n);
    os.write(reinterpret_cast<const char*>(&t_), sizeof t_);
    os.write(reinterpret_cast<const char*>(&dtLast_), sizeof dtLast_);
    os.write(reinterpret_cast<const char*>(&nSteps_), sizeof nSteps_);
    for (const auto* field : {&u_, &vHalf_, &fext_}) {
        os.write(reinterpret_cast<const char*>(field->data()),
                 static_cast<std::streamsize>(sizeof(Vec3) * field->size()));
    }
    if (!os) throw Error("error while writing state file '" + fileName + "'");
}

void ExplicitSolid::loadState(const std::string& fileName)
{
    std::ifstream is(fileName, std::ios::binary);
    if (!is) throw Error("cannot open state file '" + fileName + "'");
    char magic[sizeof kStateMagic] = {};
    is.read(magic, sizeof magic);
    if (std::string(magic) != kStateMagic) {
        throw Error("'" + fileName + "' is not a smoothedSolid state file");
    }
    std::int64_t n = 0;
    is.read(reinterpret_cast<char*>(&n), sizeof n);
    if (n != mesh_.nNodes()) {
        throw Error("state file '" + fileName + "' is for a mesh of " + std::to_string(n) +
                    " nodes, this solid has " + std::to_string(mesh_.nNodes()));
    }
    is.read(reinterpret_cast<char*>(&t_), sizeof t_);
    is.read(reinterpret_cast<char*>(&dtLast_), sizeof dtLast_);
    is.read(reinterpret_cast<char*>(&nSteps_), sizeof nSteps_);
    for (auto* field : {&u_, &vHalf_, &fext_}) {
        is.read(reinterpret_cast<char*>(field->data()),
                static_cast<std::streamsize>(sizeof(Vec3) * field->size()));
    }
    if (!is) throw Error("state file '" + fileName + "' is truncated");
}

}  // namespace smoothedSolid
