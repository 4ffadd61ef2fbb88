#include "material/Material.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace smoothedSolid {

namespace {

void requirePositive(const std::string& material, const std::string& what, double v)
{
    if (!(v > 0) || !std::isfinite(v)) {
        throw Error(material + ": " + what + " must be positive (got " + std::to_string(v) +
                    ")");
    }
}

double jacobian(const Mat3& F, const char* who)
{
    const double J = F.determinant();
    if (!(J > 0)) {
        throw Error(std::string(who) + ": det F = " + std::to_string(J) +
                    " <= 0 (inverted material)");
    }
    return J;
}

}  // namespace

Material::Material(double rho) : rho_(rho) { requirePositive("material", "density", rho); }

// ---------------------------------------------------------------------------

MooneyRivlin::MooneyRivlin(double c10, double c01, double kappa, double rho)
    : Material(rho), c10_(c10), c01_(c01), kappa_(kappa)
{
    requirePositive("MooneyRivlin", "c10", c10);
    if (!(c01 >= 0)) {
        throw Error("MooneyRivlin: c01 must be non-negative (got " + std::to_string(c01) + ")");
    }
    requirePositive("MooneyRivlin", "kappa", kappa);
}

double MooneyRivlin::kappaFromPoisson(double c10, double c01, double nu)
{
    if (!(nu > -1.0 && nu < 0.5)) {
        throw Error("MooneyRivlin: Poisson ratio must lie in (-1, 0.5) (got " +
                    std::to_string(nu) + ")");
    }
    return 2.0 * (c10 + c01) / (1.0 - 2.0 * nu);  // Eq. 27
}

double MooneyRivlin::energyDeviatoric(const Mat3& F) const
{
    const double J = jacobian(F, "MooneyRivlin");
    const Mat3 C = F.transpose() * F;
    const double I1 = C.trace();
    const double I2 = 0.5 * (I1 * I1 - (C * C).trace());  // corrected Eq. 26
    return c10_ * (I1 * std::pow(J, -2.0 / 3.0) - 3.0) +
           c01_ * (I2 * std::pow(J, -4.0 / 3.0) - 3.0);
}

double MooneyRivlin::energyVolumetric(const Mat3& F) const
{
    const double J = F.determinant();
    return 0.5 * kappa_ * (J - 1.0) * (J - 1.0);
}

// dI1/dF = 2F, dI2/dF = 2(I1 F - F C), dJ/dF = J F^-T
Mat3 MooneyRivlin::stressDeviatoric(const Mat3& F) const
{
    const double J = jacobian(F, "MooneyRivlin");
    const Mat3 C = F.transpose() * F;
    const double I1 = C.trace();
    const double I2 = 0.5 * (I1 * I1 - C.squaredNorm());  // C symmetric: tr(C^2) = |C|^2
    const Mat3 FinvT = F.inverse().transpose();
    const double Jm13 = 1.0 / std::cbrt(J);
    const double J23 = Jm13 * Jm13;  // J^(-2/3)
    const double J43 = J23 * J23;    // J^(-4/3)
    return c10_ * J23 * (2.0 * F - (2.0 / 3.0) * I1 * FinvT) +
           c01_ * J43 * (2.0 * (I1 * F - F * C) - (4.0 / 3.0) * I2 * FinvT);
}

Mat3 MooneyRivlin::stressVolumetric(const Mat3& F) const
{
    const double J = jacobian(F, "MooneyRivlin");
    return kappa_ * (J - 1.0) * J * F.inverse().transpose();
}

// Tangent bounds (see Material.hpp). Isochoric part (Holzapfel 2000,
// Sect. 6.6, in Kirchhoff form), with bbar = J^(-2/3) F F^T (eigenvalues
// beta_i), the fictitious Kirchhoff stress taubar and elasticity cbar:
//   c_iso = P:cbar:P + (2/3) tr(taubar) P - (2/3)(tau_iso (x) I + I (x) tau_iso),
//   P = II - (1/3) I (x) I,  tau_iso = dev taubar,
//   taubar = 2 c10 bbar + 2 c01 (I1bar bbar - bbar^2),
//   tr taubar = 2 c10 I1bar + 4 c01 I2bar,
//   cbar = 4 c01 (bbar (x) bbar - bbar (.) bbar).
// With X = dev sym G (|X| <= |G|):
//   X:cbar:X = 4 c01 ((X:dev bbar)^2 - |bbar^1/2 X bbar^1/2|^2)
//            <= 4 c01 (|dev bbar|^2 - beta_min^2) |X|^2,
//   (4/3)|tau_iso:G||tr G| <= (2/3)|tau_iso|_F (|G|^2 + (tr G)^2),
//   geometric tr(G tau_iso G^T)/J <= max(0, max eig tau_iso) |G|^2 / J.
// Exact at F = I: shear 2 mu = 4 (c10 + c01), bulk 0.
Material::TangentBound MooneyRivlin::tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2) const
{
    const double J = F.determinant();
    const Eigen::Array3d b = std::pow(J, -2.0 / 3.0) * lambda2.array();
    const double I1 = b.sum();
    const double I2 = b[0] * b[1] + b[1] * b[2] + b[2] * b[0];
    const Eigen::Array3d tau = 2.0 * c10_ * b + 2.0 * c01_ * (I1 * b - b.square());
    const Eigen::Array3d tauIso = tau - tau.sum() / 3.0;
    const Eigen::Array3d devB = b - I1 / 3.0;
    const double a = (2.0 / 3.0) * (2.0 * c10_ * I1 + 4.0 * c01_ * I2) +
                     4.0 * c01_ * (devB.square().sum() - b.minCoeff() * b.minCoeff());
    const double tauF = std::sqrt(tauIso.square().sum());
    TangentBound t;
    t.shear = (std::max(0.0, a) + (2.0 / 3.0) * tauF + std::max(0.0, tauIso.maxCoeff())) / J;
    t.bulk = (2.0 / 3.0) * tauF / J;
    return t;
}

// Volumetric part U = kappa/2 (J - 1)^2, p = U'(J) = kappa (J - 1):
// c/J = (p + J U'') I (x) I - 2 p II, geometric term p |G|^2:
//   Q = kappa (2J - 1)(tr G)^2 - 2 p |sym G|^2 + p |G|^2 <= |p| |G|^2 + kappa (2J - 1)(tr G)^2
Material::TangentBound MooneyRivlin::tangentBoundVolumetric(const Mat3& F, const Vec3&) const
{
    const double J = F.determinant();
    TangentBound t;
    t.shear = kappa_ * std::abs(J - 1.0);
    t.bulk = std::max(0.0, kappa_ * (2.0 * J - 1.0));
    return t;
}

NeoHookean::NeoHookean(double mu, double K, double rho) : MooneyRivlin(0.5 * mu, 0.0, K, rho)
{
}

// ---------------------------------------------------------------------------

StVenantKirchhoff::StVenantKirchhoff(double mu, double lambda, double rho)
    : Material(rho), mu_(mu), lambda_(lambda)
{
    requirePositive("StVenantKirchhoff", "mu", mu);
    requirePositive("StVenantKirchhoff", "lambda", lambda);
}

StVenantKirchhoff StVenantKirchhoff::fromYoung(double E, double nu, double rho)
{
    requirePositive("StVenantKirchhoff", "Young's modulus", E);
    if (!(nu > 0.0 && nu < 0.5)) {
        throw Error("StVenantKirchhoff: Poisson ratio must lie in (0, 0.5) (got " +
                    std::to_string(nu) + ")");
    }
    return StVenantKirchhoff(E / (2.0 * (1.0 + nu)), E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
                             rho);
}

double StVenantKirchhoff::energyDeviatoric(const Mat3& F) const
{
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    return mu_ * (E * E).trace();
}

double StVenantKirchhoff::energyVolumetric(const Mat3& F) const
{
    const double trE = 0.5 * ((F.transpose() * F).trace() - 3.0);
    return 0.5 * lambda_ * trE * trE;
}

Mat3 StVenantKirchhoff::stressDeviatoric(const Mat3& F) const
{
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    return F * (2.0 * mu_ * E);
}

// St Venant-Kirchhoff: c = lambda b (x) b + 2 mu b (.) b (push-forward of
// the constant material tensor), b = F F^T (eigenvalues beta_i = lambda2):
//   2 mu G:(b (.) b):G <= 2 mu beta_max^2 |G|^2,
//   lambda (b:G)^2 = lambda (tr G + (b - I):G)^2
//                  <= lambda ((1 + e)(tr G)^2 + (e + e^2)|G|^2),  e = |b - I|_F;
// geometric terms with tau = F S F^T: mu beta_i (beta_i - 1) (mu part),
// lambda tr(E) beta_i (lambda part). Exact at F = I (2 mu; lambda).
Material::TangentBound StVenantKirchhoff::tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2) const
{
    const double J = F.determinant();
    const Eigen::Array3d b = lambda2.array();
    TangentBound t;
    t.shear = (2.0 * mu_ * b.maxCoeff() * b.maxCoeff() +
               std::max(0.0, (mu_ * b * (b - 1.0)).maxCoeff())) / J;
    return t;
}

Material::TangentBound StVenantKirchhoff::tangentBoundVolumetric(const Mat3& F, const Vec3& lambda2) const
{
    const double J = F.determinant();
    const Eigen::Array3d b = lambda2.array();
    const double e = std::sqrt((b - 1.0).square().sum());
    const double trE = 0.5 * (b.sum() - 3.0);
    TangentBound t;
    t.shear = (lambda_ * (e + e * e) + std::max(0.0, (lambda_ * trE * b).maxCoeff())) / J;
    t.bulk = lambda_ * (1.0 + e) / J;
    return t;
}

Mat3 StVenantKirchhoff::stressVolumetric(const Mat3& F) const
{
    const double trE = 0.5 * ((F.transpose() * F).trace() - 3.0);
    return lambda_ * trE * F;
}

// ---------------------------------------------------------------------------

HolzapfelGasserOgden::HolzapfelGasserOgden(double c10, double c01, double k1, double k2,
                                           double kappa, double rho)
    : MooneyRivlin(c10, c01, kappa, rho), k1_(k1), k2_(k2)
{
    requirePositive("holzapfelGasserOgden", "k1", k1);
    requirePositive("holzapfelGasserOgden", "k2", k2);
}

namespace {

[[noreturn]] void needsDirection()
{
    throw Error("holzapfelGasserOgden: the fibre term needs the fibre direction a0 (use the "
                "overloads with a0; ExplicitSolid::setFibreDirections)");
}

}  // namespace

double HolzapfelGasserOgden::energyDeviatoric(const Mat3&) const { needsDirection(); }
Mat3 HolzapfelGasserOgden::stressDeviatoric(const Mat3&) const { needsDirection(); }

// The fibre term's exponent k2 (I4 - 1)^2 beyond which the motion is taken
// as blown up: the energy and the stress are then not finite (quiet NaN),
// which the solid reports (ExplicitSolid::internalForce), rather than an
// overflow that a trapping host (OpenFOAM's FOAM_SIGFPE) turns into a
// crash. exp(200) = 7e86 leaves the stress, its prefactors and the step
// bound's psi2 I4^2 far inside the double range; k2 (I4 - 1)^2 = 200 is a
// fibre stretch of 2.0 at k2 = 20 and of 4.0 at k2 = 0.84.
static constexpr double kMaxFibreExponent = 200.0;

double HolzapfelGasserOgden::energyDeviatoric(const Mat3& F, const Vec3& a0) const
{
    double W = MooneyRivlin::energyDeviatoric(F);
    const double E4 = (F * a0).squaredNorm() - 1.0;  // I4 - 1
    if (E4 > 0) {
        const double x = k2_ * E4 * E4;
        if (!(x < kMaxFibreExponent)) return std::numeric_limits<double>::quiet_NaN();
        W += 0.5 * k1_ / k2_ * std::expm1(x);
    }
    return W;
}

// P_fibre = 2 psi1 (F a0) (x) a0, psi1 = dW_f/dI4 = k1 (I4 - 1) exp(k2 (I4 - 1)^2)
Mat3 HolzapfelGasserOgden::stressDeviatoric(const Mat3& F, const Vec3& a0) const
{
    Mat3 P = MooneyRivlin::stressDeviatoric(F);
    const Vec3 a = F * a0;
    const double E4 = a.squaredNorm() - 1.0;
    if (E4 > 0) {
        const double x = k2_ * E4 * E4;
        if (!(x < kMaxFibreExponent)) {
            return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
        }
        P.noalias() += (2.0 * k1_ * E4 * std::exp(x)) * a * a0.transpose();
    }
    return P;
}

// The fibre term's share of Q(G) (Material.hpp): W_f = Psi(I4), I4 = |F a0|^2.
// Along dF = G F, with a = F a0 (|a|^2 = I4): dI4 = 2 a.(G a), d2I4 = 2 |G a|^2,
// so the full second variation (elastic and geometric terms together) is
//   Q_f(G) = (1/J) (4 psi2 (a.G a)^2 + 2 psi1 |G a|^2),
//   psi1 = Psi'  = k1 (I4 - 1) exp(k2 (I4 - 1)^2),
//   psi2 = Psi'' = k1 (1 + 2 k2 (I4 - 1)^2) exp(k2 (I4 - 1)^2)   (I4 > 1; 0 below).
// With |a.G a| <= |a|^2 |G|_2 <= I4 |G|_F and |G a|^2 <= I4 |G|_F^2:
//   Q_f(G) <= (1/J) (4 psi2 I4^2 + 2 psi1 I4) |G|_F^2   (a shear term only).
// psi1, psi2 and the bound grow with I4 on I4 >= 1, so the bound is taken
// at I4* = max(I4, 1): at I4 <= 1 the fibres are slack but a vibration about
// a state near I4 = 1 switches them on with psi2 -> k1 (the bound must hold
// for the stiffer side). Without a0, I4 = a0.C a0 <= lambda_max(C) gives a
// bound valid for every direction (tight when the fibres lie along the
// largest principal stretch, loose when the tissue is stretched across them).
// Even with a0 the |G|_F^2 form is loose on thin sheets: the fibres stiffen
// only the gradient along a, G a, never the through-thickness one. A tighter
// step bound would keep that as a third coefficient beside shear and bulk,
//   Q_f(G) <= (1/J) (4 psi2 I4 + 2 psi1) |G a|^2,
// and, in the notation of dynamics/StableStep.hpp (G_d = sum_I u_I (x) bt_dI,
// bt_dI = F^-T b_dI, so bt_dI . a = b_dI . a0),
//   |G_d a|^2 <= (a0 . N0_d a0) sum_I w_dI |u_I|^2,
// independent of the current shape of the domain: a per-domain fibre
// direction in StableStepBound: with a0 the bound below returns this third
// coefficient (TangentBound::fibre), without it the |G|_F^2 form.
Material::TangentBound HolzapfelGasserOgden::fibreBound(const Mat3& F, const Vec3& lambda2,
                                                        double I4, bool directional) const
{
    TangentBound t = MooneyRivlin::tangentBoundDeviatoric(F, lambda2);
    const double I4s = std::max(I4, 1.0), E4 = I4s - 1.0;
    // beyond kMaxFibreExponent the stress has stopped the solid already
    const double e = std::exp(std::min(k2_ * E4 * E4, kMaxFibreExponent));
    const double psi1 = k1_ * E4 * e, psi2 = k1_ * (1.0 + 2.0 * k2_ * E4 * E4) * e;
    if (directional) t.fibre = (4.0 * psi2 * I4s + 2.0 * psi1) / F.determinant();
    else t.shear += (4.0 * psi2 * I4s * I4s + 2.0 * psi1 * I4s) / F.determinant();
    return t;
}

Material::TangentBound HolzapfelGasserOgden::tangentBoundDeviatoric(const Mat3& F,
                                                                    const Vec3& lambda2) const
{
    return fibreBound(F, lambda2, lambda2.maxCoeff(), false);
}

Material::TangentBound HolzapfelGasserOgden::tangentBoundDeviatoric(const Mat3& F,
                                                                    const Vec3& lambda2,
                                                                    const Vec3& a0) const
{
    return fibreBound(F, lambda2, (F * a0).squaredNorm(), true);
}

}  // namespace smoothedSolid
