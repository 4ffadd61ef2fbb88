// Exact restart with contact driven by advance(), state-file checks, and
// a state that stops being finite
#include "dynamics/ExplicitSolid.hpp"
#include "testMeshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>

using namespace smoothedSolid;

namespace {

// Two plates 40 x 40 x 10 mm, 6 mm apart, as one mesh of two parts; the
// lower one clamped at its bottom, the upper one pushed down by a pressure
TetMesh twoPlates()
{
    const TetMesh lower = TetMesh::box(5, 5, 2, [](const Vec3& x) { return Vec3(0.04 * x.x(), 0.04 * x.y(), 0.01 * x.z()); });
    const TetMesh upper = TetMesh::box(4, 4, 2, [](const Vec3& x) {
        return Vec3(0.005 + 0.03 * x.x(), 0.005 + 0.03 * x.y(), 0.016 + 0.01 * x.z());
    });
    std::vector<Vec3> X = lower.coordinates();
    std::vector<Tet> tets = lower.elements();
    const int off = lower.nNodes();
    X.insert(X.end(), upper.coordinates().begin(), upper.coordinates().end());
    for (Tet t : upper.elements()) {
        for (int& v : t) v += off;
        tets.push_back(t);
    }
    TetMesh mesh(std::move(X), std::move(tets));
    mesh.addNodeSet("bottom", lower.nodeSet("zmin"));
    std::vector<Tri> top;
    for (Tri t : upper.faceSet("zmax")) {
        for (int& v : t) v += off;
        top.push_back(t);
    }
    mesh.addFaceSet("top", top);
    return mesh;
}

std::unique_ptr<ExplicitSolid> plates()
{
    auto s = std::make_unique<ExplicitSolid>(twoPlates(), std::make_shared<NeoHookean>(3e5, 5e6, 1000.0),
                                             SolidOptions{Formulation::Selective, 0.9, 200.0});
    s->fix("bottom");
    s->addFollowerPressure("top", [](double t) { return 4e4 * std::min(1.0, t / 2e-3); });
    s->enableContact();
    return s;
}

const double kDt = 2e-4;  // the "fluid" step: many solid sub-steps each

bool bitwiseEqual(const std::vector<Vec3>& a, const std::vector<Vec3>& b)
{
    return a.size() == b.size() &&
           std::equal(a.begin(), a.end(), b.begin(), [](const Vec3& x, const Vec3& y) {
               return x.x() == y.x() && x.y() == y.y() && x.z() == y.z();
           });
}

}  // namespace

// 30 calls of advance(kDt); stopped after call k, saved, loaded into a new
// solid and continued: bitwise equal to the uninterrupted run
TEST(Restart, ContactAndAdvanceRestartIsBitwiseExact)
{
    auto ref = plates();
    std::vector<int> subSteps;
    std::vector<std::string> states;
    const std::vector<int> stops = {5, 12, 20, 27};
    long contactCalls = 0;
    for (int call = 1; call <= 30; ++call) {
        subSteps.push_back(ref->advance(kDt));
        if (ref->maxPenetration() > 0) ++contactCalls;
        if (std::find(stops.begin(), stops.end(), call) != stops.end()) {
            states.push_back(test::tempDir() + "/plates" + std::to_string(call) + ".state");
            ref->saveState(states.back());
        }
    }
    std::printf("uninterrupted: 30 calls of advance(%.1e s), sub-steps per call %d .. %d, %ld calls "
                "in contact, %ld candidate builds, t = %.6e s\n",
                kDt, *std::min_element(subSteps.begin(), subSteps.end()),
                *std::max_element(subSteps.begin(), subSteps.end()), contactCalls,
                ref->contact()->candidateBuilds(), ref->time());
    EXPECT_GT(contactCalls, 5);  // the restart really happens in contact
    for (std::size_t i = 0; i < stops.size(); ++i) {
        auto r = plates();
        r->loadState(states[i]);
        long steps = 0;
        bool sameSubSteps = true;
        for (int call = stops[i] + 1; call <= 30; ++call) {
            const int n = r->advance(kDt);
            sameSubSteps = sameSubSteps && n == subSteps[call - 1];
            steps += n;
        }
        const bool u = bitwiseEqual(r->displacement(), ref->displacement());
        const bool v = bitwiseEqual(r->velocity(), ref->velocity());
        double du = 0;
        for (int k = 0; k < r->mesh().nNodes(); ++k) {
            du = std::max(du, (r->displacement()[k] - ref->displacement()[k]).norm());
        }
        std::printf("restarted after call %2d: %ld sub-steps, same per call: %s; u bitwise equal: "
                    "%s, v bitwise equal: %s (largest |du| %.1e m), steps %ld vs %ld, t %.17g vs "
                    "%.17g\n",
                    stops[i], steps, sameSubSteps ? "yes" : "no", u ? "yes" : "no", v ? "yes" : "no",
                    du, r->steps(), ref->steps(), r->time(), ref->time());
        EXPECT_TRUE(sameSubSteps);
        EXPECT_TRUE(u);
        EXPECT_TRUE(v);
        EXPECT_EQ(r->steps(), ref->steps());
        EXPECT_EQ(r->time(), ref->time());
    }
}

TEST(Restart, TruncatedOrMismatchedStateThrows)
{
    auto a = plates();
    a->advance(kDt);
    const std::string file = test::tempDir() + "/good.state";
    a->saveState(file);
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Loading 'path' into 'b' must throw naming the file and 'fragment', and
    // load nothing
    auto expectError = [&](ExplicitSolid& b, const std::string& path, const std::string& words,
                           const std::string& fragment) {
        const std::vector<Vec3> before = b.displacement();
        try {
            b.loadState(path);
            ADD_FAILURE() << "no error for " << words;
        } catch (const Error& e) {
            std::printf("%-40s -> %s\n", words.c_str(), e.what());
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos);
            EXPECT_TRUE(bitwiseEqual(before, b.displacement()));
        }
    };
    for (std::size_t cut : {bytes.size() / 3, bytes.size() - 5}) {
        const std::string path = test::tempDir() + "/cut" + std::to_string(cut) + ".state";
        std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(cut));
        expectError(*plates(), path, "truncated to " + std::to_string(cut) + " bytes", "truncated");
    }
    const auto neoHookean = std::make_shared<NeoHookean>(3e5, 5e6, 1000.0);
    ExplicitSolid other(twoPlates(), std::make_shared<MooneyRivlin>(1e5, 1e4, 5e6, 1000.0));
    expectError(other, file, "another material", "material");
    ExplicitSolid fem(twoPlates(), neoHookean, {Formulation::FEM_T4, 0.9, 0.0});
    expectError(fem, file, "another formulation", "formulation");
    ExplicitSolid small(TetMesh::box(2, 2, 2, [](const Vec3& x) { return x; }), neoHookean);
    expectError(small, file, "another mesh", "nodes");
    const std::string junk = test::tempDir() + "/junk.state";
    std::ofstream(junk) << "not a state file";
    expectError(*plates(), junk, "not a state file", "not a smoothedSolid state file");
}

// A node whose force stops being finite stops the step, names time, step
// and node, and leaves the last good state in place
TEST(Restart, NonFiniteStateThrowsAndKeepsLastGoodState)
{
    auto s = plates();
    for (int k = 0; k < 5; ++k) s->step(s->stableTimeStep());
    const std::vector<Vec3> u = s->displacement();
    const double t = s->time();
    s->externalForce()[17] = Vec3(0, std::nan(""), 0);
    try {
        s->step(s->stableTimeStep());
        ADD_FAILURE() << "no error for a non-finite force";
    } catch (const Error& e) {
        std::printf("non-finite force -> %s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("node 17"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("step 5"), std::string::npos);
    }
    EXPECT_EQ(s->time(), t);
    EXPECT_TRUE(bitwiseEqual(u, s->displacement()));
}

TEST(Restart, ContactOptionsOutOfRangeThrowNamingTheOption)
{
    const std::pair<const char*, ContactOptions> cases[] = {
        {"stepFraction", [] { ContactOptions o; o.stepFraction = 1.0; return o; }()},
        {"penaltyScale", [] { ContactOptions o; o.penaltyScale = 0; return o; }()},
        {"depthFraction", [] { ContactOptions o; o.depthFraction = 2.5; return o; }()},
        {"facingCosine", [] { ContactOptions o; o.facingCosine = -0.1; return o; }()},
        {"dampingRatio", [] { ContactOptions o; o.dampingRatio = 2; return o; }()},
    };
    for (const auto& [name, o] : cases) {
        ExplicitSolid s(twoPlates(), std::make_shared<NeoHookean>(3e5, 5e6, 1000.0));
        try {
            s.enableContact(o);
            ADD_FAILURE() << "no error for " << name;
        } catch (const Error& e) {
            std::printf("%-14s -> %s\n", name, e.what());
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos);
        }
    }
    // Self contact on a thin slab (two layers through 0.3 mm, as a leaflet)
    // with the deepest search allowed: its two faces must not see each
    // other (no contact force on the undeformed, unloaded slab)
    TetMesh slab = TetMesh::box(12, 12, 2, [](const Vec3& x) {
        return Vec3(0.01 * x.x(), 0.01 * x.y(), 0.0003 * x.z());
    });
    ExplicitSolid thin(std::move(slab), std::make_shared<NeoHookean>(3e5, 5e6, 1000.0));
    ContactOptions o;
    o.selfContact = true;
    o.depthFraction = 2.0;
    thin.enableContact(o);
    thin.step(thin.stableTimeStep());
    double force = 0;
    for (double p : thin.contactPressure()) force = std::max(force, p);
    std::printf("thin slab (2 layers), self contact, depthFraction 2: largest contact pressure "
                "%.3e Pa, penetration %.3e m (both must be 0)\n",
                force, thin.maxPenetration());
    EXPECT_EQ(force, 0.0);
    EXPECT_EQ(thin.maxPenetration(), 0.0);
}

// The fibre-reinforced tissue: the state file names the material; the fibre
// directions are set up by the caller (like the mesh) before loadState. The
// plates with circumferential fibres about the z axis, restarted in contact:
// bitwise equal; loading into a Mooney-Rivlin solid fails naming the material
TEST(Restart, FibreTissueRestartIsBitwiseExact)
{
    auto make = [] {
        auto s = std::make_unique<ExplicitSolid>(
            twoPlates(), std::make_shared<HolzapfelGasserOgden>(1.5e5, 0.0, 1e6, 2.0, 5e6, 1000.0),
            SolidOptions{Formulation::Selective, 0.9, 200.0});
        std::vector<Vec3> a(s->mesh().nElements());
        const auto& X = s->mesh().coordinates();
        for (int e = 0; e < s->mesh().nElements(); ++e) {
            const Tet& t = s->mesh().elements()[e];
            const Vec3 c = 0.25 * (X[t[0]] + X[t[1]] + X[t[2]] + X[t[3]]) - Vec3(0.02, 0.02, 0);
            a[e] = Vec3(-c.y(), c.x(), 0);
        }
        s->setFibreDirections(a);
        s->fix("bottom");
        s->addFollowerPressure("top", [](double t) { return 4e4 * std::min(1.0, t / 2e-3); });
        s->enableContact();
        return s;
    };
    auto ref = make();
    const std::string file = test::tempDir() + "/fibrePlates.state";
    for (int call = 1; call <= 20; ++call) {
        ref->advance(kDt);
        if (call == 12) ref->saveState(file);
    }
    auto r = make();
    r->loadState(file);
    for (int call = 13; call <= 20; ++call) r->advance(kDt);
    const bool u = bitwiseEqual(r->displacement(), ref->displacement());
    const bool v = bitwiseEqual(r->velocity(), ref->velocity());
    std::printf("fibre tissue plates restarted after call 12 of 20 (t = %.3e s, largest "
                "penetration %.2e m): u bitwise equal %s, v %s\n",
                ref->time(), ref->maxPenetration(), u ? "yes" : "no", v ? "yes" : "no");
    EXPECT_TRUE(u);
    EXPECT_TRUE(v);
    EXPECT_EQ(r->steps(), ref->steps());
    ExplicitSolid other(twoPlates(), std::make_shared<MooneyRivlin>(1.5e5 / 2, 0.0, 5e6, 1000.0));
    try {
        other.loadState(file);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        std::printf("fibre state into a Mooney-Rivlin solid -> %s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("holzapfelGasserOgden"), std::string::npos);
    }
}
