// VTU output and exact restart
#include "dynamics/ExplicitSolid.hpp"
#include "io/VtuWriter.hpp"
#include "testMeshes.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

using namespace smoothedSolid;

namespace {

ExplicitSolid smallBeam()
{
    TetMesh mesh = TetMesh::box(6, 2, 2, [](const Vec3& x) {
        return Vec3(0.6 * x.x(), 0.1 * x.y(), 0.1 * x.z());
    });
    ExplicitSolid solid(std::move(mesh), std::make_shared<MooneyRivlin>(1000, 200, 50000, 1000),
                        {Formulation::Selective, 0.8, 0.0});
    solid.fix("xmin");
    solid.setBodyForce(Vec3(0, -9.81, 0));
    solid.addFollowerPressure("ymax", [](double t) { return 50.0 * t; });
    return solid;
}

}  // namespace

// Save at step 50, load into a fresh solid, continue: bitwise the same as
// the uninterrupted run
TEST(Output, RestartIsExact)
{
    ExplicitSolid a = smallBeam();
    const double dt = a.stableTimeStep();
    for (int k = 0; k < 50; ++k) a.step(dt);
    const std::string state = test::tempDir() + "/beam.state";
    a.saveState(state);
    for (int k = 0; k < 50; ++k) a.step(dt);

    ExplicitSolid b = smallBeam();
    b.loadState(state);
    EXPECT_EQ(b.steps(), 50);
    for (int k = 0; k < 50; ++k) b.step(dt);
    double diff = 0, scale = 0;
    for (int i = 0; i < a.mesh().nNodes(); ++i) {
        diff = std::max(diff, (a.displacement()[i] - b.displacement()[i]).norm());
        diff = std::max(diff, (a.velocity()[i] - b.velocity()[i]).norm());
        scale = std::max(scale, a.displacement()[i].norm());
    }
    std::printf("restart after 50 of 100 steps: max difference %.3e (max |u| %.3e); "
                "expected exactly 0\n",
                diff, scale);
    EXPECT_GT(scale, 0.0);
    EXPECT_EQ(diff, 0.0);
    EXPECT_EQ(a.time(), b.time());

    ExplicitSolid other(TetMesh::box(2, 2, 2, [](const Vec3& x) { return x; }),
                        std::make_shared<NeoHookean>(1, 10, 1));
    EXPECT_THROW(other.loadState(state), Error);
}

TEST(Output, VtuSeriesWritesFieldsAndCollection)
{
    ExplicitSolid solid = smallBeam();
    const std::string dir = test::tempDir() + "/vtu";
    VtuSeries series(dir, "beam");
    series.write(solid);
    solid.advance(20 * solid.stableTimeStep());
    std::vector<double> cp(solid.mesh().nNodes(), 1.5);
    series.write(solid, {{"contactPressure", cp}});

    std::ifstream pvd(dir + "/beam.pvd");
    std::stringstream ps;
    ps << pvd.rdbuf();
    EXPECT_NE(ps.str().find("beam_000001.vtu"), std::string::npos);

    std::ifstream vtu(dir + "/beam_000001.vtu");
    std::stringstream vs;
    vs << vtu.rdbuf();
    for (const char* name : {"displacement", "velocity", "externalForce", "contactPressure",
                             "cauchyStress", "vonMises", "maxPrincipalStress", "\"J\"",
                             "format=\"binary\""}) {
        EXPECT_NE(vs.str().find(name), std::string::npos) << name;
    }
    std::printf("wrote %s/beam.pvd with %d binary .vtu files\n", dir.c_str(), series.count());
}
