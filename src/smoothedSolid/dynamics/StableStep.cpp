#include "dynamics/StableStep.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace smoothedSolid {

StableStepBound::StableStepBound(const Smoothing& smoothing, Formulation formulation,
                                 const std::vector<double>& mass)
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
        u.N0.assign(nd, Mat3::Zero());
        u.start.assign(nn + 1, 0);
        // Mass partition: each node's mass is shared among the domains
        // around it in proportion to their stiffness on it, V_d |b_dI|^2
        // (stiff, small domains get more of the mass of their nodes)
        std::vector<double> share(sd.node.size()), total(nn, 0.0);
        for (int d = 0; d < nd; ++d) {
            for (int k = sd.start[d]; k < sd.start[d + 1]; ++k) {
                share[k] = sd.volume[d] * sd.grad[k].squaredNorm();
                total[sd.node[k]] += share[k];
            }
        }
        std::vector<double> w(sd.node.size());
        for (int d = 0; d < nd; ++d) {
            for (int k = sd.start[d]; k < sd.start[d + 1]; ++k) {
                // a node whose smoothed gradient in d vanishes (it can cancel
                // on structured meshes) gets no share and adds nothing
                w[k] = share[k] > 0 ? mass[sd.node[k]] * share[k] / total[sd.node[k]] : 0.0;
                if (w[k] > 0) u.N0[d].noalias() += sd.grad[k] * sd.grad[k].transpose() / w[k];
                ++u.start[sd.node[k] + 1];
            }
        }
        for (int i = 0; i < nn; ++i) u.start[i + 1] += u.start[i];
        u.domain.resize(u.start[nn]);
        u.weight.resize(u.start[nn]);
        std::vector<int> fill(u.start.begin(), u.start.end() - 1);
        for (int d = 0; d < nd; ++d) {
            for (int k = sd.start[d]; k < sd.start[d + 1]; ++k) {
                const int i = fill[sd.node[k]]++;
                u.domain[i] = d;
                u.weight[i] = w[k];
            }
        }
        u.rhoD.resize(nd);
        uses_.push_back(std::move(u));
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
                const auto b = material.tangentBoundDeviatoric(Fdd, lambda2);
                t.shear += b.shear, t.bulk += b.bulk;
            }
            if (part != StressPart::Deviatoric) {
                const auto b = material.tangentBoundVolumetric(Fdd, lambda2);
                t.shear += b.shear, t.bulk += b.bulk;
            }
            const Mat3 Finv = Fdd.inverse();
            const Mat3 N = Finv.transpose() * u.N0[d] * Finv;
            double nMax = N.trace();
            if (t.shear > 0) {
                es.computeDirect(N, Eigen::EigenvaluesOnly);
                nMax = es.eigenvalues()[2];
            }
            u.rhoD[d] = J * u.volume[d] * (t.shear * nMax + t.bulk * N.trace());
        }
#pragma omp parallel for schedule(static)
        for (int i = 0; i < nn; ++i) {
            double s = 0;
            for (int j = u.start[i]; j < u.start[i + 1]; ++j) s += u.rhoD[u.domain[j]] * u.weight[j];
            omega2[i] += s * invMass_[i];
        }
    }
    double m = 0;
    for (double w : omega2) m = std::isnan(w) ? w : std::max(m, w);
    return m;
}

}  // namespace smoothedSolid
