#include "dynamics/ExplicitSolid.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>

namespace smoothedSolid {

namespace {

std::vector<double> nodalMass(const TetMesh& mesh, double rho)
{
    std::vector<double> m(mesh.nNodes(), 0.0);
    for (int e = 0; e < mesh.nElements(); ++e) {
        const double me = 0.25 * rho * mesh.elementVolume(e);
        for (int v : mesh.elements()[e]) m[v] += me;
    }
    return m;
}

const std::shared_ptr<const Material>& checked(const std::shared_ptr<const Material>& m)
{
    if (!m) throw Error("ExplicitSolid: no material");
    return m;
}

}  // namespace

ExplicitSolid::ExplicitSolid(TetMesh mesh, std::shared_ptr<const Material> material,
                             SolidOptions options)
    : mesh_(std::make_shared<const TetMesh>(std::move(mesh))),
      material_(checked(material)),
      options_(options),
      smoothing_(mesh_),
      uses_(domainUses(options.formulation)),
      mass_(nodalMass(*mesh_, material_->density())),
      bound_(smoothing_, options.formulation, mass_, *material_)
{
    if (!(options_.safety > 0 && options_.safety <= 1)) {
        throw Error("ExplicitSolid: safety factor must lie in (0, 1], not " +
                    std::to_string(options_.safety));
    }
    if (!(options_.damping >= 0) || !std::isfinite(options_.damping)) {
        throw Error("ExplicitSolid: the damping coefficient must be non-negative");
    }
    setStiffnessDamping(options_.stiffnessDamping);
    const int ne = mesh_->nElements();
    Fe_.resize(ne);
    Pbar_.resize(ne);
    Fd_.resize(uses_.size());
    Pd_.resize(uses_.size());
    for (std::size_t k = 0; k < uses_.size(); ++k) {
        Fd_[k].resize(smoothing_.size(uses_[k].kind));
        Pd_[k].resize(smoothing_.size(uses_[k].kind));
    }

    const int n = mesh_->nNodes();
    hMin_ = std::numeric_limits<double>::max();
    for (int e = 0; e < ne; ++e) hMin_ = std::min(hMin_, mesh_->elementHeight(e));
    u_.assign(n, Vec3::Zero());
    vHalf_.assign(n, Vec3::Zero());
    fext_.assign(n, Vec3::Zero());
    work_.assign(n, Vec3::Zero());
    x_.assign(n, Vec3::Zero());
    deformationGradients(u_);
    refreshBound();
}

// ---------------------------------------------------------------------------

void ExplicitSolid::fix(const std::string& nodeSet, std::array<bool, 3> components)
{
    prescribeDisplacement(
        nodeSet, [](double, const Vec3&) { return Vec3::Zero(); }, components);
    constraints_.back().still = true;
    passStillNodesToContact();
}

void ExplicitSolid::passStillNodesToContact()
{
    if (!contact_) return;
    std::vector<unsigned char> held(mesh_->nNodes(), 0);  // bit k: component k fixed
    for (const Constraint& c : constraints_) {
        if (!c.still) continue;
        const unsigned char bits = (c.components[0] ? 1 : 0) | (c.components[1] ? 2 : 0) |
                                   (c.components[2] ? 4 : 0);
        for (int i : c.nodes) held[i] |= bits;
    }
    std::vector<char> still(held.size());
    for (std::size_t i = 0; i < held.size(); ++i) still[i] = held[i] == 7;
    contact_->setStillNodes(std::move(still));
}

void ExplicitSolid::prescribeDisplacement(const std::string& nodeSet, VectorFunction u,
                                          std::array<bool, 3> components)
{
    constraints_.push_back({mesh_->nodeSet(nodeSet), components, std::move(u), false});
}

void ExplicitSolid::prescribeVelocity(const std::string& nodeSet, VectorFunction v,
                                      std::array<bool, 3> components)
{
    constraints_.push_back({mesh_->nodeSet(nodeSet), components, std::move(v), true});
}

void ExplicitSolid::addFollowerPressure(const std::string& faceSet, ScalarFunction p)
{
    pressures_.push_back({mesh_->faceSet(faceSet), std::move(p)});
}

// ---------------------------------------------------------------------------

void ExplicitSolid::setStiffnessDamping(double beta)
{
    if (!(beta >= 0) || !std::isfinite(beta)) {
        throw Error("ExplicitSolid: the stiffness damping coefficient must be non-negative "
                    "and finite, not " + std::to_string(beta));
    }
    options_.stiffnessDamping = beta;
}

double ExplicitSolid::stepOfOmega2(double omega2) const
{
    const double omega = std::sqrt(omega2);
    // damping ratio of the fastest mode; the central difference with the
    // damping force at v^{n-1/2} is stable for omega dt <= 2 (sqrt(1 + z^2) - z),
    // written 2 / (z + sqrt(1 + z^2)) (no cancellation, no overflow)
    const double z = 0.5 * options_.stiffnessDamping * omega;
    return options_.safety * 2.0 / omega / (z + std::hypot(1.0, z));
}

double ExplicitSolid::stableTimeStep() const
{
    const double dt = stepOfOmega2(omega2Max_);
    if (!contact_) return dt;
    // near contact as of the last search (each force evaluation makes one)
    if (!contact_->searched()) contact_->search(*mesh_, currentCoordinates());
    return contact_->nearContact() ? dt * contact_->options().stepFraction : dt;
}

double ExplicitSolid::stableTimeStep(const std::vector<Vec3>& u) const
{
    if (u.size() != u_.size()) throw Error("stableTimeStep(u): u has the wrong size");
    deformationGradients(u);
    std::vector<const std::vector<Mat3>*> F;
    for (const auto& f : Fd_) F.push_back(&f);
    std::vector<double> omega2;
    const double w2 = bound_.evaluate(*material_, F, omega2);
    return stepOfOmega2(w2);
}

void ExplicitSolid::refreshBound()
{
    std::vector<const std::vector<Mat3>*> F;
    for (const auto& f : Fd_) F.push_back(&f);
    const double previous = omega2Max_;
    const auto start = std::chrono::steady_clock::now();
    omega2Max_ = bound_.evaluate(*material_, F, nodeOmega2_);
    boundSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++boundEvaluations_;
    if (!std::isfinite(omega2Max_) || !(omega2Max_ > 0)) {
        throw Error("stable time step: no finite bound at t = " + std::to_string(t_) +
                    " (step " + std::to_string(nSteps_) + "): a smoothing domain has degenerated");
    }
    if (previous > 0) {
        // the next interval lets omega_max^2 drift by about kStableStepDrift
        // at the rate seen over the last one (safety 0.9 leaves 23 %),
        // growing at most twofold per evaluation
        const double rate = std::abs(omega2Max_ / previous - 1.0) / std::max(1, boundAge_);
        const double fit = rate > 0 ? kStableStepDrift / rate : kMaxStableStepInterval;
        boundInterval_ = static_cast<int>(std::clamp(std::floor(fit), 1.0,
                                                     double(std::min(kMaxStableStepInterval, 2 * boundInterval_))));
    }
    boundAge_ = 0;
}

void ExplicitSolid::enableContact(ContactOptions options)
{
    std::vector<RigidSurface> keep;
    if (contact_) keep = contact_->rigidSurfaces();
    contact_ = std::make_unique<PenaltyContact>(*mesh_, hMin_, material_->waveModulus(),
                                                material_->density(), mass_, options);
    for (auto& s : keep) contact_->addRigidSurface(std::move(s));
    passStillNodesToContact();
    contactPressure_.assign(mesh_->nNodes(), 0.0);
}

void ExplicitSolid::addRigidSurface(RigidSurface surface)
{
    if (!contact_) enableContact();
    contact_->addRigidSurface(std::move(surface));
}

void ExplicitSolid::setFibreDirections(std::vector<Vec3> a0)
{
    if (!material_->hasFibres()) {
        throw Error("setFibreDirections: material " + material_->name() +
                    " has no fibres (use a fibre-reinforced material such as holzapfelGasserOgden)");
    }
    const int ne = mesh_->nElements();
    if (static_cast<int>(a0.size()) != ne) {
        throw Error("setFibreDirections: " + std::to_string(a0.size()) + " directions for " +
                    std::to_string(ne) + " elements (give one per element)");
    }
    for (int e = 0; e < ne; ++e) {
        const double n = a0[e].norm();
        if (!(n > 0) || !std::isfinite(n)) {
            throw Error("setFibreDirections: the direction of element " + std::to_string(e) +
                        " is zero or not finite");
        }
        a0[e] /= n;
    }
    std::vector<std::vector<Vec3>> domain(uses_.size());
    for (std::size_t k = 0; k < uses_.size(); ++k) {
        smoothing_.domainDirections(uses_[k].kind, a0, domain[k]);
    }
    fibreElement_ = std::move(a0);
    fibreDomain_ = std::move(domain);
    // the bound so far held for any direction; now for these
    std::vector<const std::vector<Vec3>*> perUse;
    for (std::size_t k = 0; k < uses_.size(); ++k) perUse.push_back(fibres(k));
    bound_.setFibres(perUse);
    deformationGradients(u_);
    omega2Max_ = 0;
    refreshBound();
}

const std::vector<Vec3>* ExplicitSolid::fibres(std::size_t k) const
{
    if (!material_->hasFibres() || uses_[k].part == StressPart::Volumetric) return nullptr;
    if (fibreDomain_.empty()) {
        throw Error("material " + material_->name() +
                    " needs fibre directions: call ExplicitSolid::setFibreDirections (case "
                    "files: the 'fibres' entry)");
    }
    return &fibreDomain_[k];
}

void ExplicitSolid::deformationGradients(const std::vector<Vec3>& u) const
{
    smoothing_.elementF(u, Fe_);
    for (std::size_t k = 0; k < uses_.size(); ++k) {
        if (uses_[k].kind == DomainKind::Element) Fd_[k] = Fe_;
        else smoothing_.domainF(uses_[k].kind, Fe_, Fd_[k]);
    }
}

namespace {

const char* kindName(DomainKind k)
{
    switch (k) {
        case DomainKind::Element: return "element";
        case DomainKind::Face: return "face";
        case DomainKind::Node: return "node";
    }
    return "?";
}

}  // namespace

// The internal force in gather form, so that every loop writes only its own
// entries and runs in parallel with OpenMP (when built with it):
//   F_e            per element
//   F_d            per smoothing domain: the weighted mean of its F_e (Eq. 23)
//   P_d = P(F_d)   (the deviatoric or volumetric part with the selective scheme)
//   Pbar_e = (V_e/4) sum of the P_d of the domains e takes part in
//            (V_e P_e for FEM-T4)
//   f_I = sum_{e around I} Pbar_e g_eI   (Eq. 31 with the first PK stress)
std::vector<Vec3> ExplicitSolid::internalForce(const std::vector<Vec3>& u) const
{
    const Material& m = *material_;
    const TetMesh& mesh = *mesh_;
    const int ne = mesh.nElements();
    deformationGradients(u);

    for (std::size_t k = 0; k < uses_.size(); ++k) {
        const DomainUse use = uses_[k];
        const std::vector<Mat3>& F = Fd_[k];
        std::vector<Mat3>& P = Pd_[k];
        const int nd = static_cast<int>(F.size());
        const std::vector<Vec3>* a = fibres(k);
        // An inverted domain is recorded (lowest index) inside the parallel
        // loop and reported after it: exceptions cannot leave an OpenMP loop
        int bad = std::numeric_limits<int>::max();
        int nonFinite = std::numeric_limits<int>::max();
#pragma omp parallel for schedule(static) reduction(min : bad, nonFinite)
        for (int d = 0; d < nd; ++d) {
            if (!(F[d].determinant() > 0)) {
                bad = std::min(bad, d);
                P[d].setZero();
                continue;
            }
            switch (use.part) {
                case StressPart::Full:
                    P[d] = a ? m.firstPK(F[d], (*a)[d]) : m.firstPK(F[d]);
                    break;
                case StressPart::Deviatoric:
                    P[d] = a ? m.stressDeviatoric(F[d], (*a)[d]) : m.stressDeviatoric(F[d]);
                    break;
                case StressPart::Volumetric:
                    P[d] = m.stressVolumetric(F[d]);
                    break;
            }
            if (!P[d].allFinite()) {
                nonFinite = std::min(nonFinite, d);
                P[d].setZero();
            }
        }
        if (bad == std::numeric_limits<int>::max() && nonFinite != std::numeric_limits<int>::max()) {
            bad = nonFinite;
        }
        if (bad != std::numeric_limits<int>::max()) {
            std::string where = std::string(kindName(use.kind)) + " smoothing domain " + std::to_string(bad);
            if (use.kind == DomainKind::Face) {
                const Face& f = mesh.faces()[bad];
                where += " (between elements " + std::to_string(f.owner) +
                         (f.neighbour >= 0 ? " and " + std::to_string(f.neighbour) : std::string()) + ")";
            } else if (use.kind == DomainKind::Node) {
                where += " (around node " + std::to_string(bad) + ")";
            }
            const bool inverted = !(F[bad].determinant() > 0);
            throw Error(std::string(inverted ? "inverted material" : "stress beyond range (blown-up stretch)") +
                        " in " + where + " at t = " + std::to_string(t_) +
                        ", step " + std::to_string(nSteps_) +
                        " (det F = " + std::to_string(F[bad].determinant()) +
                        ", |F| = " + std::to_string(F[bad].norm()) +
                        "): the time step or the load is too large");
        }
    }

    const auto& tets = mesh.elements();
    const auto& elemFaces = mesh.elementFaces();
#pragma omp parallel for schedule(static)
    for (int e = 0; e < ne; ++e) {
        Mat3 S = Mat3::Zero();
        for (std::size_t k = 0; k < uses_.size(); ++k) {
            const std::vector<Mat3>& P = Pd_[k];
            switch (uses_[k].kind) {
                case DomainKind::Element: S.noalias() += 4.0 * P[e]; break;
                case DomainKind::Face: {
                    const auto& ef = elemFaces[e];
                    S.noalias() += P[ef[0]] + P[ef[1]] + P[ef[2]] + P[ef[3]];
                    break;
                }
                case DomainKind::Node: {
                    const Tet& t = tets[e];
                    S.noalias() += P[t[0]] + P[t[1]] + P[t[2]] + P[t[3]];
                    break;
                }
            }
        }
        Pbar_[e] = smoothing_.quarterVolume(e) * S;
    }
    std::vector<Vec3> f;
    smoothing_.gatherForce(Pbar_, f);
    return f;
}

double ExplicitSolid::strainEnergy(const std::vector<Vec3>& u) const
{
    const Material& m = *material_;
    deformationGradients(u);
    double W = 0;
    for (std::size_t k = 0; k < uses_.size(); ++k) {
        const std::vector<Mat3>& F = Fd_[k];
        const std::vector<Vec3>* a = fibres(k);
        for (int d = 0; d < static_cast<int>(F.size()); ++d) {
            const double V = smoothing_.volume(uses_[k].kind, d);
            switch (uses_[k].part) {
                case StressPart::Full: W += V * (a ? m.energy(F[d], (*a)[d]) : m.energy(F[d])); break;
                case StressPart::Deviatoric:
                    W += V * (a ? m.energyDeviatoric(F[d], (*a)[d]) : m.energyDeviatoric(F[d]));
                    break;
                case StressPart::Volumetric: W += V * m.energyVolumetric(F[d]); break;
            }
        }
    }
    return W;
}

double ExplicitSolid::kineticEnergy() const
{
    double K = 0;
    for (int i = 0; i < mesh_->nNodes(); ++i) K += 0.5 * mass_[i] * vHalf_[i].squaredNorm();
    return K;
}

void ExplicitSolid::setInitialVelocity(const VectorFunction& v0)
{
    if (nSteps_ > 0) throw Error("setInitialVelocity: the solid has already been advanced");
    for (int i = 0; i < mesh_->nNodes(); ++i) vHalf_[i] = v0(0.0, mesh_->coordinates()[i]);
}

void ExplicitSolid::setInitialDisplacement(const VectorFunction& u0)
{
    if (nSteps_ > 0) throw Error("setInitialDisplacement: the solid has already been advanced");
    for (int i = 0; i < mesh_->nNodes(); ++i) u_[i] = u0(0.0, mesh_->coordinates()[i]);
    internalForce(u_);  // throws on inverted material
    omega2Max_ = 0;
    refreshBound();
}

std::vector<Vec3> ExplicitSolid::currentCoordinates() const
{
    std::vector<Vec3> x(mesh_->coordinates());
    for (int i = 0; i < mesh_->nNodes(); ++i) x[i] += u_[i];
    return x;
}

// f = f_ext - f_int at the current state (Eq. 42); with stiffness damping
// f_int(u + beta v^{n-1/2}) = f_int(u) + beta K v to first order
void ExplicitSolid::accelerationForces(std::vector<Vec3>& f, double dt)
{
    const int nn = mesh_->nNodes();
    const double beta = options_.stiffnessDamping;
    if (beta > 0) {
        uDamped_.resize(nn);
#pragma omp parallel for schedule(static)
        for (int i = 0; i < nn; ++i) uDamped_[i] = u_[i] + beta * vHalf_[i];
        f = internalForce(uDamped_);
    } else {
        f = internalForce(u_);
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nn; ++i) f[i] = fext_[i] + mass_[i] * bodyForce_ - f[i];

    if (!pressures_.empty()) {
        const auto& X = mesh_->coordinates();
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
        const auto& X = mesh_->coordinates();
#pragma omp parallel for schedule(static)
        for (int i = 0; i < nn; ++i) x_[i] = X[i] + u_[i];
        // carried by a fluid (interactionForce()), the elements' own stable
        // step does not bound this step, the fluid's mass does: the springs
        // get the whole budget of dt with the nodes' own mass (conservative)
        if (carried_ && static_cast<int>(zeroOmega2_.size()) != nn) zeroOmega2_.assign(nn, 0.0);
        maxPenetration_ = contact_->addForces(*mesh_, x_, vHalf_, dt,
                                              carried_ ? zeroOmega2_ : nodeOmega2_, f,
                                              contactPressure_);
    }
}

void ExplicitSolid::applyConstraints(double dt)
{
    const auto& X = mesh_->coordinates();
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
        throw Error("ExplicitSolid::step: the time step must be positive and finite, not " +
                    std::to_string(dt));
    }
    if (loadUpdate_) loadUpdate_(t_);
    const double dtAvg = 0.5 * (dtLast_ + dt);
    accelerationForces(work_, std::max(dt, dtAvg));

    // A state that stops being finite stops here, before it is stored
    const int nn = mesh_->nNodes();
    int bad = std::numeric_limits<int>::max();
#pragma omp parallel for schedule(static) reduction(min : bad)
    for (int i = 0; i < nn; ++i) {
        if (!work_[i].allFinite() || !vHalf_[i].allFinite()) bad = std::min(bad, i);
    }
    if (bad != std::numeric_limits<int>::max()) {
        throw Error("the solid's state stopped being finite at t = " + std::to_string(t_) +
                    ", step " + std::to_string(nSteps_) + ": node " + std::to_string(bad) +
                    " (reference position " + std::to_string(mesh_->coordinates()[bad].x()) + ", " +
                    std::to_string(mesh_->coordinates()[bad].y()) + ", " +
                    std::to_string(mesh_->coordinates()[bad].z()) +
                    ") has a non-finite force or velocity; the state of the last step is kept");
    }
    // The stable step bound, from the domain F's this force evaluation made
    if (++boundAge_ >= boundInterval_) refreshBound();

    if (addedMass_.empty()) {
        const double c = 0.5 * options_.damping * dtAvg;
        const double a = (1.0 - c) / (1.0 + c);
        const double b = dtAvg / (1.0 + c);
#pragma omp parallel for schedule(static)
        for (int i = 0; i < nn; ++i) vHalf_[i] = a * vHalf_[i] + (b / mass_[i]) * work_[i];
    } else {
        // (m + m_a)(v+ - v-)/dt = f - damping m (v+ + v-)/2
#pragma omp parallel for schedule(static)
        for (int i = 0; i < nn; ++i) {
            const double M = mass_[i] + addedMass_[i];
            const double c = 0.5 * options_.damping * dtAvg * mass_[i] / M;
            vHalf_[i] = ((1.0 - c) / (1.0 + c)) * vHalf_[i] + (dtAvg / ((1.0 + c) * M)) * work_[i];
        }
    }
    applyConstraints(dt);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nn; ++i) u_[i] += dt * vHalf_[i];

    t_ += dt;
    dtLast_ = dt;
    ++nSteps_;
}

void ExplicitSolid::setAddedMass(std::vector<double> m)
{
    if (!m.empty() && static_cast<int>(m.size()) != mesh_->nNodes()) {
        throw Error("ExplicitSolid::setAddedMass: " + std::to_string(m.size()) +
                    " values for " + std::to_string(mesh_->nNodes()) + " nodes");
    }
    for (std::size_t i = 0; i < m.size(); ++i) {
        if (!(m[i] >= 0) || !std::isfinite(m[i])) {
            throw Error("ExplicitSolid::setAddedMass: node " + std::to_string(i) +
                        " has a negative or non-finite added mass");
        }
    }
    addedMass_ = std::move(m);
}

std::vector<Vec3> ExplicitSolid::freeComponents() const
{
    std::vector<Vec3> free(mesh_->nNodes(), Vec3(1, 1, 1));
    for (const Constraint& c : constraints_) {
        for (int i : c.nodes) {
            for (int k = 0; k < 3; ++k) {
                if (c.components[k]) free[i][k] = 0;
            }
        }
    }
    return free;
}

void ExplicitSolid::correctVelocity(const std::vector<Vec3>& dv, double dt)
{
    const int nn = mesh_->nNodes();
    if (static_cast<int>(dv.size()) != nn) {
        throw Error("ExplicitSolid::correctVelocity: " + std::to_string(dv.size()) +
                    " values for " + std::to_string(nn) + " nodes");
    }
    if (!(dt >= 0) || !std::isfinite(dt)) {
        throw Error("ExplicitSolid::correctVelocity: the step must be non-negative and finite, not " +
                    std::to_string(dt));
    }
    const std::vector<Vec3> free = freeComponents();
    for (int i = 0; i < nn; ++i) {
        if (!dv[i].allFinite()) {
            throw Error("ExplicitSolid::correctVelocity: node " + std::to_string(i) +
                        " has a non-finite velocity correction at t = " + std::to_string(t_));
        }
        const Vec3 d = dv[i].cwiseProduct(free[i]);
        vHalf_[i] += d;
        u_[i] += dt * d;
    }
}

std::vector<Vec3> ExplicitSolid::interactionForce(double dt)
{
    if (!(dt > 0) || !std::isfinite(dt)) {
        throw Error("ExplicitSolid::interactionForce: the step must be positive and finite, not " +
                    std::to_string(dt));
    }
    if (loadUpdate_) loadUpdate_(t_);
    std::vector<Vec3> f;
    carried_ = true;
    try {
        accelerationForces(f, dt);
    } catch (...) {
        carried_ = false;
        throw;
    }
    carried_ = false;
    const std::vector<Vec3> free = freeComponents();
    const int nn = mesh_->nNodes();
    for (int i = 0; i < nn; ++i) {
        f[i] = f[i].cwiseProduct(free[i]);
        if (!f[i].allFinite()) {
            throw Error("ExplicitSolid::interactionForce: node " + std::to_string(i) +
                        " has a non-finite force at t = " + std::to_string(t_));
        }
    }
    return f;
}

void ExplicitSolid::moveWith(const std::vector<Vec3>& v, double dt)
{
    const int nn = mesh_->nNodes();
    if (static_cast<int>(v.size()) != nn) {
        throw Error("ExplicitSolid::moveWith: " + std::to_string(v.size()) + " velocities for " +
                    std::to_string(nn) + " nodes");
    }
    if (!(dt > 0) || !std::isfinite(dt)) {
        throw Error("ExplicitSolid::moveWith: the step must be positive and finite, not " +
                    std::to_string(dt));
    }
    for (int i = 0; i < nn; ++i) {
        if (!v[i].allFinite()) {
            throw Error("ExplicitSolid::moveWith: node " + std::to_string(i) +
                        " has a non-finite velocity at t = " + std::to_string(t_));
        }
    }
    const std::vector<Vec3> free = freeComponents();
    for (int i = 0; i < nn; ++i) {
        for (int k = 0; k < 3; ++k) {
            if (free[i][k] > 0) vHalf_[i][k] = v[i][k];
        }
    }
    applyConstraints(dt);
    for (int i = 0; i < nn; ++i) u_[i] += dt * vHalf_[i];
    t_ += dt;
    dtLast_ = dt;
    ++nSteps_;
}

KinematicContact ExplicitSolid::constrainCarriedVelocity(std::vector<Vec3>& v, double dt) const
{
    if (!contact_ || !contact_->options().kinematic) return {};
    const int nn = mesh_->nNodes();
    if (static_cast<int>(v.size()) != nn) {
        throw Error("ExplicitSolid::constrainCarriedVelocity: " + std::to_string(v.size()) +
                    " velocities for " + std::to_string(nn) + " nodes");
    }
    const std::vector<Vec3> free = freeComponents();
    std::vector<double> invMass(nn, 0.0);
    for (int i = 0; i < nn; ++i) {
        if (free[i].minCoeff() > 0) invMass[i] = 1.0 / mass_[i];
    }
    return contact_->constrainVelocities(*mesh_, currentCoordinates(), v, invMass, dt);
}

// Sub-steps of equal size within what is left of dt, re-chosen after each
// one: the stable step follows the deformation and shrinks when contact
// comes near
int ExplicitSolid::advance(double dt)
{
    if (!(dt > 0) || !std::isfinite(dt)) {
        throw Error("ExplicitSolid::advance: the time interval must be positive and finite, not " +
                    std::to_string(dt));
    }
    double left = dt;
    int n = 0;
    for (;;) {
        // A stable step that collapses (a blown-up solid: omega_max grows
        // without bound as elements flatten) stops here, with the state of
        // the last sub-step kept, rather than in an integer overflow
        const double h0 = stableTimeStep();
        if (!(h0 * kMaxSubSteps > left)) {
            std::ostringstream os;
            os << "ExplicitSolid::advance: the stable step " << h0 << " s at t = " << t_
               << " (step " << nSteps_ << ") would take more than " << kMaxSubSteps
               << " sub-steps for the remaining " << left
               << " s: the solid has blown up (elements nearly flat); reduce the time step "
                  "or check the loads";
            throw Error(os.str());
        }
        const int k = static_cast<int>(std::ceil(left / h0 - 1e-12));
        ++n;
        if (k <= 1) {
            step(left);
            return n;
        }
        const double h = left / k;
        step(h);
        left -= h;
    }
}

// Cauchy stress and J per element, from the domains it takes part in: the
// mean of its 4 face (or node) domains' values, the element's own for FEM-T4;
// with the selective scheme the deviatoric part from its face domains and
// the volumetric part (and J) from its node domains
void ExplicitSolid::elementStress(std::vector<Mat3>& sigma, std::vector<double>& J) const
{
    const TetMesh& mesh = *mesh_;
    const int ne = mesh.nElements();
    sigma.assign(ne, Mat3::Zero());
    J.assign(ne, 0.0);
    const Material& m = *material_;
    deformationGradients(u_);
    for (std::size_t k = 0; k < uses_.size(); ++k) {
        const std::vector<Mat3>& F = Fd_[k];
        const int nd = static_cast<int>(F.size());
        std::vector<Mat3> s(nd);
        std::vector<double> j(nd);
        const std::vector<Vec3>* a = fibres(k);
        for (int d = 0; d < nd; ++d) {
            Mat3 P = Mat3::Zero();
            switch (uses_[k].part) {
                case StressPart::Full: P = a ? m.firstPK(F[d], (*a)[d]) : m.firstPK(F[d]); break;
                case StressPart::Deviatoric:
                    P = a ? m.stressDeviatoric(F[d], (*a)[d]) : m.stressDeviatoric(F[d]);
                    break;
                case StressPart::Volumetric: P = m.stressVolumetric(F[d]); break;
            }
            j[d] = F[d].determinant();
            s[d] = P * F[d].transpose() / j[d];
        }
        const bool takesJ = uses_[k].part != StressPart::Deviatoric;
        for (int e = 0; e < ne; ++e) {
            switch (uses_[k].kind) {
                case DomainKind::Element:
                    sigma[e] += s[e];
                    if (takesJ) J[e] += j[e];
                    break;
                case DomainKind::Face:
                    for (int f : mesh.elementFaces()[e]) {
                        sigma[e] += 0.25 * s[f];
                        if (takesJ) J[e] += 0.25 * j[f];
                    }
                    break;
                case DomainKind::Node:
                    for (int v : mesh.elements()[e]) {
                        sigma[e] += 0.25 * s[v];
                        if (takesJ) J[e] += 0.25 * j[v];
                    }
                    break;
            }
        }
    }
}

// ---------------------------------------------------------------------------
// State files: binary, native byte order.
//   tag "smoothedSolid-state\0", version (int32),
//   nodes, elements (int64), formulation, material (int32 length + chars),
//   t, dtLast, nSteps, bound (omega2Max, age, interval, omega2 per node),
//   u, v, f_ext, maxPenetration, contact flag (+ contact state, contact pressure)

namespace {

constexpr char kStateTag[] = "smoothedSolid-state";
constexpr std::int32_t kStateVersion = 2;

template <class T>
void put(std::ostream& os, const T& v)
{
    os.write(reinterpret_cast<const char*>(&v), sizeof v);
}

void putString(std::ostream& os, const std::string& s)
{
    put(os, static_cast<std::int32_t>(s.size()));
    os.write(s.data(), static_cast<std::streamsize>(s.size()));
}

template <class T>
void putVector(std::ostream& os, const std::vector<T>& v)
{
    put(os, static_cast<std::int64_t>(v.size()));
    os.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(sizeof(T) * v.size()));
}

class Reader {
public:
    Reader(std::istream& is, std::string file) : is_(is), file_(std::move(file)) {}

    template <class T>
    T get(const char* what)
    {
        T v{};
        is_.read(reinterpret_cast<char*>(&v), sizeof v);
        if (!is_) truncated(what);
        return v;
    }
    std::string getString(const char* what)
    {
        const auto n = get<std::int32_t>(what);
        if (n < 0 || n > 4096) corrupt(what);
        std::string s(static_cast<std::size_t>(n), '\0');
        is_.read(s.data(), n);
        if (!is_) truncated(what);
        return s;
    }
    template <class T>
    void getVector(std::vector<T>& v, std::size_t expected, const char* what)
    {
        const auto n = get<std::int64_t>(what);
        if (n < 0 || (expected != std::size_t(-1) && static_cast<std::size_t>(n) != expected)) {
            throw Error("state file '" + file_ + "': " + what + " has " + std::to_string(n) +
                        " entries, this solid expects " + std::to_string(expected));
        }
        if (n > (std::int64_t(1) << 34)) corrupt(what);
        v.resize(static_cast<std::size_t>(n));
        is_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(sizeof(T) * v.size()));
        if (!is_) truncated(what);
    }
    [[noreturn]] void truncated(const char* what)
    {
        throw Error("state file '" + file_ + "' is truncated (reading " + what +
                    "): write it again or restart from an earlier one");
    }
    [[noreturn]] void corrupt(const char* what)
    {
        throw Error("state file '" + file_ + "' is corrupt (reading " + what + ")");
    }
    const std::string& file() const { return file_; }

private:
    std::istream& is_;
    std::string file_;
};

}  // namespace

void ExplicitSolid::saveState(const std::string& fileName) const
{
    std::ofstream os(fileName, std::ios::binary);
    if (!os) throw Error("cannot write state file '" + fileName + "'");
    saveState(os, fileName);
}

void ExplicitSolid::loadState(const std::string& fileName)
{
    std::ifstream is(fileName, std::ios::binary);
    if (!is) throw Error("cannot open state file '" + fileName + "'");
    loadState(is, fileName);
}

void ExplicitSolid::saveState(std::ostream& os, const std::string& fileName) const
{
    os.write(kStateTag, sizeof kStateTag);
    put(os, kStateVersion);
    put(os, static_cast<std::int64_t>(mesh_->nNodes()));
    put(os, static_cast<std::int64_t>(mesh_->nElements()));
    putString(os, toString(options_.formulation));
    putString(os, material_->name());
    put(os, t_);
    put(os, dtLast_);
    put(os, static_cast<std::int64_t>(nSteps_));
    put(os, omega2Max_);
    put(os, static_cast<std::int32_t>(boundAge_));
    put(os, static_cast<std::int32_t>(boundInterval_));
    putVector(os, nodeOmega2_);
    putVector(os, u_);
    putVector(os, vHalf_);
    putVector(os, fext_);
    put(os, maxPenetration_);
    put(os, static_cast<std::int32_t>(contact_ ? 1 : 0));
    if (contact_) {
        contact_->writeState(os);
        putVector(os, contactPressure_);
    }
    os.write(kStateTag, sizeof kStateTag);  // end mark: a cut file is found
    if (!os) throw Error("error while writing state file '" + fileName + "'");
}

void ExplicitSolid::loadState(std::istream& is, const std::string& fileName)
{
    Reader r(is, fileName);
    char tag[sizeof kStateTag] = {};
    is.read(tag, sizeof tag);
    if (!is || std::string(tag) != kStateTag) {
        throw Error("'" + fileName + "' is not a smoothedSolid state file");
    }
    const auto version = r.get<std::int32_t>("version");
    if (version != kStateVersion) {
        throw Error("state file '" + fileName + "' has format version " + std::to_string(version) +
                    ", this library reads version " + std::to_string(kStateVersion));
    }
    auto mismatch = [&](const std::string& what, const std::string& file, const std::string& here) {
        throw Error("state file '" + fileName + "' is for a solid with " + what + " " + file +
                    ", this solid has " + here);
    };
    const auto nodes = r.get<std::int64_t>("node count");
    const auto elems = r.get<std::int64_t>("element count");
    if (nodes != mesh_->nNodes()) mismatch("nodes:", std::to_string(nodes), std::to_string(mesh_->nNodes()));
    if (elems != mesh_->nElements()) {
        mismatch("elements:", std::to_string(elems), std::to_string(mesh_->nElements()));
    }
    const std::string form = r.getString("formulation");
    if (form != toString(options_.formulation)) mismatch("formulation", form, toString(options_.formulation));
    const std::string mat = r.getString("material");
    if (mat != material_->name()) mismatch("material", mat, material_->name());

    // Read into copies: a failed load leaves this solid as it was
    const auto t = r.get<double>("time");
    const auto dtLast = r.get<double>("last step");
    const auto nSteps = r.get<std::int64_t>("step count");
    const auto omega2Max = r.get<double>("stable step bound");
    const auto age = r.get<std::int32_t>("bound age");
    const auto interval = r.get<std::int32_t>("bound interval");
    std::vector<double> omega2;
    std::vector<Vec3> u, v, f;
    const std::size_t nn = mesh_->nNodes();
    r.getVector(omega2, nn, "node frequencies");
    r.getVector(u, nn, "displacement");
    r.getVector(v, nn, "velocity");
    r.getVector(f, nn, "external force");
    const auto maxPen = r.get<double>("penetration");
    const bool hadContact = r.get<std::int32_t>("contact flag") != 0;
    if (hadContact != bool(contact_)) {
        mismatch("contact", hadContact ? "enabled" : "disabled", contact_ ? "enabled" : "disabled");
    }
    std::vector<double> pressure;
    std::unique_ptr<PenaltyContact::State> cstate;
    if (contact_) {
        cstate = contact_->readState(is, fileName);
        r.getVector(pressure, nn, "contact pressure");
    }
    char end[sizeof kStateTag] = {};
    is.read(end, sizeof end);
    if (!is || std::string(end) != kStateTag) r.truncated("end mark");

    t_ = t;
    dtLast_ = dtLast;
    nSteps_ = nSteps;
    omega2Max_ = omega2Max;
    boundAge_ = age;
    boundInterval_ = interval;
    nodeOmega2_ = std::move(omega2);
    u_ = std::move(u);
    vHalf_ = std::move(v);
    fext_ = std::move(f);
    maxPenetration_ = maxPen;
    if (contact_) {
        contact_->setState(std::move(*cstate));
        contactPressure_ = std::move(pressure);
    }
}

}  // namespace smoothedSolid
