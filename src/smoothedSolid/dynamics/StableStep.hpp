// A bound of the critical time step of the central difference in the
// current configuration: dt_crit = 2 / omega_max, omega_max^2 the largest
// eigenvalue of M^-1 K_T(u) (Belytschko, Liu & Moran, Nonlinear Finite
// Elements, 2000, Sect. 6.3: lumped mass M, tangent stiffness K_T).
//
// K_T sums over smoothing domains d (reference volume V_d, smoothed
// reference gradients b_dI, deformation gradient F_d, J_d):
//   u.K_T u = sum_d J_d V_d Q_d(G_d),  G_d = sum_I u_I (x) bt_dI,  bt_dI = F_d^-T b_dI,
// with Q_d(G) <= s_d |G|^2 + k_d (tr G)^2 from the material
// (Material::tangentBound*). Each node's lumped mass is partitioned over
// the domains it takes part in, w_dI >= 0 with sum_d w_dI = m_I for each
// kind of domain, in proportion to the domain's stiffness on the node,
// V_d |b_dI|^2 (stiff, small domains take more of their nodes' mass). By
// Cauchy-Schwarz,
// with the 3x3 matrix N_d = sum_I bt_dI bt_dI^T / w_dI = F_d^-T N0_d F_d^-1,
//   |G_d|^2   <= lambda_max(N_d) sum_I w_dI |u_I|^2,
//   (tr G_d)^2 <= tr(N_d)       sum_I w_dI |u_I|^2,
// so that, with rho_d = J_d V_d (s_d lambda_max(N_d) + k_d tr(N_d)),
//   u.K_T u <= sum_I |u_I|^2 sum_d rho_d w_dI = sum_I m_I omega_I^2 |u_I|^2,
//   omega_I^2 = (1/m_I) sum_{d around I} rho_d w_dI,
// A fibre-reinforced material adds fibre_d |G_d a|^2, a = F_d a0_d the
// current fibre (Material::TangentBound::fibre); G_d a = sum_I u_I (b_dI . a0_d)
// since bt_dI . F_d a0 = b_dI . a0, so by the same Cauchy-Schwarz step
//   |G_d a|^2 <= (a0_d . N0_d a0_d) sum_I w_dI |u_I|^2,
// and rho_d gains J_d V_d fibre_d (a0_d . N0_d a0_d). The bound is a sum of
// terms, each bounded by its own Cauchy-Schwarz step, so the fibre term
// takes its own weights wf_dI, balanced for the fibre operator
// sum_d V_d (sum_I u_I c_dI)^2, c_dI = b_dI . a0_d (the fibres stiffen a
// different, one-dimensional pattern than the matrix): it adds
// J_d V_d fibre_d (sum_I c_dI^2 / wf_dI) wf_dI / m_I to omega_I^2.
// Then omega_max^2 <= max_I omega_I^2 (an element-by-element bound in the
// manner of Irons' theorem, Hughes, The Finite Element Method, 1987,
// Sect. 9.3). The selective scheme adds its face (deviatoric) and node
// (volumetric) sums. The bound follows the deformation: an element that
// thins out raises N_d through F_d^-1, a stiffening material raises s_d
// and k_d. The per-node omega_I^2 also give the contact springs their
// budget (PenaltyContact): sum_I m_I (omega_I^2 + c_I)|u_I|^2 bounds the sum
// with a contact stiffness of row sums m_I c_I.
#pragma once

#include "material/Material.hpp"
#include "smoothing/SmoothingDomains.hpp"

#include <vector>

namespace smoothedSolid {

class StableStepBound {
public:
    // material: the weights are balanced for it in the reference
    // configuration (balanceIterations rounds, 0: the initial partition)
    StableStepBound(const Smoothing& smoothing, Formulation formulation,
                    const std::vector<double>& mass, const Material& material,
                    int balanceIterations = kBalanceIterations);
    static constexpr int kBalanceIterations = 60;

    // omega_I^2 per node for the domain deformation gradients Fd (one array
    // per DomainUse of the formulation, in the order of domainUses());
    // returns max_I omega_I^2
    double evaluate(const Material& material, const std::vector<const std::vector<Mat3>*>& Fd,
                    std::vector<double>& omega2) const;

    // Reference fibre directions of each use's domains (null: none, e.g. the
    // volumetric part); until set, a fibre material's bound holds for any
    // direction. The fibre term gets its own weights (below).
    void setFibres(const std::vector<const std::vector<Vec3>*>& a0);

private:
    struct Use {
        DomainUse use;
        std::vector<double> volume;  // V_d
        std::vector<Mat3> N0;        // sum_I b_dI b_dI^T / w_dI
        // domain entries (as SmoothingDomains): b_dI and w_dI
        std::vector<int> entryStart;
        std::vector<int> node;
        std::vector<Vec3> grad;
        std::vector<double> weight;
        // per node I: its entries and their domains (CSR)
        std::vector<int> start, entry, domain;
        std::vector<double> nodeWeight;  // w_dI / m_I in CSR order
        // fibre term: directions per domain, weights per entry, sum c^2/wf
        // per domain, wf_dI / m_I in CSR order (empty without fibres)
        std::vector<Vec3> fibre;
        std::vector<double> fibreWeight, fibreC, fibreNodeWeight;
        mutable std::vector<double> rhoF;
        mutable std::vector<double> rhoD;  // rho_d of the last evaluation
    };
    void updateN0();
    void balance(const Material& material, int iterations);

    std::vector<Use> uses_;
    std::vector<double> invMass_;
};

}  // namespace smoothedSolid
