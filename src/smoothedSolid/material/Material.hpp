// Hyperelastic materials behind one small interface: strain energy density
// W(F) and first Piola-Kirchhoff stress P = dW/dF, each split into a
// deviatoric (shear) part and a volumetric (bulk) part so that the selective
// FS/NS-FEM can integrate them on different smoothing domains (Sect. 3.2).
//
// Stresses are derived from W (not copied from the paper's Eq. 30, which has
// misprints; Eq. 26 should read I2 = ((tr C)^2 - tr(C^2))/2); the tests check
// them against central finite differences of W.
#pragma once

#include "Types.hpp"

#include <memory>
#include <string>

namespace smoothedSolid {

class Material {
public:
    virtual ~Material() = default;

    virtual std::string name() const = 0;
    double density() const { return rho_; }

    virtual double energyDeviatoric(const Mat3& F) const = 0;
    virtual double energyVolumetric(const Mat3& F) const = 0;
    virtual Mat3 stressDeviatoric(const Mat3& F) const = 0;  // first PK
    virtual Mat3 stressVolumetric(const Mat3& F) const = 0;  // first PK

    double energy(const Mat3& F) const { return energyDeviatoric(F) + energyVolumetric(F); }
    Mat3 firstPK(const Mat3& F) const { return stressDeviatoric(F) + stressVolumetric(F); }
    // Cauchy stress sigma = P F^T / J
    Mat3 cauchy(const Mat3& F) const { return firstPK(F) * F.transpose() / F.determinant(); }

    // Small-strain moduli: shear mu, bulk K; the wave modulus K + 4 mu/3
    // sets the dilatational wave speed of the stable time step
    virtual double shearModulus() const = 0;
    virtual double bulkModulus() const = 0;
    double waveModulus() const { return bulkModulus() + 4.0 * shearModulus() / 3.0; }

    // Bounds for the stable time step (dynamics/StableStep.hpp). With the
    // spatial gradient G = grad_x du, dF = G F, the second variation of W
    // per unit current volume is
    //   Q(G) = (1/J) dF : d2W/dFdF : dF = G : (c/J) : G + tr(G sigma G^T)
    // (spatial elasticity c of the Kirchhoff stress plus the geometric
    // stress term; Holzapfel, Nonlinear Solid Mechanics, 2000, Sect. 6.6).
    // A bound gives shear and bulk coefficients with
    //   Q(G) <= shear |G|_F^2 + bulk (tr G)^2   for every G.
    // At F = I an isotropic material gives shear = 2 mu, bulk = K - 2 mu/3
    // (the deviatoric part: 2 mu, 0; the volumetric part: 0, K).
    // lambda2: the eigenvalues of C = F^T F, ascending (computed by the caller).
    struct TangentBound {
        double shear = 0, bulk = 0;
    };
    virtual TangentBound tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2) const = 0;
    virtual TangentBound tangentBoundVolumetric(const Mat3& F, const Vec3& lambda2) const = 0;

protected:
    explicit Material(double rho);
    double rho_;
};

// Mooney-Rivlin, paper Eq. 24:
//   W = c10 (I1bar - 3) + c01 (I2bar - 3) + kappa/2 (J - 1)^2,
//   I1bar = I1 J^(-2/3), I2bar = I2 J^(-4/3) (Eq. 25 with J = I3^(1/2)).
// kappa given, or from Eq. 27: kappa = 2 (c10 + c01)/(1 - 2 nu).
class MooneyRivlin : public Material {
public:
    MooneyRivlin(double c10, double c01, double kappa, double rho);
    static double kappaFromPoisson(double c10, double c01, double nu);

    std::string name() const override { return "MooneyRivlin"; }
    double energyDeviatoric(const Mat3& F) const override;
    double energyVolumetric(const Mat3& F) const override;
    Mat3 stressDeviatoric(const Mat3& F) const override;
    Mat3 stressVolumetric(const Mat3& F) const override;
    double shearModulus() const override { return 2.0 * (c10_ + c01_); }
    double bulkModulus() const override { return kappa_; }
    TangentBound tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2) const override;
    TangentBound tangentBoundVolumetric(const Mat3& F, const Vec3& lambda2) const override;

protected:
    double c10_, c01_, kappa_;
};

// Compressible neo-Hookean: W = mu/2 (I1bar - 3) + K/2 (J - 1)^2
// (the Mooney-Rivlin form with c10 = mu/2, c01 = 0)
class NeoHookean : public MooneyRivlin {
public:
    NeoHookean(double mu, double K, double rho);
    std::string name() const override { return "neoHookean"; }
};

// St Venant-Kirchhoff: W = lambda/2 (tr E)^2 + mu tr(E^2), E = (C - I)/2.
// "Deviatoric" part: the mu term; "volumetric" part: the lambda term.
class StVenantKirchhoff : public Material {
public:
    StVenantKirchhoff(double mu, double lambda, double rho);
    static StVenantKirchhoff fromYoung(double E, double nu, double rho);

    std::string name() const override { return "StVenantKirchhoff"; }
    double energyDeviatoric(const Mat3& F) const override;
    double energyVolumetric(const Mat3& F) const override;
    Mat3 stressDeviatoric(const Mat3& F) const override;
    Mat3 stressVolumetric(const Mat3& F) const override;
    double shearModulus() const override { return mu_; }
    double bulkModulus() const override { return lambda_ + 2.0 * mu_ / 3.0; }
    TangentBound tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2) const override;
    TangentBound tangentBoundVolumetric(const Mat3& F, const Vec3& lambda2) const override;

private:
    double mu_, lambda_;
};

}  // namespace smoothedSolid
