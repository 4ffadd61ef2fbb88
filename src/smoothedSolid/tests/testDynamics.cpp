// Explicit dynamics: energy conservation, stable time step, sub-cycling
#include "Parallel.hpp"
#include "dynamics/ExplicitSolid.hpp"
#include "testMeshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace smoothedSolid;

namespace {

// Cantilever 1 x 0.1 x 0.1 m, 20 x 2 x 2 hexahedra split into tets, clamped
// at x = 0; neo-Hookean mu = 1e5 Pa, nu = 0.3, rho = 1000 kg/m3
ExplicitSolid cantilever(Formulation form)
{
    const double mu = 1e5, nu = 0.3;
    const double K = 2 * mu * (1 + nu) / (3 * (1 - 2 * nu));
    TetMesh mesh = TetMesh::box(20, 2, 2, [](const Vec3& x) {
        return Vec3(1.0 * x.x(), 0.1 * x.y(), 0.1 * x.z());
    });
    ExplicitSolid solid(std::move(mesh), std::make_shared<NeoHookean>(mu, K, 1000.0),
                        {form, 0.8, 0.0});
    solid.fix("xmin");
    return solid;
}

}  // namespace

// Undamped free vibration from an initial bending velocity: the total energy
// K(v^n) + W(u^n), v^n = (v^{n-1/2} + v^{n+1/2})/2, stays within 0.5% over
// ten periods of the first bending mode
TEST(Dynamics, CantileverEnergyConservedOverTenPeriods)
{
    ExplicitSolid solid = cantilever(Formulation::Selective);
    solid.setInitialVelocity([](double, const Vec3& X) {
        return Vec3(0, 0.05 * X.x() * X.x(), 0);
    });

    // Euler-Bernoulli first bending period (an upper bound for the stiffer
    // discrete beam): T1 = 2 pi L^2 sqrt(rho A/(E I))/1.875^2
    const double mu = 1e5, E = 2 * mu * 1.3;
    const double T1 = 2 * M_PI * std::sqrt(1000.0 * 12.0 / (E * 0.01)) / (1.875 * 1.875);
    const double tEnd = 10 * T1;
    const double dt = solid.stableTimeStep();

    const auto& m = solid.lumpedMass();
    auto energyAt = [&](const std::vector<Vec3>& vPrev, const std::vector<Vec3>& vNext,
                        const std::vector<Vec3>& u) {
        double K = 0;
        for (std::size_t i = 0; i < m.size(); ++i) {
            K += 0.5 * m[i] * (0.5 * (vPrev[i] + vNext[i])).squaredNorm();
        }
        return K + solid.strainEnergy(u);
    };

    const double E0 = solid.kineticEnergy();
    double worst = 0, tipMin = 0, tipMax = 0;
    int crossings = 0;
    double lastTip = 0;
    long n = 0;
    // tip node: (1, 0.05, 0.05)
    int tip = 0;
    for (int i = 0; i < solid.mesh().nNodes(); ++i) {
        if ((solid.mesh().coordinates()[i] - Vec3(1, 0.05, 0.05)).norm() < 1e-9) tip = i;
    }
    while (solid.time() < tEnd) {
        const std::vector<Vec3> vPrev = solid.velocity();
        const std::vector<Vec3> uN = solid.displacement();
        solid.step(dt);
        if (n++ % 20 == 0 && n > 1) {
            const double En = energyAt(vPrev, solid.velocity(), uN);
            worst = std::max(worst, std::abs(En - E0) / E0);
        }
        const double y = solid.displacement()[tip].y();
        if ((y > 0) != (lastTip > 0) && n > 1) ++crossings;
        lastTip = y;
        tipMin = std::min(tipMin, y);
        tipMax = std::max(tipMax, y);
    }
    std::printf("cantilever: %ld steps of %.3e s to t = %.2f s (%.1f beam periods; %d zero "
                "crossings of the tip), tip y in [%.4f, %.4f] m\n",
                n, dt, solid.time(), tEnd / T1, crossings, tipMin, tipMax);
    std::printf("max |E - E0|/E0 = %.3e (tolerance 5e-3)\n", worst);
    EXPECT_GE(crossings, 20);  // at least ten periods really happened
    EXPECT_LT(worst, 5e-3);
}

// The threaded internal force is in gather form (each entry summed by one
// thread in a fixed order): the result must not depend on the thread count,
// bitwise. The build states whether the library must be threaded
// (SMOOTHEDSOLID_EXPECT_OPENMP from CMake), so a library silently built
// without OpenMP cannot pass by comparing one thread with one thread.
TEST(Dynamics, InternalForceIndependentOfThreadCount)
{
#if SMOOTHEDSOLID_EXPECT_OPENMP
    const bool threaded = true;
    std::printf("built with SMOOTHEDSOLID_OPENMP=ON: builtWithOpenMP() = %s (expected true)\n",
                builtWithOpenMP() ? "true" : "false");
    ASSERT_TRUE(builtWithOpenMP()) << "SMOOTHEDSOLID_OPENMP is ON but the library has no OpenMP";
#else
    const bool threaded = false;
    std::printf("built with SMOOTHEDSOLID_OPENMP=OFF: this build is single-threaded, only the "
                "1-thread internal force is checked; builtWithOpenMP() = %s (expected false)\n",
                builtWithOpenMP() ? "true" : "false");
    ASSERT_FALSE(builtWithOpenMP());
#endif
    const int threads = numThreads();
    const TetMesh mesh = TetMesh::fromGmsh(test::boxMsh("threads", 1.0, 0.5, 0.4, 0.12));
    std::vector<Vec3> u(mesh.nNodes());
    for (int i = 0; i < mesh.nNodes(); ++i) {
        const Vec3& X = mesh.coordinates()[i];
        u[i] = 0.05 * Vec3(std::sin(3 * X.y()), X.x() * X.z(), std::cos(2 * X.x()) - 1);
    }
    double worst = 0, size = 0;
    int threadsUsed = 0;
    for (Formulation form : {Formulation::FEM_T4, Formulation::NS_FEM, Formulation::FS_FEM,
                             Formulation::Selective}) {
        ExplicitSolid solid(mesh, std::make_shared<MooneyRivlin>(1000.0, 200.0, 5e4, 1000.0),
                            {form, 0.8, 0.0});
        setNumThreads(1);
        EXPECT_EQ(numThreads(), 1);
        const std::vector<Vec3> f1 = solid.internalForce(u);
        for (const Vec3& f : f1) size = std::max(size, f.norm());
        if (!threaded) continue;
        // overrides OMP_NUM_THREADS=1, which ctest sets
        setNumThreads(2);
        threadsUsed = numThreads();
        EXPECT_EQ(threadsUsed, 2);
        const std::vector<Vec3> f2 = solid.internalForce(u);
        for (int i = 0; i < mesh.nNodes(); ++i) worst = std::max(worst, (f1[i] - f2[i]).norm());
    }
    setNumThreads(threads);
    EXPECT_GT(size, 0.0);
    if (threaded) {
        std::printf("internal force on 1 and %d threads, %d nodes, 4 formulations: largest "
                    "difference %.3e (max |f| %.3e; must be 0)\n",
                    threadsUsed, mesh.nNodes(), worst, size);
    } else {
        std::printf("internal force on 1 thread, %d nodes, 4 formulations: max |f| %.3e "
                    "(single-threaded build, no 2-thread comparison)\n",
                    mesh.nNodes(), size);
    }
    EXPECT_EQ(worst, 0.0);
    EXPECT_THROW(setNumThreads(0), Error);
}

// Added mass (setAddedMass): a solid of density rho with added mass k m per
// node under an external tip force moves exactly as the same solid of
// density (1 + k) rho (internal forces do not depend on the density), step
// by step at the same dt; with damping, the damping force keeps the solid's
// own mass: c m v = (c/(1+k)) (1+k) m v
TEST(Dynamics, AddedMassEqualsHeavierSolid)
{
    const double mu = 1e5, nu = 0.3, k = 2.5, c = 4.0;
    const double K = 2 * mu * (1 + nu) / (3 * (1 - 2 * nu));
    auto make = [&](double rho, double damping) {
        TetMesh mesh = TetMesh::box(10, 2, 2, [](const Vec3& x) {
            return Vec3(1.0 * x.x(), 0.1 * x.y(), 0.1 * x.z());
        });
        ExplicitSolid s(std::move(mesh), std::make_shared<NeoHookean>(mu, K, rho),
                        {Formulation::Selective, 0.8, damping});
        s.fix("xmin");
        return s;
    };
    ExplicitSolid light = make(1000.0, c), heavy = make(1000.0 * (1 + k), c / (1 + k));
    std::vector<double> ma(light.lumpedMass());
    for (double& m : ma) m *= k;
    light.setAddedMass(ma);
    for (std::size_t i = 0; i < light.externalForce().size(); ++i) {
        const double x = light.mesh().coordinates()[i].x();
        light.externalForce()[i] = heavy.externalForce()[i] = Vec3(0, 10.0 * x, 0);
    }
    const double dt = light.stableTimeStep();
    double worst = 0, scale = 0;
    for (int n = 0; n < 400; ++n) {
        light.step(dt);
        heavy.step(dt);
        for (std::size_t i = 0; i < ma.size(); ++i) {
            worst = std::max(worst, (light.displacement()[i] - heavy.displacement()[i]).norm());
            scale = std::max(scale, heavy.displacement()[i].norm());
        }
    }
    std::printf("added mass vs heavier solid: largest difference %.3g of largest displacement %.3g\n",
                worst, scale);
    EXPECT_GT(scale, 1e-4);
    EXPECT_LT(worst, 1e-10 * scale);

    // Negative control: without the added mass the light solid moves faster
    ExplicitSolid bare = make(1000.0, c);
    bare.externalForce() = heavy.externalForce();
    ExplicitSolid heavy2 = make(1000.0 * (1 + k), c / (1 + k));
    heavy2.externalForce() = heavy.externalForce();
    double diff = 0;
    for (int n = 0; n < 400; ++n) {
        bare.step(dt);
        heavy2.step(dt);
    }
    for (std::size_t i = 0; i < ma.size(); ++i) {
        diff = std::max(diff, (bare.displacement()[i] - heavy2.displacement()[i]).norm());
    }
    EXPECT_GT(diff, 0.1 * scale);

    EXPECT_THROW(light.setAddedMass(std::vector<double>(3, 1.0)), Error);
}

// correctVelocity: free components move by dv (velocity) and dt*dv
// (displacement); fixed ones stay; a wrong size throws
TEST(Dynamics, CorrectVelocityKeepsConstraints)
{
    TetMesh mesh = TetMesh::box(4, 1, 1, [](const Vec3& x) { return x; });
    ExplicitSolid s(std::move(mesh), std::make_shared<NeoHookean>(1e5, 1e6, 1000.0),
                    {Formulation::Selective, 0.8, 0.0});
    s.fix("xmin");
    const std::vector<Vec3> free = s.freeComponents();
    const int nn = s.mesh().nNodes();
    std::vector<Vec3> dv(nn, Vec3(0.5, -1.0, 2.0));
    const std::vector<Vec3> u0 = s.displacement(), v0 = s.velocity();
    s.correctVelocity(dv, 0.1);
    int nFixed = 0, nFree = 0;
    for (int i = 0; i < nn; ++i) {
        const bool fixed = s.mesh().coordinates()[i].x() < 1e-12;
        EXPECT_EQ(free[i].sum(), fixed ? 0.0 : 3.0) << "node " << i;
        const Vec3 du = s.displacement()[i] - u0[i], dvi = s.velocity()[i] - v0[i];
        if (fixed) {
            ++nFixed;
            EXPECT_EQ(du.norm(), 0.0);
            EXPECT_EQ(dvi.norm(), 0.0);
        } else {
            ++nFree;
            EXPECT_NEAR((du - 0.1 * dv[i]).norm(), 0.0, 1e-15);
            EXPECT_NEAR((dvi - dv[i]).norm(), 0.0, 1e-15);
        }
    }
    EXPECT_GT(nFixed, 0);
    EXPECT_GT(nFree, 0);
    EXPECT_THROW(s.correctVelocity(std::vector<Vec3>(3), 0.1), Error);
}

// Stiffness-proportional (Rayleigh) damping beta K v: a mode of angular
// frequency omega decays with the damping ratio zeta = beta omega / 2
// (Chopra, Dynamics of Structures, Sect. 11.4). The clamped bar's first
// axial mode, excited by v_x = v0 sin(pi X / 2L): omega from its undamped
// period, zeta from the logarithmic decrement of the tip's axial
// displacement over the damped run, within 5 % of beta omega / 2. The
// stable step shrinks by sqrt(1 + z^2) - z, z = beta omega_max / 2.
// Negative control: without beta the same peaks decay by less than 0.5 %
// (with it, by 40 %).
TEST(Dynamics, StiffnessDampingRatio)
{
    const double mu = 1e5, nu = 0.3, L = 1.0;
    const double K = 2 * mu * (1 + nu) / (3 * (1 - 2 * nu));
    auto make = [&](double beta) {
        TetMesh mesh = TetMesh::box(20, 2, 2, [&](const Vec3& x) {
            return Vec3(L * x.x(), 0.1 * x.y(), 0.1 * x.z());
        });
        SolidOptions o{Formulation::Selective, 0.8, 0.0};
        o.stiffnessDamping = beta;
        ExplicitSolid s(std::move(mesh), std::make_shared<NeoHookean>(mu, K, 1000.0), o);
        s.fix("xmin");
        s.setInitialVelocity([&](double, const Vec3& X) {
            return Vec3(1e-4 * std::sin(0.5 * M_PI * X.x() / L), 0, 0);
        });
        return s;
    };
    auto tipOf = [&](const ExplicitSolid& s) {
        for (int i = 0; i < s.mesh().nNodes(); ++i) {
            if ((s.mesh().coordinates()[i] - Vec3(L, 0.05, 0.05)).norm() < 1e-9) return i;
        }
        return -1;
    };
    // maxima of the tip's u_x (parabola through the three samples around
    // each) over tEnd, at the solid's stable step
    auto peaks = [&](ExplicitSolid& s, double tEnd, std::vector<double>& t, std::vector<double>& a) {
        const int tip = tipOf(s);
        const double dt = s.stableTimeStep();
        double u0 = 0, u1 = 0;
        while (s.time() < tEnd) {
            s.step(dt);
            const double u2 = s.displacement()[tip].x();
            if (u1 > u0 && u1 >= u2 && u1 > 0) {
                const double d = u0 - 2 * u1 + u2;
                const double off = d != 0 ? 0.5 * (u0 - u2) / d : 0.0;
                t.push_back(s.time() - dt * (1 - off));
                a.push_back(u1 - 0.125 * (u0 - u2) * (u0 - u2) / d);
            }
            u0 = u1;
            u1 = u2;
        }
    };
    // bar's first axial mode: omega = (pi/2) sqrt(E/rho)/L about 25 rad/s
    ExplicitSolid bare = make(0.0);
    std::vector<double> t0, a0;
    peaks(bare, 1.2, t0, a0);
    ASSERT_GE(t0.size(), 4u);
    const double T = (t0.back() - t0.front()) / double(t0.size() - 1);
    const double omega = 2 * M_PI / T;
    const double decay0 = 1 - a0.back() / a0.front();

    const double zetaTarget = 0.02, beta = 2 * zetaTarget / omega;
    ExplicitSolid damped = make(beta);
    std::vector<double> t1, a1;
    peaks(damped, 1.2, t1, a1);
    ASSERT_GE(t1.size(), 4u);
    const double n = double(a1.size() - 1);
    const double delta = std::log(a1.front() / a1.back()) / n;
    const double zeta = delta / std::sqrt(4 * M_PI * M_PI + delta * delta);
    std::printf("axial mode: omega %.4f rad/s (bar theory %.4f), undamped peaks decay %.2e over "
                "%zu periods\n",
                omega, 0.5 * M_PI * std::sqrt(2 * mu * (1 + nu) / 1000.0) / L, decay0,
                t0.size() - 1);
    std::printf("beta %.4e s: damping ratio %.5f, beta omega / 2 = %.5f (tolerance 5 %%)\n", beta,
                zeta, 0.5 * beta * omega);
    EXPECT_NEAR(zeta, 0.5 * beta * omega, 0.05 * 0.5 * beta * omega);
    EXPECT_LT(decay0, 5e-3);

    // the stable step of the damped solid (the bare one's is 0.8 * 2 / omega_max)
    const double omegaMax = 2 * 0.8 / bare.stableTimeStep();
    const double z = 0.5 * beta * omegaMax;
    const double expected = bare.stableTimeStep() * (std::sqrt(1 + z * z) - z);
    std::printf("stable step %.5e s, expected %.5e s (z = %.3f at omega_max)\n",
                damped.stableTimeStep(), expected, z);
    EXPECT_NEAR(damped.stableTimeStep(), expected, 0.02 * expected);
    EXPECT_THROW(make(-1.0), Error);
}
