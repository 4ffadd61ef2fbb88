// Contact: a cube dropped on a rigid plane
#include "dynamics/ExplicitSolid.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <numeric>

using namespace smoothedSolid;

namespace {

double minHeight(const TetMesh& m)
{
    double h = 1e300;
    for (int e = 0; e < m.nElements(); ++e) h = std::min(h, m.elementHeight(e));
    return h;
}

}  // namespace

TEST(Contact, CubeDroppedOnRigidPlane)
{
    // 0.1 m cube, 1 cm above the plane y = 0, falling at 1 m/s under gravity
    TetMesh mesh = TetMesh::box(4, 4, 4, [](const Vec3& s) {
        return Vec3(0.1 * s.x(), 0.01 + 0.1 * s.y(), 0.1 * s.z());
    });
    const double h = minHeight(mesh);
    const double mu = 1e5, K = 5e5, rho = 1000;
    ExplicitSolid solid(std::move(mesh), std::make_shared<NeoHookean>(mu, K, rho),
                        {Formulation::Selective, 0.8, 0.0});
    const double dtFree = solid.stableTimeStep();
    const Vec3 g(0, -9.81, 0);
    solid.setBodyForce(g);
    solid.setInitialVelocity([](double, const Vec3&) { return Vec3(0, -1.0, 0); });
    solid.addRigidSurface({{Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(-1, 0, 1)},
                           {{0, 2, 1}, {0, 3, 2}}});
    const double dt = solid.stableTimeStep();
    EXPECT_LT(dt, dtFree);  // the penalty springs are counted

    // Total energy at full steps, in the form the central difference
    // conserves exactly for a linear system (the leapfrog's modified
    // energy): (1/2) v^{n-1/2}.M v^{n+1/2} + W(u^n) - m g.u^n. The kinetic
    // energy of the mean velocity (v^{n-1/2} + v^{n+1/2})/2 would instead
    // misread the energy of modes excited by the impact by up to
    // (omega dt)^2/4.
    const auto& m = solid.lumpedMass();
    auto energy = [&](const std::vector<Vec3>& vPrev, const std::vector<Vec3>& vNext,
                      const std::vector<Vec3>& u) {
        double E = solid.strainEnergy(u);
        for (std::size_t i = 0; i < m.size(); ++i) {
            E += 0.5 * m[i] * vPrev[i].dot(vNext[i]) - m[i] * g.dot(u[i]);
        }
        return E;
    };
    const double E0 = 0.5 * 1.0 * std::accumulate(m.begin(), m.end(), 0.0);
    double maxPen = 0, Emax = E0, minVy = 0, maxVy = -1e9;
    while (solid.time() < 0.06) {
        const std::vector<Vec3> vPrev = solid.velocity();
        const std::vector<Vec3> uN = solid.displacement();
        solid.step(dt);
        maxPen = std::max(maxPen, solid.maxPenetration());
        // energy while free of contact (the penalty springs hold energy)
        if (solid.maxPenetration() == 0) Emax = std::max(Emax, energy(vPrev, solid.velocity(), uN));
        double vy = 0, M = 0;
        for (std::size_t i = 0; i < m.size(); ++i) {
            vy += m[i] * solid.velocity()[i].y();
            M += m[i];
        }
        minVy = std::min(minVy, vy / M);
        maxVy = std::max(maxVy, vy / M);
    }
    std::printf("cube on rigid plane: dt %.3e s (%.2f of the contact-free step), "
                "centre-of-mass v_y from %.3f to %.3f m/s\n",
                dt, dt / dtFree, minVy, maxVy);
    std::printf("  max penetration %.3e m = %.2f %% of the smallest element height "
                "(tolerance 5 %%)\n",
                maxPen, 100 * maxPen / h);
    std::printf("  max total energy / initial = %.5f (no gain: tolerance 1.005)\n", Emax / E0);
    EXPECT_GT(maxVy, 0.5);  // it bounced
    EXPECT_LT(maxPen, 0.05 * h);
    EXPECT_LT(Emax / E0, 1.005);
}
