// Stresses against central finite differences of W, and objectivity
#include "material/Material.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <random>
#include <vector>

using namespace smoothedSolid;

namespace {

std::vector<std::shared_ptr<Material>> allMaterials()
{
    return {std::make_shared<MooneyRivlin>(1000.0, 200.0, 50000.0, 1000.0),
            std::make_shared<NeoHookean>(80.1938, 400942.0, 1.0),
            std::make_shared<StVenantKirchhoff>(0.5e6, 2.0e6, 1000.0)};
}

Mat3 randomF(std::mt19937& rng, double amplitude)
{
    std::uniform_real_distribution<double> d(-amplitude, amplitude);
    Mat3 F;
    do {
        F = Mat3::Identity();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) F(i, j) += d(rng);
    } while (F.determinant() < 0.3);
    return F;
}

// dW/dF by central differences, step relative to |F|
Mat3 finiteDifference(double (Material::*W)(const Mat3&) const, const Material& m,
                      const Mat3& F)
{
    const double h = 1e-6;
    Mat3 P;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            Mat3 Fp = F, Fm = F;
            Fp(i, j) += h;
            Fm(i, j) -= h;
            P(i, j) = ((m.*W)(Fp) - (m.*W)(Fm)) / (2 * h);
        }
    }
    return P;
}

}  // namespace

TEST(Material, StressIsDerivativeOfEnergy)
{
    std::mt19937 rng(42);
    const double tol = 1e-6;
    for (const auto& m : allMaterials()) {
        double worstDev = 0, worstVol = 0;
        for (int sample = 0; sample < 50; ++sample) {
            const Mat3 F = randomF(rng, 0.4);
            const Mat3 Pd = m->stressDeviatoric(F);
            const Mat3 Pv = m->stressVolumetric(F);
            const Mat3 Pd_fd = finiteDifference(&Material::energyDeviatoric, *m, F);
            const Mat3 Pv_fd = finiteDifference(&Material::energyVolumetric, *m, F);
            worstDev = std::max(worstDev, (Pd - Pd_fd).norm() / Pd_fd.norm());
            worstVol = std::max(worstVol, (Pv - Pv_fd).norm() / Pv_fd.norm());
        }
        std::printf("%-18s max relative |P - dW/dF|: deviatoric %.2e, volumetric %.2e "
                    "(tolerance %.0e)\n",
                    m->name().c_str(), worstDev, worstVol, tol);
        EXPECT_LT(worstDev, tol) << m->name();
        EXPECT_LT(worstVol, tol) << m->name();
    }
}

TEST(Material, ZeroStressInRigidRotation)
{
    const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (const auto& m : allMaterials()) {
        const double scale = m->shearModulus();
        const double P = m->firstPK(R).norm() / scale;
        const double W = std::abs(m->energy(R)) / scale;
        std::printf("%-18s rotation 0.7 rad: |P|/mu = %.2e, |W|/mu = %.2e (tolerance 1e-12)\n",
                    m->name().c_str(), P, W);
        EXPECT_LT(P, 1e-12);
        EXPECT_LT(W, 1e-12);
    }
}

TEST(Material, SmallStrainModuli)
{
    // Simple shear gamma: sigma_12 = mu gamma; volumetric strain e: p = K e
    const double g = 1e-7;
    for (const auto& m : allMaterials()) {
        Mat3 F = Mat3::Identity();
        F(0, 1) = g;
        const double mu = m->cauchy(F)(0, 1) / g;
        const Mat3 Fv = (1.0 + g / 3.0) * Mat3::Identity();
        const double K = m->cauchy(Fv).trace() / 3.0 / g;
        std::printf("%-18s mu %.6g (model %.6g), K %.6g (model %.6g)\n", m->name().c_str(), mu,
                    m->shearModulus(), K, m->bulkModulus());
        EXPECT_NEAR(mu / m->shearModulus(), 1.0, 1e-5);
        EXPECT_NEAR(K / m->bulkModulus(), 1.0, 1e-5);
    }
}
