#include "material/Material.hpp"

#include <cmath>

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

Mat3 StVenantKirchhoff::stressVolumetric(const Mat3& F) const
{
    const double trE = 0.5 * ((F.transpose() * F).trace() - 3.0);
    return lambda_ * trE * F;
}

}  // namespace smoothedSolid
