#include "dynamics/CriticalStep.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>

namespace smoothedSolid {

CriticalStep criticalTimeStep(const ExplicitSolid& solid, const std::vector<Vec3>& u,
                              int iterations)
{
    const int nn = solid.mesh().nNodes();
    const int n = 3 * nn;
    const auto& m = solid.lumpedMass();
    Eigen::VectorXd invSqrtM(n);
    for (int i = 0; i < nn; ++i) invSqrtM.segment<3>(3 * i).setConstant(1.0 / std::sqrt(m[i]));
    double hMin = 1e300;
    for (int e = 0; e < solid.mesh().nElements(); ++e) hMin = std::min(hMin, solid.mesh().elementHeight(e));

    // y = M^-1/2 K M^-1/2 q, K w = (f(u + eps w) - f(u - eps w)) / (2 eps)
    std::vector<Vec3> up(nn), um(nn);
    auto apply = [&](const Eigen::VectorXd& q) {
        const Eigen::VectorXd w = invSqrtM.cwiseProduct(q);
        const double eps = 1e-7 * hMin / std::max(w.cwiseAbs().maxCoeff(), 1e-300);
        for (int i = 0; i < nn; ++i) {
            const Vec3 d = eps * w.segment<3>(3 * i);
            up[i] = u[i] + d;
            um[i] = u[i] - d;
        }
        const auto fp = solid.internalForce(up);
        const auto fm = solid.internalForce(um);
        Eigen::VectorXd y(n);
        for (int i = 0; i < nn; ++i) y.segment<3>(3 * i) = (fp[i] - fm[i]) / (2 * eps);
        return Eigen::VectorXd(invSqrtM.cwiseProduct(y));
    };

    const int k = std::min(iterations, n);
    Eigen::MatrixXd Q(n, k + 1);
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> uni(-1, 1);
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q[i] = uni(rng);
    Q.col(0) = q.normalized();
    Eigen::VectorXd alpha(k), beta(k);
    std::vector<double> history;
    int used = 0;
    for (int j = 0; j < k; ++j) {
        Eigen::VectorXd w = apply(Q.col(j));
        alpha[j] = Q.col(j).dot(w);
        // full reorthogonalisation, twice (Kahan's "twice is enough")
        for (int pass = 0; pass < 2; ++pass) w -= Q.leftCols(j + 1) * (Q.leftCols(j + 1).transpose() * w);
        beta[j] = w.norm();
        used = j + 1;
        Eigen::MatrixXd T = Eigen::MatrixXd::Zero(used, used);
        for (int i = 0; i < used; ++i) {
            T(i, i) = alpha[i];
            if (i + 1 < used) T(i, i + 1) = T(i + 1, i) = beta[i];
        }
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(T, Eigen::EigenvaluesOnly);
        history.push_back(es.eigenvalues().maxCoeff());
        if (beta[j] < 1e-12 * std::abs(alpha[j])) break;  // invariant subspace
        Q.col(j + 1) = w / beta[j];
    }
    CriticalStep r;
    r.omega2 = history.back();
    r.dt = 2.0 / std::sqrt(r.omega2);
    const std::size_t back = history.size() > 10 ? history.size() - 11 : 0;
    r.change = (history.back() - history[back]) / history.back();
    r.iterations = used;
    return r;
}

}  // namespace smoothedSolid
