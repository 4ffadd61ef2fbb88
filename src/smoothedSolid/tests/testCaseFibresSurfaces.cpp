// Case-file input of the fibre-reinforced tissue ('material
// holzapfelGasserOgden', 'fibres') and of rigid contact surfaces
// ('contactSurface', io/SurfaceFile: STL ASCII/binary and gmsh .msh):
// directions and surfaces as read, a block pushed onto a rigid plane from an
// STL stops there (a run without the surface passes through), and bad input
// names the file, line and keyword.
#include "io/SolidRun.hpp"
#include "io/SurfaceFile.hpp"
#include "testMeshes.hpp"

#include <gmsh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

using namespace smoothedSolid;

namespace {

std::string writeFile(const std::string& name, const std::string& text)
{
    const std::string file = test::tempDir() + "/" + name;
    std::ofstream(file) << text;
    return file;
}

template <class F>
std::string errorOf(F f)
{
    try {
        f();
    } catch (const Error& e) {
        std::printf("error: %s\n", e.what());
        return e.what();
    }
    ADD_FAILURE() << "no exception";
    return {};
}

void expectFragments(const std::string& message, std::initializer_list<const char*> fragments)
{
    for (const char* s : fragments) {
        EXPECT_NE(message.find(s), std::string::npos) << "message lacks '" << s << "'";
    }
}

// The square [x0,x1] x [y0,y1] at height z as two triangles, normal +z
struct Square {
    double x0, y0, x1, y1, z;
    std::array<Vec3, 6> corners() const
    {
        return {Vec3(x0, y0, z), Vec3(x1, y0, z), Vec3(x1, y1, z),
                Vec3(x0, y0, z), Vec3(x1, y1, z), Vec3(x0, y1, z)};
    }
};

std::string asciiStl(const std::string& name, const Square& s)
{
    const auto c = s.corners();
    std::string t = "solid plane\n";
    for (int f = 0; f < 2; ++f) {
        t += "  facet normal 0 0 1\n    outer loop\n";
        for (int k = 0; k < 3; ++k) {
            const Vec3& p = c[3 * f + k];
            t += "      vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
                 std::to_string(p.z()) + "\n";
        }
        t += "    endloop\n  endfacet\n";
    }
    t += "endsolid plane\n";
    return writeFile(name, t);
}

std::string binaryStl(const std::string& name, const Square& s)
{
    const auto c = s.corners();
    const std::string file = test::tempDir() + "/" + name;
    std::ofstream os(file, std::ios::binary);
    char header[80] = "solid binary plane";  // binary files may start with 'solid' too
    os.write(header, 80);
    const std::uint32_t n = 2;
    os.write(reinterpret_cast<const char*>(&n), 4);
    for (int f = 0; f < 2; ++f) {
        float v[12] = {0, 0, 1};
        for (int k = 0; k < 3; ++k) {
            for (int d = 0; d < 3; ++d) v[3 + 3 * k + d] = static_cast<float>(c[3 * f + k][d]);
        }
        os.write(reinterpret_cast<const char*>(v), sizeof v);
        const std::uint16_t attr = 0;
        os.write(reinterpret_cast<const char*>(&attr), 2);
    }
    return file;
}

double area(const RigidSurface& s, Vec3* normalSum = nullptr)
{
    double A = 0;
    Vec3 n = Vec3::Zero();
    for (const Tri& t : s.triangles) {
        const Vec3 a = 0.5 * (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]);
        A += a.norm();
        n += a;
    }
    if (normalSum) *normalSum = n;
    return A;
}

}  // namespace

TEST(CaseFile, RigidSurfaceFilesRead)
{
    const Square sq{0, 0, 1, 1, 0};
    const RigidSurface ascii = readRigidSurface(asciiStl("plane.stl", sq));
    const RigidSurface binary = readRigidSurface(binaryStl("planeBinary.stl", sq));
    const RigidSurface flipped = readRigidSurface(asciiStl("planeFlip.stl", sq), true);
    const RigidSurface msh = readRigidSurface(test::surfaceOnlyMsh("surfaceForContact"));
    Vec3 na, nb, nf, nm;
    const double Aa = area(ascii, &na), Ab = area(binary, &nb), Af = area(flipped, &nf),
                 Am = area(msh, &nm);
    std::printf("ASCII STL: %zu triangles, %zu points (shared vertices merged), area %.6f, "
                "normal sum (%g %g %g)\nbinary STL: %zu triangles, area %.6f; flipped: normal "
                "sum z %g\ngmsh .msh: %zu triangles, area %.6f, normal sum z %g\n",
                ascii.triangles.size(), ascii.points.size(), Aa, na.x(), na.y(), na.z(),
                binary.triangles.size(), Ab, nf.z(), msh.triangles.size(), Am, nm.z());
    EXPECT_EQ(ascii.triangles.size(), 2u);
    EXPECT_EQ(ascii.points.size(), 4u);
    EXPECT_EQ(binary.points.size(), 4u);
    EXPECT_NEAR(Aa, 1.0, 1e-12);
    EXPECT_NEAR(Ab, 1.0, 1e-6);
    EXPECT_NEAR(na.z(), 1.0, 1e-12);
    EXPECT_NEAR(nb.z(), 1.0, 1e-6);
    EXPECT_NEAR(nf.z(), -1.0, 1e-12);
    EXPECT_GT(msh.triangles.size(), 4u);
    EXPECT_NEAR(Am, 1.0, 1e-9);
    EXPECT_NEAR(std::abs(nm.z()), 1.0, 1e-9);
}

TEST(CaseFile, RigidSurfaceBadFilesNameTheFile)
{
    expectFragments(errorOf([] { readRigidSurface("/nonexistent/wall.stl"); }),
                    {"/nonexistent/wall.stl", "cannot open"});
    const std::string empty = writeFile("empty.stl", "solid nothing\nendsolid nothing\n");
    expectFragments(errorOf([&] { readRigidSurface(empty); }), {"empty.stl", "no triangles"});
    const std::string garbage = writeFile("garbage.stl", "this is not an STL file\n");
    expectFragments(errorOf([&] { readRigidSurface(garbage); }), {"garbage.stl", "not an STL"});
    const std::string quad = writeFile("quad.stl",
                                       "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                       "vertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\n"
                                       "endfacet\nendsolid q\n");
    expectFragments(errorOf([&] { readRigidSurface(quad); }), {"quad.stl", "4 vertices"});
    const std::string obj = writeFile("wall.obj", "v 0 0 0\n");
    expectFragments(errorOf([&] { readRigidSurface(obj); }), {"wall.obj", "extension"});
    const std::string corrupt = writeFile("corruptWall.msh", "$MeshFormat\n4.1 0 8\ngarbage\n");
    expectFragments(errorOf([&] { readRigidSurface(corrupt); }), {"corruptWall.msh"});
    // a gmsh file with lines only
    initializeGmsh();
    gmsh::clear();
    gmsh::model::add("linesOnly");
    const int p0 = gmsh::model::occ::addPoint(0, 0, 0), p1 = gmsh::model::occ::addPoint(1, 0, 0);
    gmsh::model::occ::addLine(p0, p1);
    gmsh::model::occ::synchronize();
    gmsh::model::mesh::generate(1);
    const std::string lines = test::tempDir() + "/linesOnly.msh";
    gmsh::write(lines);
    gmsh::clear();
    expectFragments(errorOf([&] { readRigidSurface(lines); }), {"linesOnly.msh", "no triangles"});
}

// ---------------------------------------------------------------------------
// A block 10 x 10 x 5 mm (4 x 4 x 2 hexahedra of 6 tets), 1 mm above a rigid
// plane z = 0 read from an STL, thrown at it at 1 m/s. With the surface it
// stops there and bounces: the largest penetration over every sub-step below
// 5 % of the smallest element height. Without it (the negative control),
// and with the plane's normals flipped away from the block, it passes
// through.

namespace {

struct Throw {
    double maxPenetration = 0, lowestZ = 0, hMin = 0, finalVz = 0;
    long steps = 0;
};

Throw throwBlock(const std::string& surfaceLine, const std::string& name, double endTime)
{
    const std::string stl = asciiStl("floor.stl", {-0.01, -0.01, 0.02, 0.02, 0.0});
    (void)stl;
    const std::string file = writeFile(name + ".solid",
                                       "box 4 4 2 0 0 0.001 0.01 0.01 0.006\n"
                                       "material neoHookean mu 1e5 K 1e6 rho 1000\n"
                                       "formulation selective\n" +
                                           surfaceLine +
                                           "\nendTime 7e-3\nwriteInterval 1e-3\noutput " + name +
                                           "\n");
    SolidRun run(file);
    ExplicitSolid& s = run.solid();
    s.setInitialVelocity([](double, const Vec3&) { return Vec3(0, 0, -1.0); });
    Throw r;
    r.hMin = std::numeric_limits<double>::max();
    for (int e = 0; e < s.mesh().nElements(); ++e) r.hMin = std::min(r.hMin, s.mesh().elementHeight(e));
    r.lowestZ = std::numeric_limits<double>::max();
    while (s.time() < endTime) {
        s.step(s.stableTimeStep());
        ++r.steps;
        for (const Vec3& x : s.currentCoordinates()) {
            r.lowestZ = std::min(r.lowestZ, x.z());
            r.maxPenetration = std::max(r.maxPenetration, -x.z());
        }
    }
    double vz = 0, m = 0;
    for (int i = 0; i < s.mesh().nNodes(); ++i) {
        vz += s.lumpedMass()[i] * s.velocity()[i].z();
        m += s.lumpedMass()[i];
    }
    r.finalVz = vz / m;
    return r;
}

}  // namespace

TEST(CaseFile, BlockStopsAtRigidPlaneFromStl)
{
    const Throw with = throwBlock("contactSurface floor.stl", "blockOnFloor", 4e-3);
    const Throw without = throwBlock("", "blockNoFloor", 7e-3);
    // (until its top face, which faces the flipped normals, nears the plane)
    const Throw flipped = throwBlock("contactSurface floor.stl flip", "blockFlippedFloor", 3e-3);
    std::printf("block thrown at 1 m/s onto the STL plane z = 0 (%ld sub-steps): largest "
                "penetration %.3e m = %.2f %% of h_min %.3e m (tolerance 5 %%), lowest z %.3e m, "
                "centre-of-mass v_z at the end %.3f m/s\n",
                with.steps, with.maxPenetration, 100 * with.maxPenetration / with.hMin, with.hMin,
                with.lowestZ, with.finalVz);
    std::printf("without the surface: lowest z %.3e m at 7 ms (must pass below -5 mm, the "
                "block's thickness); with its normals flipped away: lowest z %.3e m at 3 ms (must "
                "pass below -1.5 mm)\n",
                without.lowestZ, flipped.lowestZ);
    EXPECT_LT(with.maxPenetration, 0.05 * with.hMin);
    EXPECT_GT(with.finalVz, 0.0);  // it bounced
    EXPECT_LT(without.lowestZ, -0.005);
    EXPECT_LT(flipped.lowestZ, -0.0015);
}

TEST(CaseFile, ContactSurfaceBadEntriesNameFileAndLine)
{
    auto caseWith = [](const std::string& name, const std::string& line) {
        return writeFile(name + ".solid", "box 2 2 2 0 0 0 1 1 1\n"
                                          "material neoHookean mu 80 K 4e5 rho 1\n" +
                                              line + "\nendTime 1\nwriteInterval 0.5\n");
    };
    expectFragments(errorOf([&] { SolidRun r(caseWith("surfaceMissing", "contactSurface nowhere.stl")); }),
                    {"surfaceMissing.solid:3", "contactSurface", "nowhere.stl", "cannot open"});
    expectFragments(errorOf([&] { SolidRun r(caseWith("surfaceWord", "contactSurface floor.stl flop")); }),
                    {"surfaceWord.solid:3", "contactSurface", "[flip]"});
    writeFile("emptySurface.stl", "solid e\nendsolid e\n");
    expectFragments(errorOf([&] { SolidRun r(caseWith("surfaceEmpty", "contactSurface emptySurface.stl")); }),
                    {"surfaceEmpty.solid:3", "emptySurface.stl", "no triangles"});
    // several surfaces, relative to the case directory
    asciiStl("floorA.stl", {0, 0, 1, 1, -0.1});
    binaryStl("floorB.stl", {0, 0, 1, 1, 1.1});
    SolidRun two(caseWith("twoSurfaces", "contactSurface floorA.stl\ncontactSurface floorB.stl flip"));
    ASSERT_NE(two.solid().contact(), nullptr);
    EXPECT_EQ(two.solid().contact()->rigidSurfaces().size(), 2u);
}

// ---------------------------------------------------------------------------
// The fibre-reinforced tissue from a case file

namespace {

std::string fibreCase(const std::string& name, const std::string& material, const std::string& fibres)
{
    return writeFile(name + ".solid", "box 4 4 1 -1 -1 0 1 1 0.2\n" + material + "\n" + fibres +
                                          "\nendTime 1e-3\nwriteInterval 1e-3\noutput " + name + "\n");
}

const char* kTissue = "material holzapfelGasserOgden c10 1000 c01 200 k1 5000 k2 3 kappa 5e4 rho 1000";

}  // namespace

TEST(CaseFile, FibreDirectionsCylindricalAndUniform)
{
    SolidRun cyl(fibreCase("fibresCylindrical", kTissue,
                           "fibres cylindrical origin (0.05 0 0) axis (0 0 2)"));
    const ExplicitSolid& s = cyl.solid();
    ASSERT_EQ(static_cast<int>(s.fibreDirections().size()), s.mesh().nElements());
    double worst = 0;
    const auto& X = s.mesh().coordinates();
    for (int e = 0; e < s.mesh().nElements(); ++e) {
        const Tet& t = s.mesh().elements()[e];
        const Vec3 c = 0.25 * (X[t[0]] + X[t[1]] + X[t[2]] + X[t[3]]) - Vec3(0.05, 0, 0);
        const Vec3 ref = Vec3(-c.y(), c.x(), 0).normalized();  // e_theta about +z
        worst = std::max(worst, (s.fibreDirections()[e] - ref).norm());
    }
    SolidRun uni(fibreCase("fibresUniform", kTissue, "fibres uniform 1 1 0"));
    const double errU = (uni.solid().fibreDirections()[7] - Vec3(1, 1, 0).normalized()).norm();
    std::printf("cylindrical fibres: max |a0 - e_theta(centroid)| = %.1e over %d elements; "
                "uniform: %.1e (tolerance 1e-14)\n",
                worst, s.mesh().nElements(), errU);
    EXPECT_LT(worst, 1e-14);
    EXPECT_LT(errU, 1e-14);
    EXPECT_EQ(cyl.solid().material().name(), "holzapfelGasserOgden");
    // and it runs
    std::ostringstream log;
    EXPECT_GT(cyl.run(log), 0);
}

TEST(CaseFile, FibreBadInputNamesFileLineAndKeyword)
{
    expectFragments(errorOf([] { SolidRun r(fibreCase("fibresMissing", kTissue, "")); }),
                    {"fibresMissing.solid:2", "material", "needs fibre directions", "fibres cylindrical"});
    expectFragments(errorOf([] {
                        SolidRun r(fibreCase("fibresIsotropic",
                                             "material neoHookean mu 80 K 4e5 rho 1",
                                             "fibres uniform (1 0 0)"));
                    }),
                    {"fibresIsotropic.solid:3", "fibres", "has no fibres"});
    expectFragments(errorOf([] { SolidRun r(fibreCase("fibresSyntax", kTissue, "fibres cylindrical (0 0 0) (0 0 1)")); }),
                    {"fibresSyntax.solid:3", "fibres", "cylindrical origin"});
    expectFragments(errorOf([] { SolidRun r(fibreCase("fibresLayout", kTissue, "fibres helical 1 0 0")); }),
                    {"fibresLayout.solid:3", "fibres", "helical"});
    expectFragments(errorOf([] { SolidRun r(fibreCase("fibresZero", kTissue, "fibres uniform (0 0 0)")); }),
                    {"fibresZero.solid:3", "fibres", "zero"});
    // the box spans the origin: an element's centroid on the axis x = y = 0?
    // (the 4 x 4 structured box has a node, not a centroid, there; put the
    // axis through a centroid instead)
    SolidRun probe(fibreCase("fibresProbe", kTissue, "fibres uniform (1 0 0)"));
    const auto& X = probe.solid().mesh().coordinates();
    const Tet& t = probe.solid().mesh().elements()[0];
    const Vec3 c = 0.25 * (X[t[0]] + X[t[1]] + X[t[2]] + X[t[3]]);
    const std::string onAxis = "fibres cylindrical origin (" + std::to_string(c.x()) + " " +
                               std::to_string(c.y()) + " " + std::to_string(c.z()) +
                               ") axis (0 0 1)";
    const std::string msg = errorOf([&] { SolidRun r(fibreCase("fibresOnAxis", kTissue, onAxis)); });
    expectFragments(msg, {"fibresOnAxis.solid:3", "fibres", "on the axis"});
    expectFragments(errorOf([] {
                        SolidRun r(fibreCase("fibresK2",
                                             "material holzapfelGasserOgden c10 1000 k1 5000 kappa 5e4 rho 1000",
                                             "fibres uniform 1 0 0"));
                    }),
                    {"fibresK2.solid:2", "material", "k2"});
}

// fibres from a file, one direction per element in the mesh's order (as
// makeValveMeshes writes beside the leaflets); a wrong count or a bad line
// names the file
TEST(CaseFile, FibreDirectionsFromFile)
{
    SolidRun probe(fibreCase("fibresProbeFile", kTissue, "fibres uniform (1 0 0)"));
    const int ne = probe.solid().mesh().nElements();
    std::string text = "# x y z per element\n";
    for (int e = 0; e < ne; ++e) {
        const double phi = 0.1 * e;
        text += std::to_string(2 * std::cos(phi)) + " " + std::to_string(2 * std::sin(phi)) + " 0\n";
    }
    writeFile("fibres.dirs", text);
    SolidRun run(fibreCase("fibresFile", kTissue, "fibres file fibres.dirs"));
    double worst = 0;
    for (int e = 0; e < ne; ++e) {
        const double phi = 0.1 * e;
        // the file holds 6 digits
        worst = std::max(worst, (run.solid().fibreDirections()[e] - Vec3(std::cos(phi), std::sin(phi), 0)).norm());
    }
    std::printf("fibres from a file: max |a0 - written| = %.1e over %d elements (tolerance 1e-6)\n", worst, ne);
    EXPECT_LT(worst, 1e-6);

    writeFile("short.dirs", "1 0 0\n0 1 0\n");
    expectFragments(errorOf([] { SolidRun r(fibreCase("fibresShort", kTissue, "fibres file short.dirs")); }),
                    {"fibresShort.solid:3", "short.dirs", "2 directions for"});
    writeFile("bad.dirs", "1 0 0\n1 0\n");
    expectFragments(errorOf([] { SolidRun r(fibreCase("fibresBadLine", kTissue, "fibres file bad.dirs")); }),
                    {"fibresBadLine.solid:3", "bad.dirs line 2", "three numbers"});
    expectFragments(errorOf([] { SolidRun r(fibreCase("fibresNoFile", kTissue, "fibres file none.dirs")); }),
                    {"fibresNoFile.solid:3", "none.dirs", "cannot read"});
}
