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

    const int ne = mesh_.nElements();
    elemGrad_.resize(ne);
    quarterVolume_.resize(ne);
    for (int e = 0; e < ne; ++e) {
        elemGrad_[e] = elementGradients(mesh_, e);
        quarterVolume_[e] = 0.25 * mesh_.elementVolume(e);
    }
    faceWeight_.resize(mesh_.faces().size());
    for (std::size_t f = 0; f < mesh_.faces().size(); ++f) {
        const Face& fc = mesh_.faces()[f];
        const double vo = quarterVolume_[fc.owner];
        const double vn = fc.neighbour >= 0 ? quarterVolume_[fc.neighbour] : 0.0;
        faceWeight_[f] = {vo / (vo + vn), vn / (vo + vn)};
    }
    {
        const auto& start = mesh_.nodeElementStart();
        const auto& elems = mesh_.nodeElements();
        nodeWeight_.resize(elems.size());
        for (int k = 0; k < mesh_.nNodes(); ++k) {
            double V = 0;
            for (int i = start[k]; i < start[k + 1]; ++i) V += quarterVolume_[elems[i]];
            for (int i = start[k]; i < start[k + 1]; ++i) {
                nodeWeight_[i] = quarterVolume_[elems[i]] / V;
            }
        }
    }
    Fe_.resize(ne);
    Pbar_.resize(ne);
    Pf_.resize(mesh_.faces().size());
    Pn_.resize(mesh_.nNodes());
    {
        // local index (0..3) of each node in each element around it
        const auto& start = mesh_.nodeElementStart();
        const auto& elems = mesh_.nodeElements();
        nodeLocal_.resize(elems.size());
        for (int k = 0; k < mesh_.nNodes(); ++k) {
            for (int i = start[k]; i < start[k + 1]; ++i) {
                const Tet& t = mesh_.elements()[elems[i]];
                nodeLocal_[i] = static_cast<std::uint8_t>(std::find(t.begin(), t.end(), k) - t.begin());
            }
        }
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
    x_.assign(n, Vec3::Zero());
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
    if (!contact_) return dt;
    // near contact as of the last search (each force evaluation makes one)
    if (!contact_->searched()) contact_->search(mesh_, currentCoordinates());
    return contact_->nearContact() ? dt * contact_->options().stepFraction : dt;
}

void ExplicitSolid::enableContact(ContactOptions options)
{
    std::vector<RigidSurface> keep;
    if (contact_) keep = contact_->rigidSurfaces();
    contact_ = std::make_unique<PenaltyContact>(mesh_, hMin_, material_->waveModulus(),
                                                material_->density(), mass_, options);
    for (auto& s : keep) contact_->addRigidSurface(std::move(s));
    contactPressure_.assign(mesh_.nNodes(), 0.0);
}

void ExplicitSolid::addRigidSurface(RigidSurface surface)
{
    if (!contact_) enableContact();
    contact_->addRigidSurface(std::move(surface));
}

// The internal force in gather form, so that every loop writes only its own
// entries and runs in parallel with OpenMP (when built with it):
//   F_e            per element
//   P_d = P(F_d)   per smoothing domain, F_d the weighted mean of its F_e
//   Pbar_e = (V_e/4) sum of the P_d of the domains e takes part in
//   f_I = sum_{e around I} Pbar_e g_eI
std::vector<Vec3> ExplicitSolid::internalForce(const std::vector<Vec3>& u) const
{
    const Material& m = *material_;
    const auto& tets = mesh_.elements();
    const int ne = mesh_.nElements();
    const int nn = mesh_.nNodes();
    const int nf = static_cast<int>(mesh_.faces().size());

    // Element deformation gradients F_e = I + sum_a u_a (x) g_ea
#pragma omp parallel for schedule(static)
    for (int e = 0; e < ne; ++e) {
        const Tet& t = tets[e];
        const auto& g = elemGrad_[e];
        Mat3 F = Mat3::Identity();
        for (int a = 0; a < 4; ++a) F.noalias() += u[t[a]] * g.row(a);
        Fe_[e] = F;
    }

    // An inverted domain is recorded (lowest index) inside the parallel
    // loops and reported after them: exceptions cannot leave an OpenMP loop
    int badDomain = std::numeric_limits<int>::max();
    double badDet = 0;
    const char* badKind = "";
    auto check = [&](const Mat3& F, int d, const char* kind) {
        const double J = F.determinant();
        if (!(J > 0)) {
#pragma omp critical(smoothedSolidInverted)
            if (d < badDomain) badDomain = d, badDet = J, badKind = kind;
            return false;
        }
        return true;
    };
    auto report = [&] {
        if (badDomain == std::numeric_limits<int>::max()) return;
        throw Error("inverted material in " + std::string(badKind) + " smoothing domain " +
                    std::to_string(badDomain) + " at t = " + std::to_string(t_) +
                    " (det F = " + std::to_string(badDet) +
                    "): the time step or the load is too large");
    };
    // Face domains (Eq. 22 on the face-based domains): F_f from the one or
    // two elements sharing f
    auto faces = [&](auto stress) {
        const auto& fs = mesh_.faces();
#pragma omp parallel for schedule(static)
        for (int f = 0; f < nf; ++f) {
            const Face& fc = fs[f];
            const auto& w = faceWeight_[f];
            Mat3 F = w[0] * Fe_[fc.owner];
            if (fc.neighbour >= 0) F.noalias() += w[1] * Fe_[fc.neighbour];
            Pf_[f] = check(F, f, "face") ? stress(F) : Mat3::Zero();
        }
        report();
        const auto& elemFaces = mesh_.elementFaces();
#pragma omp parallel for schedule(static)
        for (int e = 0; e < ne; ++e) {
            const auto& ef = elemFaces[e];
            Pbar_[e] = quarterVolume_[e] * (Pf_[ef[0]] + Pf_[ef[1]] + Pf_[ef[2]] + Pf_[ef[3]]);
        }
    };
    // Node domains: F_k from the elements around k
    auto nodes = [&](auto stress, bool add) {
        const auto& start = mesh_.nodeElementStart();
        const auto& elems = mesh_.nodeElements();
#pragma omp parallel for schedule(static)
        for (int k = 0; k < nn; ++k) {
            Mat3 F = Mat3::Zero();
            for (int i = start[k]; i < start[k + 1]; ++i) F.noalias() += nodeWeight_[i] * Fe_[elems[i]];
            Pn_[k] = check(F, k, "node") ? stress(F) : Mat3::Zero();
        }
        report();
#pragma omp parallel for schedule(static)
        for (int e = 0; e < ne; ++e) {
            const Tet& t = tets[e];
            const Mat3 P = quarterVolume_[e] * (Pn_[t[0]] + Pn_[t[1]] + Pn_[t[2]] + Pn_[t[3]]);
            if (add) Pbar_[e] += P;
            else Pbar_[e] = P;
        }
    };
    auto full = [&](const Mat3& F) { return m.firstPK(F); };

    switch (options_.formulation) {
        case Formulation::FEM_T4:
#pragma omp parallel for schedule(static)
            for (int e = 0; e < ne; ++e) {
                Pbar_[e] = check(Fe_[e], e, "element") ? Mat3(4.0 * quarterVolume_[e] * full(Fe_[e]))
                                                       : Mat3::Zero();
            }
            report();
            break;
        case Formulation::FS_FEM: faces(full); break;
        case Formulation::NS_FEM: nodes(full, false); break;
        case Formulation::Selective:
            // Sect. 3.2: deviatoric stress on face-based domains, volumetric
            // stress on node-based domains
            faces([&](const Mat3& F) { return m.stressDeviatoric(F); });
            nodes([&](const Mat3& F) { return m.stressVolumetric(F); }, true);
            break;
    }

    // f_I = sum_e Pbar_e g_eI (Eq. 31 with the first Piola-Kirchhoff stress)
    std::vector<Vec3> f(nn);
    const auto& start = mesh_.nodeElementStart();
    const auto& elems = mesh_.nodeElements();
#pragma omp parallel for schedule(static)
    for (int k = 0; k < nn; ++k) {
        Vec3 fk = Vec3::Zero();
        for (int i = start[k]; i < start[k + 1]; ++i) {
            const int e = elems[i];
            fk.noalias() += Pbar_[e] * elemGrad_[e].row(nodeLocal_[i]).transpose();
        }
        f[k] = fk;
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
void ExplicitSolid::accelerationForces(std::vector<Vec3>& f, double dt)
{
    f = internalForce(u_);
    const int nn = mesh_.nNodes();
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nn; ++i) f[i] = fext_[i] + mass_[i] * bodyForce_ - f[i];

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
        const auto& X = mesh_.coordinates();
#pragma omp parallel for schedule(static)
        for (int i = 0; i < nn; ++i) x_[i] = X[i] + u_[i];
        maxPenetration_ = contact_->addForces(mesh_, x_, vHalf_, dt, f,
                                              contactPressure_);
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
    if (loadUpdate_) loadUpdate_(t_);
    const double dtAvg = 0.5 * (dtLast_ + dt);
    accelerationForces(work_, std::max(dt, dtAvg));

    const double c = 0.5 * options_.damping * dtAvg;
    const double a = (1.0 - c) / (1.0 + c);
    const double b = dtAvg / (1.0 + c);
    const int nn = mesh_.nNodes();
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nn; ++i) vHalf_[i] = a * vHalf_[i] + (b / mass_[i]) * work_[i];
    applyConstraints(dt);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nn; ++i) u_[i] += dt * vHalf_[i];

    t_ += dt;
    dtLast_ = dt;
    ++nSteps_;
}

// Sub-steps of equal size within what is left of dt, re-chosen after each
// one: the stable step shrinks when contact comes near
int ExplicitSolid::advance(double dt)
{
    if (dt <= 0) return 0;
    double left = dt;
    int n = 0;
    for (;;) {
        const int k = static_cast<int>(std::ceil(left / stableTimeStep() - 1e-12));
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
