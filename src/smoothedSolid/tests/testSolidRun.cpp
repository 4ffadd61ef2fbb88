// smoothedSolidRun's time loop (io/SolidRun): sub-cycling at the solid's
// stable step, halved while contact is near; outputs exactly at the write
// and probe times; time-dependent loads updated at every sub-step
#include "io/SolidRun.hpp"
#include "testMeshes.hpp"

#include <gmsh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

using namespace smoothedSolid;

namespace {

// Two boxes of one .msh (two parts): the lower one [0,1]^2 x [0,0.25]
// (physical surface "bottom" at z = 0), the upper one [0.25,0.75]^2 x
// [0.25+gap, 0.5+gap] above it
std::string twoBoxesMsh(const std::string& name, double gap, double h)
{
    initializeGmsh();
    gmsh::clear();
    gmsh::model::add(name);
    const int lower = gmsh::model::occ::addBox(0, 0, 0, 1, 1, 0.25);
    const int upper = gmsh::model::occ::addBox(0.25, 0.25, 0.25 + gap, 0.5, 0.5, 0.25);
    gmsh::model::occ::synchronize();
    gmsh::vectorpair bottom;
    gmsh::model::getEntitiesInBoundingBox(-1e-6, -1e-6, -1e-6, 1 + 1e-6, 1 + 1e-6, 1e-6, bottom, 2);
    std::vector<int> tags;
    for (const auto& [dim, tag] : bottom) tags.push_back(tag);
    gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {lower, upper}), "solid");
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, tags), "bottom");
    gmsh::option::setNumber("Mesh.CharacteristicLengthMin", h);
    gmsh::option::setNumber("Mesh.CharacteristicLengthMax", h);
    gmsh::model::mesh::generate(3);
    const std::string path = test::tempDir() + "/" + name + ".msh";
    gmsh::write(path);
    gmsh::clear();
    return path;
}

std::string writeCase(const std::string& name, const std::string& text)
{
    const std::string file = test::tempDir() + "/" + name + ".solid";
    std::ofstream(file) << text;
    return file;
}

// A clamped 2 x 2 x 2 box to t = 1, written at 0.5, then the lines of extra
// (line 6 onward)
std::string smallBoxCase(const std::string& name, const std::string& extra)
{
    return writeCase(name, "box 2 2 2 0 0 0 1 1 1\n"
                           "material neoHookean mu 80 K 4e5 rho 1\n"
                           "fix xmin\n"
                           "endTime 1\nwriteInterval 0.5\n" +
                               extra);
}

// Rows of <output>/probes.dat
std::vector<std::vector<double>> readProbes(const std::string& file)
{
    std::ifstream is(file);
    EXPECT_TRUE(is) << file;
    std::vector<std::vector<double>> rows;
    std::string line;
    while (std::getline(is, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        std::vector<double> r;
        double v;
        while (ls >> v) r.push_back(v);
        rows.push_back(r);
    }
    return rows;
}

// The timesteps of a .pvd collection
std::vector<double> readPvdTimes(const std::string& file)
{
    std::ifstream is(file);
    EXPECT_TRUE(is) << file;
    std::stringstream ss;
    ss << is.rdbuf();
    const std::string text = ss.str();
    std::vector<double> t;
    const std::regex re("timestep=\"([^\"]+)\"");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
         ++it) {
        t.push_back(std::stod((*it)[1]));
    }
    return t;
}

}  // namespace

// The upper box falls by gravity (mass damping, so that it comes to rest)
// onto the lower one, clamped at its bottom. Write intervals classified by
// the gap between the probes at the facing surfaces' centres, sampled every
// probe interval: apart while it stays above 2 h_min (the contact search
// reaches h_min, plus h_min/2 of Verlet skin), in contact while below
// h_min/4. The sub-steps while in contact must be the contact step fraction
// (0.5) of those while apart, as the solid's stableTimeStep() says.
TEST(SolidRun, ContactHalvesSubStepsAndOutputsAtEventTimes)
{
    const double gap = 0.2, W = 0.05, P = 0.025, T = 0.8;
    twoBoxesMsh("solidRunTwoBoxes", gap, 0.125);
    std::ostringstream text;
    text << "mesh          solidRunTwoBoxes.msh\n"
            "material      neoHookean mu 80 K 400 rho 1\n"
            "fix           bottom\n"
            "bodyForce     0 0 -10\n"
            "damping       4\n"
            "contact\n"
            "endTime       "
         << T << "\nwriteInterval " << W << "\nprobeInterval " << P
         << "\noutput        solidRunContact\n"
            "probe         lowerTop 0.5 0.5 0.25\n"
            "probe         upperBottom 0.5 0.5 "
         << 0.25 + gap << "\n";
    SolidRun run(writeCase("solidRunContact", text.str()));
    ExplicitSolid& s = run.solid();
    const double dt0 = s.stableTimeStep();
    const double fraction = s.contact()->options().stepFraction;
    double hMin = 1e300;
    for (int e = 0; e < s.mesh().nElements(); ++e) hMin = std::min(hMin, s.mesh().elementHeight(e));
    std::ostringstream log;
    const long steps = run.run(log);
    std::printf("%s", log.str().c_str());

    const std::string dir = test::tempDir() + "/solidRunContact";
    const auto rows = readProbes(dir + "/probes.dat");
    const auto& iv = run.writeIntervals();
    ASSERT_EQ(iv.size(), std::size_t(std::lround(T / W)));

    // (a) sub-steps per unit time apart and in contact
    auto gapAt = [&](const std::vector<double>& r) { return gap + r[6] - r[3]; };
    // sub-steps of one probe interval at stable step dt (advance(): equal
    // sub-steps, as few as the stable step allows)
    const double perChunkApart = std::ceil(P / dt0 - 1e-12);
    const double perChunkNear = std::ceil(P / (fraction * dt0) - 1e-12);
    long nApart = 0, nNear = 0;
    double tApart = 0, tNear = 0;
    std::printf("stable step %.5e s at t = 0, contact step fraction %.2f, h_min %.4f\n", dt0,
                fraction, hMin);
    std::printf("  interval end | gap min..max / h_min | sub-steps | sub-step min..max [s] | "
                "stable step at the end [s] | class\n");
    for (std::size_t k = 0; k < iv.size(); ++k) {
        const double t0 = iv[k].time - W, t1 = iv[k].time;
        double gMin = 1e300, gMax = -1e300;
        for (const auto& r : rows) {
            if (r[0] < t0 - 1e-9 || r[0] > t1 + 1e-9) continue;
            gMin = std::min(gMin, gapAt(r));
            gMax = std::max(gMax, gapAt(r));
        }
        const bool apart = gMin > 2 * hMin, near = gMax < 0.25 * hMin;
        std::printf("  %5.3f | %7.3f .. %7.3f | %4ld | %.4e .. %.4e | %.4e | %s\n", t1,
                    gMin / hMin, gMax / hMin, iv[k].subSteps, iv[k].minSubStep, iv[k].maxSubStep,
                    iv[k].stableStep, apart ? "apart" : near ? "contact" : "-");
        const double expected = apart ? dt0 : fraction * dt0;
        if (apart || near) {
            // never above the stable step; below it only by the rounding to
            // whole sub-steps per probe interval (10 % allowed for a stable
            // step that follows the deformation: the impact compresses the
            // elements by a few percent)
            const double perChunk = apart ? perChunkApart : perChunkNear;
            EXPECT_NEAR(iv[k].stableStep, expected, 0.1 * expected) << "t = " << t1;
            EXPECT_LE(iv[k].maxSubStep, expected * 1.1) << "t = " << t1;
            EXPECT_GE(iv[k].minSubStep, P / perChunk * 0.9) << "t = " << t1;
            EXPECT_NEAR(double(iv[k].subSteps), W / P * perChunk, W / P) << "t = " << t1;
        }
        if (apart) nApart += iv[k].subSteps, tApart += W;
        if (near) nNear += iv[k].subSteps, tNear += W;
    }
    ASSERT_GE(tApart, 2 * W);
    ASSERT_GE(tNear, 2 * W);
    const double rateApart = nApart / tApart, rateNear = nNear / tNear;
    std::printf("sub-steps per second: apart %.1f (1/stable step %.1f, %g per probe interval "
                "expected), in contact %.1f (1/(%.2f stable step) %.1f, %g per probe interval "
                "expected); ratio %.3f (expected 1/%.2f = %.2f, tolerance 15 %%)\n",
                rateApart, 1 / dt0, perChunkApart, rateNear, fraction, 1 / (fraction * dt0),
                perChunkNear, rateNear / rateApart, fraction, 1 / fraction);
    EXPECT_NEAR(rateNear / rateApart, 1 / fraction, 0.15 / fraction);
    long total = 0;
    for (const auto& i : iv) total += i.subSteps;
    EXPECT_EQ(steps, total);
    EXPECT_EQ(steps, s.steps());

    // (b) outputs exactly at the write and probe times
    double worstWrite = 0;
    for (std::size_t k = 0; k < iv.size(); ++k) {
        worstWrite = std::max(worstWrite, std::abs(iv[k].time - (k + 1) * W));
    }
    const auto pvd = readPvdTimes(dir + "/solid.pvd");
    double worstPvd = 0;
    for (std::size_t k = 0; k < pvd.size(); ++k) {
        worstPvd = std::max(worstPvd, std::abs(pvd[k] - k * W));
    }
    double worstProbe = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        worstProbe = std::max(worstProbe, std::abs(rows[k][0] - k * P));
    }
    std::printf("write times: %zu, largest |t - k writeInterval| %.2e s (tolerance 1e-12); "
                "solid.pvd: %zu data sets (expected %ld), largest deviation %.2e s (6 digits "
                "written: tolerance 1e-6 s)\n",
                iv.size(), worstWrite, pvd.size(), std::lround(T / W) + 1, worstPvd);
    std::printf("probes.dat: %zu rows (expected %ld), largest |t - k probeInterval| %.2e s "
                "(10 digits written: tolerance 1e-9 s)\n",
                rows.size(), std::lround(T / P) + 1, worstProbe);
    EXPECT_LT(worstWrite, 1e-12);
    EXPECT_EQ(pvd.size(), std::size_t(std::lround(T / W) + 1));
    EXPECT_LT(worstPvd, 1e-6);
    EXPECT_EQ(rows.size(), std::size_t(std::lround(T / P) + 1));
    EXPECT_LT(worstProbe, 1e-9);
    EXPECT_NEAR(s.time(), T, 1e-12);
}

// Ramped traction, gravity and follower pressure on a clamped beam: the
// probe history of the run against a reference made here by hand with
// ExplicitSolid::step at the same sub-steps (the loop of advance(): equal
// sub-steps within each probe interval, re-chosen after each one), with the
// loads updated before every step. The same reference with the loads
// updated once per probe interval must differ clearly: the run updates them
// per sub-step.
TEST(SolidRun, RampedLoadsUpdatedEverySubStep)
{
    const double W = 0.05, P = 0.01, T = 0.3, ramp = 0.15;
    const Vec3 g(0, 0, -1), tr(0, 0, -1);
    const double p = 0.5;
    std::ostringstream text;
    text << "box           8 2 2  0 0 0  1 0.25 0.25\n"
            "material      neoHookean mu 80 K 400 rho 1\n"
            "fix           xmin\n"
            "traction      xmax "
         << tr.x() << " " << tr.y() << " " << tr.z() << " ramp " << ramp
         << "\nbodyForce     " << g.x() << " " << g.y() << " " << g.z() << " ramp " << ramp
         << "\npressure      ymax " << p << " ramp " << ramp << "\nendTime       " << T
         << "\nwriteInterval " << W << "\nprobeInterval " << P
         << "\noutput        solidRunRamp\n"
            "probe         tip 1 0.25 0.25\n";
    SolidRun run(writeCase("solidRunRamp", text.str()));
    std::ostringstream log;
    const long steps = run.run(log);
    std::printf("%s", log.str().c_str());
    const auto rows = readProbes(test::tempDir() + "/solidRunRamp/probes.dat");

    // The reference: the same mesh, material and loads, built here
    auto reference = [&](bool everySubStep, long& nSteps, std::vector<std::vector<double>>& hist) {
        TetMesh mesh = TetMesh::box(8, 2, 2, [](const Vec3& s) {
            return Vec3(s.cwiseProduct(Vec3(1, 0.25, 0.25)));
        });
        int tip = -1;
        for (int i = 0; i < mesh.nNodes(); ++i) {
            if ((mesh.coordinates()[i] - Vec3(1, 0.25, 0.25)).norm() < 1e-12) tip = i;
        }
        EXPECT_GE(tip, 0);
        std::vector<Vec3> nodal(mesh.nNodes(), Vec3::Zero());
        const auto& X = mesh.coordinates();
        for (const Tri& f : mesh.faceSet("xmax")) {
            const double A = 0.5 * (X[f[1]] - X[f[0]]).cross(X[f[2]] - X[f[0]]).norm();
            for (int v : f) nodal[v] += tr * (A / 3.0);
        }
        ExplicitSolid s(std::move(mesh), std::make_shared<NeoHookean>(80, 400, 1));
        s.fix("xmin");
        s.addFollowerPressure("ymax", [&](double t) { return p * std::min(1.0, t / ramp); });
        auto loads = [&](double t) {
            const double r = std::min(1.0, t / ramp);
            for (std::size_t i = 0; i < nodal.size(); ++i) s.externalForce()[i] = r * nodal[i];
            s.setBodyForce(r * g);
        };
        auto sample = [&] {
            const Vec3 u = s.displacement()[tip];
            hist.push_back({s.time(), u.x(), u.y(), u.z()});
        };
        sample();
        const double eps = 1e-9 * std::min(W, P);
        long nW = 1, nP = 1;
        while (s.time() < T - eps) {
            const double tW = nW * W, tP = nP * P;
            const double target = std::min({tW, tP, T});
            if (!everySubStep) loads(s.time());
            double left = target - s.time();
            for (;;) {
                const int k = static_cast<int>(std::ceil(left / s.stableTimeStep() - 1e-12));
                const double h = k <= 1 ? left : left / k;
                if (everySubStep) loads(s.time());
                s.step(h);
                left -= h;
                if (k <= 1) break;
            }
            if (tP <= target + eps) ++nP, sample();
            if (tW <= target + eps) ++nW;
        }
        nSteps = s.steps();
        return s.displacement();
    };
    long refSteps = 0, chunkSteps = 0;
    std::vector<std::vector<double>> ref, chunk;
    const std::vector<Vec3> uRef = reference(true, refSteps, ref);
    reference(false, chunkSteps, chunk);

    ASSERT_EQ(rows.size(), ref.size());
    ASSERT_EQ(rows.size(), chunk.size());
    double scale = 0, diffRef = 0, diffChunk = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        EXPECT_NEAR(rows[k][0], ref[k][0], 1e-12);
        for (int c = 1; c <= 3; ++c) {
            scale = std::max(scale, std::abs(ref[k][c]));
            diffRef = std::max(diffRef, std::abs(rows[k][c] - ref[k][c]));
            diffChunk = std::max(diffChunk, std::abs(chunk[k][c] - ref[k][c]));
        }
    }
    double diffFinal = 0;
    for (std::size_t i = 0; i < uRef.size(); ++i) {
        diffFinal = std::max(diffFinal, (run.solid().displacement()[i] - uRef[i]).norm());
    }
    std::printf("ramped loads over %.2f s, %ld sub-steps (reference %ld), %zu probe samples, "
                "largest tip displacement %.4e m\n",
                ramp, steps, refSteps, rows.size(), scale);
    std::printf("  run vs reference with loads updated every sub-step: probe history %.2e "
                "(tolerance 1e-8 of the largest: 10 digits written), final displacement field "
                "%.2e m (tolerance 1e-12 of the largest)\n",
                diffRef, diffFinal);
    std::printf("  reference with loads updated once per probe interval differs by %.2e "
                "(= %.2e of the largest; must exceed 1e-4, far above the tolerance)\n",
                diffChunk, diffChunk / scale);
    EXPECT_EQ(steps, refSteps);
    EXPECT_LT(diffRef, 1e-8 * scale);
    EXPECT_LT(diffFinal, 1e-12 * scale);
    EXPECT_GT(diffChunk, 1e-4 * scale);
}

// probeInterval: default writeInterval/50; a non-positive or missing value
// is an error naming the file, line and keyword
TEST(SolidRun, ProbeIntervalKeyword)
{
    const auto write = smallBoxCase;
    SolidRun byDefault(write("probeDefault", ""));
    SolidRun given(write("probeGiven", "probeInterval 0.02\n"));
    std::printf("probeInterval: default %g s (writeInterval 0.5 s / 50 = 0.01 s), given %g s "
                "(0.02 s)\n",
                byDefault.probeInterval(), given.probeInterval());
    EXPECT_DOUBLE_EQ(byDefault.probeInterval(), 0.01);
    EXPECT_DOUBLE_EQ(given.probeInterval(), 0.02);
    for (const char* bad : {"probeInterval 0\n", "probeInterval\n", "probeInterval 1 ms\n"}) {
        try {
            SolidRun run(write("probeBad", bad));
            ADD_FAILURE() << "no exception for '" << bad << "'";
        } catch (const Error& e) {
            std::printf("error: %s\n", e.what());
            EXPECT_NE(std::string(e.what()).find("probeBad.solid:6: 'probeInterval'"),
                      std::string::npos);
        }
    }
}

// stiffnessDamping in a case file reaches the solid's options; a negative
// or non-numeric value is an error naming the file, line and keyword
TEST(SolidRun, StiffnessDampingKeyword)
{
    const auto write = smallBoxCase;
    SolidRun byDefault(write("betaDefault", ""));
    SolidRun given(write("betaGiven", "stiffnessDamping 2e-4\n"));
    std::printf("stiffnessDamping: default %g s (0), given %g s (2e-4)\n",
                byDefault.solid().options().stiffnessDamping,
                given.solid().options().stiffnessDamping);
    EXPECT_EQ(byDefault.solid().options().stiffnessDamping, 0.0);
    EXPECT_DOUBLE_EQ(given.solid().options().stiffnessDamping, 2e-4);
    for (const char* bad : {"stiffnessDamping -1e-4\n", "stiffnessDamping fast\n"}) {
        try {
            SolidRun run(write("betaBad", bad));
            ADD_FAILURE() << "no exception for '" << bad << "'";
        } catch (const Error& e) {
            std::printf("error: %s\n", e.what());
            EXPECT_NE(std::string(e.what()).find("betaBad.solid:6: 'stiffnessDamping'"),
                      std::string::npos);
        }
    }
}
