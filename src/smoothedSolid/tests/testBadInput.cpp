// Bad input: each a clear exception naming the problem
#include "dynamics/ExplicitSolid.hpp"
#include "io/SolidRun.hpp"
#include "testMeshes.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

using namespace smoothedSolid;

namespace {

// Run f, expect an Error whose message contains every fragment
template <class F>
void expectError(F f, std::initializer_list<const char*> fragments)
{
    try {
        f();
        ADD_FAILURE() << "no exception";
    } catch (const Error& e) {
        std::printf("error: %s\n", e.what());
        for (const char* s : fragments) {
            EXPECT_NE(std::string(e.what()).find(s), std::string::npos)
                << "message lacks '" << s << "'";
        }
    }
}

}  // namespace

TEST(BadInput, MissingFile)
{
    expectError([] { TetMesh::fromGmsh("/nonexistent/leaflet.msh"); },
                {"/nonexistent/leaflet.msh", "cannot open"});
}

TEST(BadInput, CorruptFile)
{
    const std::string path = test::tempDir() + "/corrupt.msh";
    std::ofstream(path) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 3\ngarbage\n";
    expectError([&] { TetMesh::fromGmsh(path); }, {"corrupt.msh"});
}

TEST(BadInput, MeshWithoutTets)
{
    const std::string path = test::surfaceOnlyMsh("noTets");
    expectError([&] { TetMesh::fromGmsh(path); }, {"noTets.msh", "no linear tetrahedra"});
}

TEST(BadInput, UnknownSetName)
{
    const TetMesh mesh = TetMesh::fromGmsh(test::boxMsh("sets", 1, 1, 1, 0.5));
    expectError([&] { mesh.nodeSet("clamped"); }, {"clamped", "xmin", "xmax", "solid"});
    ExplicitSolid solid(mesh, std::make_shared<NeoHookean>(1.0, 10.0, 1.0));
    expectError([&] { solid.fix("clamped"); }, {"clamped"});
    expectError([&] { solid.addFollowerPressure("top", [](double) { return 1.0; }); },
                {"top", "face set"});
}

TEST(BadInput, NonPositiveMaterialConstants)
{
    expectError([] { MooneyRivlin(-1000, 200, 5e4, 1000); }, {"c10", "positive"});
    expectError([] { MooneyRivlin(1000, 200, 0, 1000); }, {"kappa", "positive"});
    expectError([] { NeoHookean(80, 400, -1); }, {"density", "positive"});
    expectError([] { StVenantKirchhoff(0, 2e6, 1000); }, {"mu", "positive"});
    expectError([] { StVenantKirchhoff::fromYoung(1e6, 0.5, 1000); }, {"Poisson"});
    expectError([] { MooneyRivlin::kappaFromPoisson(1000, 200, 0.5); }, {"Poisson"});
}

TEST(BadInput, InvertedInitialElement)
{
    std::vector<Vec3> X = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                           Vec3(1, 1, 1)};
    // second element has negative orientation
    std::vector<Tet> tets = {{0, 1, 2, 3}, {1, 3, 2, 4}};
    expectError([&] { TetMesh(X, tets); }, {"element 1", "inverted"});
    std::vector<Tet> flat = {{0, 1, 2, 3}, {0, 1, 2, 2}};
    expectError([&] { TetMesh(X, flat); }, {"element 1", "zero volume"});
}

TEST(BadInput, CaseFileContactOptions)
{
    auto write = [](const std::string& name, const std::string& contact) {
        const std::string file = test::tempDir() + "/" + name + ".solid";
        std::ofstream os(file);
        os << "box 2 2 2 0 0 0 1 1 1\n"
              "material neoHookean mu 80 K 4e5 rho 1\n"
              "fix xmin\n"
           << contact
           << "\nendTime 1\nwriteInterval 0.5\n";
        return file;
    };
    expectError([&] { SolidRun run(write("contactWord", "contact self dampingRate 0.1")); },
                {"contactWord.solid:4", "contact", "dampingRate"});
    expectError([&] { SolidRun run(write("contactFraction", "contact stepFraction 1.5")); },
                {"contactFraction.solid", "contact", "stepFraction"});
    // the options are taken
    expectError([&] { SolidRun run(write("contactDepth", "contact depthFraction 3")); },
                {"contactDepth.solid", "contact", "depthFraction"});
    SolidRun ok(write("contactGood", "contact self dampingRatio 0 stepFraction 0.3 penaltyScale 3 "
                                     "depthFraction 1.5 facingCosine 0.4"));
    ASSERT_NE(ok.solid().contact(), nullptr);
    const ContactOptions& o = ok.solid().contact()->options();
    EXPECT_TRUE(o.selfContact);
    EXPECT_EQ(o.dampingRatio, 0.0);
    EXPECT_EQ(o.stepFraction, 0.3);
    EXPECT_EQ(o.penaltyScale, 3.0);
    EXPECT_EQ(o.depthFraction, 1.5);
    EXPECT_EQ(o.facingCosine, 0.4);
}

// advance() over an interval that would take more than kMaxSubSteps stable
// sub-steps (what a blown-up solid's collapsing stable step asks for) stops
// with an error naming the stable step and the time, the state unchanged
// (here a solid 1e16 times too stiff for the interval: about 1e9 sub-steps)
TEST(BadInput, AdvanceRefusesACollapsedStableStep)
{
    TetMesh mesh = TetMesh::box(2, 2, 2, [](const Vec3& x) { return x; });
    ExplicitSolid solid(std::move(mesh), std::make_shared<NeoHookean>(8e17, 4e18, 1.0));
    solid.fix("xmin");
    std::printf("stable step %.3e s, interval 1 s\n", solid.stableTimeStep());
    expectError([&] { solid.advance(1.0); }, {"stable step", "t = 0", "blown up"});
    EXPECT_EQ(solid.time(), 0.0);
    // an interval it can do is done
    EXPECT_GE(solid.advance(1e3 * solid.stableTimeStep()), 1000);
}
