#include "dynamics/StableStep.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace smoothedSolid {

namespace {

// Rounds of w_dI <- w_dI (omega_I^2 / max_J omega_J^2)^(-1/2) on each
// node's weights (scaleNode), while max_I omega_I^2 falls by more than
// 0.02 % a round, keeping the best weights: omegas(w2) brings the bound up
// to date with the weights, writes omega_I^2 and returns their maximum;
// weights are the arrays saved and restored
void balanceRounds(int iterations, const std::function<double(std::vector<double>&)>& omegas,
                   const std::function<void(int, double)>& scaleNode,
                   const std::vector<std::vector<double>*>& weights)
{
    std::vector<double> w2;
    double best = omegas(w2);
    std::vector<std::vector<double>> saved;
    for (const auto* w : weights) saved.push_back(*w);
    for (int it = 0; it < iterations && best > 0; ++it) {
        for (int i = 0; i < static_cast<int>(w2.size()); ++i) {
            if (w2[i] > 0) scaleNode(i, 1.0 / std::sqrt(w2[i] / best));
        }
        const double m = omegas(w2);
        if (!(m < best)) break;
        const bool converged = m > 0.9998 * best;
        best = m;
        for (std::size_t k = 0; k < weights.size(); ++k) saved[k] = *weights[k];
        if (converged) break;
    }
    for (std::size_t k = 0; k < weights.size(); ++k) *weights[k] = std::move(saved[k]);
}

}  // namespace

StableStepBound::StableStepBound(const Smoothing& smoothing, Formulation formulation,
                                 const std::vector<double>& mass, const Material& material,
                                 int balanceIterations)
{
    const int nn = smoothing.mesh().nNodes();
    invMass_.resize(nn);
    for (int i = 0; i < nn; ++i) invMass_[i] = 1.0 / mass[i];

    for (const DomainUse& du : domainUses(formulation)) {
        const SmoothingDomains sd = smoothing.merged(du.kind);
        Use u;
        u.use = du;
        const int nd = sd.size();
        u.volume = sd.volume;
        u.entryStart = sd.start;
        u.grad = sd.grad;
        u.node = sd.node;
        u.N0.assign(nd, Mat3::Zero());
        u.start.assign(nn + 1, 0);
        // Initial mass partition: each node's mass is shared among the
        // domains around it in proportion to their stiffness on it,
        // V_d |b_dI|^2 (stiff, small domains get more of the mass of their
        // nodes); balance() then improves it
        std::vector<double> share(sd.node.size()), total(nn, 0.0);
        for (int d = 0; d < nd; ++d) {
            for (int k = sd.start[d]; k < sd.start[d + 1]; ++k) {
                share[k] = sd.volume[d] * sd.grad[k].squaredNorm();
                total[sd.node[k]] += share[k];
            }
        }
        u.weight.resize(sd.node.size());
        for (int d = 0; d < nd; ++d) {
            for (int k = sd.start[d]; k < sd.start[d + 1]; ++k) {
                // a node whose smoothed gradient in d vanishes (it can cancel
                // on structured meshes) gets no share and adds nothing
                u.weight[k] = share[k] > 0 ? mass[sd.node[k]] * share[k] / total[sd.node[k]] : 0.0;
                ++u.start[sd.node[k] + 1];
            }
        }
        for (int i = 0; i < nn; ++i) u.start[i + 1] += u.start[i];
        u.entry.resize(u.start[nn]);
        u.domain.resize(u.start[nn]);
        std::vector<int> fill(u.start.begin(), u.start.end() - 1);
        for (int d = 0; d < nd; ++d) {
            for (int k = sd.start[d]; k < sd.start[d + 1]; ++k) {
                const int i = fill[sd.node[k]]++;
                u.entry[i] = k;
                u.domain[i] = d;
            }
        }
        u.rhoD.resize(nd);
        uses_.push_back(std::move(u));
    }
    updateN0();
    balance(material, balanceIterations);
}

void StableStepBound::updateN0()
{
    for (Use& u : uses_) {
        const int nn = static_cast<int>(invMass_.size());
        u.nodeWeight.resize(u.entry.size());
        for (int i = 0; i < nn; ++i) {
            for (int j = u.start[i]; j < u.start[i + 1]; ++j) u.nodeWeight[j] = u.weight[u.entry[j]] * invMass_[i];
        }
        const int nd = static_cast<int>(u.volume.size());
#pragma omp parallel for schedule(static)
        for (int d = 0; d < nd; ++d) {
            Mat3 N = Mat3::Zero();
            for (int k = u.entryStart[d]; k < u.entryStart[d + 1]; ++k) {
                if (u.weight[k] > 0) N.noalias() += u.grad[k] * u.grad[k].transpose() / u.weight[k];
            }
            u.N0[d] = N;
        }
    }
}

// The bound holds for any positive weights w_dI (the Cauchy-Schwarz step
// needs no normalisation: a common factor cancels between N_d and w_dI), so
// they are chosen to make it tight in the reference configuration: a node
// whose omega_I^2 is above the others gives up weight (its own term in
// omega_I^2 shrinks, the other nodes of its domains pay for it through N_d),
// w_dI <- w_dI (omega_I^2)^(-1/2), while max_I omega_I^2 falls by more than
// 0.02 % a round (the first rounds gain 1-3 % each; in all about 15 %, e.g.
// selective on gmsh tets from 0.63 to 0.67 of the critical step). Any weights remain a
// bound under deformation.
void StableStepBound::balance(const Material& material, int iterations)
{
    std::vector<std::vector<Mat3>> identity;
    std::vector<const std::vector<Mat3>*> F;
    for (const Use& u : uses_) identity.emplace_back(u.volume.size(), Mat3::Identity());
    for (const auto& f : identity) F.push_back(&f);
    std::vector<std::vector<double>*> weights;
    for (Use& u : uses_) weights.push_back(&u.weight);
    balanceRounds(
        iterations,
        [&](std::vector<double>& w2) {
            updateN0();
            return evaluate(material, F, w2);
        },
        [&](int i, double scale) {
            for (Use& u : uses_) {
                for (int j = u.start[i]; j < u.start[i + 1]; ++j) u.weight[u.entry[j]] *= scale;
            }
        },
        weights);
    updateN0();
}

// The fibre operator's weights: initially each node's mass shared in
// proportion to V_d c_dI^2, then balanced the same way (balanceRounds) for
// sum_d V_d (sum_I u_I c_dI)^2 alone (rho_d = V_d sum_I c_dI^2 / wf_dI)
void StableStepBound::setFibres(const std::vector<const std::vector<Vec3>*>& a0)
{
    const int nn = static_cast<int>(invMass_.size());
    for (std::size_t k = 0; k < uses_.size(); ++k) {
        Use& u = uses_[k];
        const int nd = static_cast<int>(u.volume.size());
        if (k >= a0.size() || !a0[k]) {
            u.fibre.clear(), u.fibreWeight.clear(), u.fibreC.clear(), u.fibreNodeWeight.clear();
            continue;
        }
        u.fibre = *a0[k];
        std::vector<double> c(u.grad.size()), total(nn, 0.0);
        for (int d = 0; d < nd; ++d) {
            for (int e = u.entryStart[d]; e < u.entryStart[d + 1]; ++e) {
                c[e] = u.grad[e].dot(u.fibre[d]);
                total[u.node[e]] += u.volume[d] * c[e] * c[e];
            }
        }
        u.fibreWeight.assign(u.grad.size(), 0.0);
        for (int d = 0; d < nd; ++d) {
            for (int e = u.entryStart[d]; e < u.entryStart[d + 1]; ++e) {
                const int I = u.node[e];
                const double share = u.volume[d] * c[e] * c[e];
                if (share > 0) u.fibreWeight[e] = share / (total[I] * invMass_[I]);
            }
        }
        u.fibreC.assign(nd, 0.0);
        u.fibreNodeWeight.assign(u.entry.size(), 0.0);
        u.rhoF.assign(nd, 0.0);
        auto update = [&]() {
            for (int d = 0; d < nd; ++d) {
                double sum = 0;
                for (int e = u.entryStart[d]; e < u.entryStart[d + 1]; ++e) {
                    if (u.fibreWeight[e] > 0) sum += c[e] * c[e] / u.fibreWeight[e];
                }
                u.fibreC[d] = sum;
            }
            for (int i = 0; i < nn; ++i) {
                for (int j = u.start[i]; j < u.start[i + 1]; ++j) {
                    u.fibreNodeWeight[j] = u.fibreWeight[u.entry[j]] * invMass_[i];
                }
            }
        };
        auto omegas = [&](std::vector<double>& w2) {
            w2.assign(nn, 0.0);
            double m = 0;
            for (int i = 0; i < nn; ++i) {
                for (int j = u.start[i]; j < u.start[i + 1]; ++j) {
                    w2[i] += u.volume[u.domain[j]] * u.fibreC[u.domain[j]] * u.fibreNodeWeight[j];
                }
                m = std::max(m, w2[i]);
            }
            return m;
        };
        balanceRounds(
            kBalanceIterations,
            [&](std::vector<double>& w2) {
                update();
                return omegas(w2);
            },
            [&](int i, double scale) {
                for (int j = u.start[i]; j < u.start[i + 1]; ++j) u.fibreWeight[u.entry[j]] *= scale;
            },
            {&u.fibreWeight});
        update();
    }
}

double StableStepBound::evaluate(const Material& material,
                                 const std::vector<const std::vector<Mat3>*>& Fd,
                                 std::vector<double>& omega2) const
{
    const int nn = static_cast<int>(invMass_.size());
    omega2.assign(nn, 0.0);
    for (std::size_t k = 0; k < uses_.size(); ++k) {
        const Use& u = uses_[k];
        const std::vector<Mat3>& F = *Fd[k];
        const int nd = static_cast<int>(u.rhoD.size());
        const StressPart part = u.use.part;
        const std::vector<Vec3>* fibre = u.fibre.empty() ? nullptr : &u.fibre;
#pragma omp parallel for schedule(static)
        for (int d = 0; d < nd; ++d) {
            const Mat3& Fdd = F[d];
            const double J = Fdd.determinant();
            if (!(J > 0)) {
                u.rhoD[d] = std::numeric_limits<double>::infinity();
                continue;
            }
            Eigen::SelfAdjointEigenSolver<Mat3> es;
            es.computeDirect(Fdd.transpose() * Fdd, Eigen::EigenvaluesOnly);
            const Vec3 lambda2 = es.eigenvalues();
            Material::TangentBound t;
            if (part != StressPart::Volumetric) {
                const auto b = fibre ? material.tangentBoundDeviatoric(Fdd, lambda2, (*fibre)[d])
                                     : material.tangentBoundDeviatoric(Fdd, lambda2);
                t.shear += b.shear, t.bulk += b.bulk, t.fibre += b.fibre;
            }
            if (part != StressPart::Deviatoric) {
                const auto b = material.tangentBoundVolumetric(Fdd, lambda2);
                t.shear += b.shear, t.bulk += b.bulk;
            }
            const Mat3 Finv = Fdd.inverse();
            const Mat3 N = Finv.transpose() * u.N0[d] * Finv;
            // lambda_max(N) <= tr N / 3 + sqrt(2/3) |dev N| (the largest
            // eigenvalue of a traceless symmetric 3x3 matrix is at most
            // sqrt(2/3) of its Frobenius norm; equality for two equal
            // eigenvalues, at most 15 % above otherwise)
            const double trN = N.trace();
            const double dev2 = N.squaredNorm() - trN * trN / 3.0;
            const double nMax = trN / 3.0 + std::sqrt(std::max(0.0, 2.0 / 3.0 * dev2));
            u.rhoD[d] = J * u.volume[d] * (t.shear * nMax + t.bulk * trN);
            if (fibre) u.rhoF[d] = J * u.volume[d] * t.fibre * u.fibreC[d];
        }
#pragma omp parallel for schedule(static)
        for (int i = 0; i < nn; ++i) {
            double s = 0;
            for (int j = u.start[i]; j < u.start[i + 1]; ++j) s += u.rhoD[u.domain[j]] * u.nodeWeight[j];
            if (!u.fibre.empty()) {
                for (int j = u.start[i]; j < u.start[i + 1]; ++j) s += u.rhoF[u.domain[j]] * u.fibreNodeWeight[j];
            }
            omega2[i] += s;
        }
    }
    double m = 0;
    bool nan = false;
    for (double w : omega2) {
        m = std::max(m, w);
        nan |= std::isnan(w);
    }
    return nan ? std::numeric_limits<double>::quiet_NaN() : m;
}

}  // namespace smoothedSolid
