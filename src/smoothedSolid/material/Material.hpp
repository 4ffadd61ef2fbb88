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
    // A fibre-reinforced material given its direction a0 adds a third
    // term, fibre |G a|^2 with a = F a0 the current fibre (it stiffens only
    // the gradient along the fibre; see HolzapfelGasserOgden).
    struct TangentBound {
        double shear = 0, bulk = 0, fibre = 0;
    };
    virtual TangentBound tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2) const = 0;
    virtual TangentBound tangentBoundVolumetric(const Mat3& F, const Vec3& lambda2) const = 0;

    // --- Fibre-reinforced (anisotropic) materials ------------------------
    // The deviatoric part of such a material also depends on a unit fibre
    // direction a0 in the reference configuration. The solver keeps one per
    // smoothing domain (ExplicitSolid::setFibreDirections) and calls the
    // overloads below only when hasFibres(); isotropic materials keep their
    // F-only path (these defaults forward to it and ignore a0). The F-only
    // energy and stress of a fibre material throw (no direction); its F-only
    // tangent bound holds for every direction a0.
    virtual bool hasFibres() const { return false; }
    virtual double energyDeviatoric(const Mat3& F, const Vec3& /*a0*/) const
    {
        return energyDeviatoric(F);
    }
    virtual Mat3 stressDeviatoric(const Mat3& F, const Vec3& /*a0*/) const
    {
        return stressDeviatoric(F);
    }
    // A bound for the direction a0 (tighter than the F-only one)
    virtual TangentBound tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2,
                                                const Vec3& /*a0*/) const
    {
        return tangentBoundDeviatoric(F, lambda2);
    }
    double energy(const Mat3& F, const Vec3& a0) const
    {
        return energyDeviatoric(F, a0) + energyVolumetric(F);
    }
    Mat3 firstPK(const Mat3& F, const Vec3& a0) const
    {
        return stressDeviatoric(F, a0) + stressVolumetric(F);
    }
    Mat3 cauchy(const Mat3& F, const Vec3& a0) const
    {
        return firstPK(F, a0) * F.transpose() / F.determinant();
    }

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
    using Material::energyDeviatoric;
    using Material::stressDeviatoric;
    using Material::tangentBoundDeviatoric;

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
    using Material::energyDeviatoric;
    using Material::stressDeviatoric;
    using Material::tangentBoundDeviatoric;

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

// Fibre-reinforced soft tissue of the Holzapfel-Gasser-Ogden kind (the
// exponential fibre term of Holzapfel, Gasser & Ogden, J Elasticity 61:1-48,
// 2000, with one fibre family and no dispersion): an isochoric
// Mooney-Rivlin matrix, one exponential fibre family and the volumetric
// penalty of MooneyRivlin,
//   W = c10 (I1bar - 3) + c01 (I2bar - 3)
//       + k1/(2 k2) (exp(k2 (I4 - 1)^2) - 1)   [only while I4 > 1]
//       + kappa/2 (J - 1)^2,
//   I4 = a0 . C a0 = |F a0|^2 (squared fibre stretch), a0 the unit fibre
//   direction in the reference configuration.
// Fibres bear tension only: the fibre term is off while I4 <= 1 (Holzapfel
// et al. 2000). The fibre term uses the full I4, not I4bar = J^(-2/3) I4:
// with a penalty on J (nearly, not exactly, incompressible) the split form
// gives a non-physical volumetric response (a fibre-reinforced sphere under
// hydrostatic pressure stays a sphere, as if it had no fibres; Sansour, Eur J
// Mech A/Solids 27:28-39, 2008; Helfenstein, Jabareen, Mazza & Govindjee, Int
// J Solids Struct 47:2056-2061, 2010), so the anisotropic part is taken in the
// full I4. It is carried by the deviatoric part, evaluated on the face-based
// domains of the selective FS/NS-FEM like the matrix (it is not purely
// isochoric, but it is no bulk term: the node-based domains, whose softness
// cures volumetric locking, carry the penalty only).
// Stress (dI4/dF = 2 F a0 (x) a0):
//   P_fibre = 2 psi1 (F a0) (x) a0,  psi1 = k1 (I4 - 1) exp(k2 (I4 - 1)^2).
// Small-strain moduli: those of the matrix (the fibres are slack at F = I).
// Parameters for aortic leaflet tissue: docs/references.md.
class HolzapfelGasserOgden : public MooneyRivlin {
public:
    HolzapfelGasserOgden(double c10, double c01, double k1, double k2, double kappa, double rho);
    using MooneyRivlin::energyDeviatoric;
    using MooneyRivlin::stressDeviatoric;
    using MooneyRivlin::tangentBoundDeviatoric;

    std::string name() const override { return "holzapfelGasserOgden"; }
    bool hasFibres() const override { return true; }
    double k1() const { return k1_; }
    double k2() const { return k2_; }
    // Without a direction: throw (the fibre term needs a0)
    double energyDeviatoric(const Mat3& F) const override;
    Mat3 stressDeviatoric(const Mat3& F) const override;
    double energyDeviatoric(const Mat3& F, const Vec3& a0) const override;
    Mat3 stressDeviatoric(const Mat3& F, const Vec3& a0) const override;
    // The matrix-only part (the fibres removed), e.g. for comparisons
    double matrixEnergyDeviatoric(const Mat3& F) const { return MooneyRivlin::energyDeviatoric(F); }
    Mat3 matrixStressDeviatoric(const Mat3& F) const { return MooneyRivlin::stressDeviatoric(F); }
    // Bounds: the matrix bound plus the fibre term's; for the direction a0
    // as TangentBound::fibre (of |G F a0|^2), or (F only) in the shear
    // coefficient for the worst direction, I4 <= lambda_max(C)
    TangentBound tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2) const override;
    TangentBound tangentBoundDeviatoric(const Mat3& F, const Vec3& lambda2,
                                        const Vec3& a0) const override;

private:
    TangentBound fibreBound(const Mat3& F, const Vec3& lambda2, double I4, bool directional) const;
    double k1_, k2_;
};

}  // namespace smoothedSolid
