// VTU output, read back and compared with the solver's arrays, and exact
// restart
#include "dynamics/ExplicitSolid.hpp"
#include "io/VtuWriter.hpp"
#include "testMeshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

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

namespace {

std::string readFile(const std::string& path)
{
    std::ifstream is(path);
    std::stringstream ss;
    ss << is.rdbuf();
    return ss.str();
}

// RFC 4648 base64, whitespace ignored; throws on any other character
std::vector<unsigned char> base64Decode(const std::string& text)
{
    static const std::string alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::vector<unsigned char> out;
    unsigned bits = 0;
    int nBits = 0;
    for (const char c : text) {
        if (c == '=') break;
        if (std::isspace(static_cast<unsigned char>(c))) continue;
        const std::size_t v = alphabet.find(c);
        if (v == std::string::npos) {
            throw std::runtime_error(std::string("base64: bad character '") + c + "'");
        }
        bits = (bits << 6) | static_cast<unsigned>(v);
        nBits += 6;
        if (nBits >= 8) {
            nBits -= 8;
            out.push_back(static_cast<unsigned char>((bits >> nBits) & 0xff));
        }
    }
    return out;
}

// Value of attribute `name` in the tag text, "" if absent
std::string attribute(const std::string& tag, const std::string& name)
{
    const std::string key = " " + name + "=\"";
    const std::size_t a = tag.find(key);
    if (a == std::string::npos) return "";
    const std::size_t b = a + key.size();
    return tag.substr(b, tag.find('"', b) - b);
}

struct VtkArray {
    std::string type, section;  // section: Points, Cells, PointData or CellData
    int components = 0;
    std::vector<unsigned char> data;  // the payload after the UInt64 byte count

    template <class T>
    std::vector<T> as() const
    {
        std::vector<T> v(data.size() / sizeof(T));
        std::memcpy(v.data(), data.data(), v.size() * sizeof(T));
        return v;
    }
};

struct VtuFile {
    std::string header;  // the <VTKFile ...> tag
    int nPoints = -1, nCells = -1;
    std::map<std::string, VtkArray> arrays;
};

// Reads the writer's layout: binary DataArrays, each base64 of a
// little-endian UInt64 byte count followed by the raw data
VtuFile readVtu(const std::string& path)
{
    const std::string text = readFile(path);
    VtuFile f;
    const std::size_t head = text.find("<VTKFile");
    f.header = text.substr(head, text.find('>', head) - head);
    const std::size_t piece = text.find("<Piece");
    const std::string pieceTag = text.substr(piece, text.find('>', piece) - piece);
    f.nPoints = std::stoi(attribute(pieceTag, "NumberOfPoints"));
    f.nCells = std::stoi(attribute(pieceTag, "NumberOfCells"));
    for (std::size_t pos = text.find("<DataArray"); pos != std::string::npos;
         pos = text.find("<DataArray", pos + 1)) {
        const std::size_t tagEnd = text.find('>', pos);
        const std::string tag = text.substr(pos, tagEnd - pos);
        const std::size_t end = text.find("</DataArray>", tagEnd);
        VtkArray a;
        a.type = attribute(tag, "type");
        a.components = std::stoi(attribute(tag, "NumberOfComponents"));
        EXPECT_EQ(attribute(tag, "format"), "binary") << tag;
        // the innermost enclosing section opened before this array
        std::size_t best = 0;
        for (const char* s : {"<Points>", "<Cells>", "<PointData", "<CellData"}) {
            const std::size_t at = text.rfind(s, pos);
            if (at != std::string::npos && at >= best) {
                best = at;
                a.section = std::string(s).substr(1, std::strcspn(s + 1, "> "));
            }
        }
        const std::vector<unsigned char> raw =
            base64Decode(text.substr(tagEnd + 1, end - tagEnd - 1));
        std::uint64_t bytes = 0;
        for (int k = 7; k >= 0 && raw.size() >= 8; --k) bytes = (bytes << 8) | raw[k];
        EXPECT_EQ(bytes + 8, raw.size()) << "byte count header of " << tag;
        if (raw.size() >= 8) a.data.assign(raw.begin() + 8, raw.end());
        f.arrays[attribute(tag, "Name")] = std::move(a);
    }
    return f;
}

std::vector<double> flat(const std::vector<Vec3>& v)
{
    std::vector<double> out;
    for (const Vec3& x : v) out.insert(out.end(), {x.x(), x.y(), x.z()});
    return out;
}

// Largest |a - b|, and whether a and b are bitwise the same
std::pair<double, bool> compare(const std::vector<double>& a, const std::vector<double>& b)
{
    if (a.size() != b.size()) return {INFINITY, false};
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    return {worst, a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0};
}

bool hostIsLittleEndian()
{
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

// Largest eigenvalue of a symmetric 3x3 matrix, closed form (trigonometric
// solution of the characteristic cubic), independent of the writer's solver
double maxEigenvalue(const Mat3& s)
{
    const double q = s.trace() / 3.0;
    const double p1 = s(0, 1) * s(0, 1) + s(0, 2) * s(0, 2) + s(1, 2) * s(1, 2);
    const double p2 = std::pow(s(0, 0) - q, 2) + std::pow(s(1, 1) - q, 2) +
                      std::pow(s(2, 2) - q, 2) + 2 * p1;
    const double p = std::sqrt(p2 / 6.0);
    if (p == 0) return q;
    const double r = std::clamp(((s - q * Mat3::Identity()) / p).determinant() / 2.0, -1.0, 1.0);
    return q + 2 * p * std::cos(std::acos(r) / 3.0);
}

// The .vtu just written against the solid it was written from: state arrays
// and the mesh bitwise, derived stress measures to round-off. `deformed`: the
// state is not the initial one, so u, v and the stress must be non-zero (all
// zeros on both sides would compare equal however wrong the writer)
void checkVtu(const std::string& path, const ExplicitSolid& solid,
              const VtuSeries::NodalFields& extra, bool deformed)
{
    SCOPED_TRACE(path);
    const VtuFile f = readVtu(path);
    const TetMesh& mesh = solid.mesh();
    const int nn = mesh.nNodes(), ne = mesh.nElements();
    EXPECT_NE(f.header.find("byte_order=\"LittleEndian\""), std::string::npos) << f.header;
    EXPECT_NE(f.header.find("header_type=\"UInt64\""), std::string::npos) << f.header;
    ASSERT_TRUE(hostIsLittleEndian()) << "the raw read-back below assumes a little-endian host";
    EXPECT_EQ(f.nPoints, nn);
    EXPECT_EQ(f.nCells, ne);

    // Float64 arrays copied from the solver: bitwise
    std::vector<Vec3> x(mesh.coordinates());
    for (int i = 0; i < nn; ++i) x[i] += solid.displacement()[i];
    std::map<std::string, std::pair<std::string, std::vector<double>>> exact = {
        {"Points", {"Points", flat(x)}},
        {"displacement", {"PointData", flat(solid.displacement())}},
        {"velocity", {"PointData", flat(solid.velocity())}},
        {"externalForce", {"PointData", flat(solid.externalForce())}}};
    for (const auto& [name, values] : extra) exact[name] = {"PointData", values};
    std::vector<Mat3> sigma;
    std::vector<double> J;
    solid.elementStress(sigma, J);
    std::vector<double> sig9;
    for (const Mat3& s : sigma) {
        const Mat3 sym = 0.5 * (s + s.transpose());  // the writer symmetrizes
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) sig9.push_back(sym(a, b));
    }
    exact["cauchyStress"] = {"CellData", sig9};
    exact["J"] = {"CellData", J};
    for (const auto& [name, ref] : exact) {
        const auto it = f.arrays.find(name);
        if (it == f.arrays.end()) {
            ADD_FAILURE() << "no DataArray " << name;
            continue;
        }
        const VtkArray& a = it->second;
        const int n = ref.first == "CellData" ? ne : nn;
        const auto [diff, same] = compare(a.as<double>(), ref.second);
        double size = 0;
        for (const double v : ref.second) size = std::max(size, std::abs(v));
        std::printf("  %-16s %-9s %d x %d Float64: max |value| %.3e, largest difference %.3e, "
                    "bitwise %s (expected 0, yes)\n",
                    name.c_str(), a.section.c_str(), n, a.components, size, diff,
                    same ? "yes" : "NO");
        if (deformed) EXPECT_GT(size, 0.0) << name;
        EXPECT_EQ(a.type, "Float64") << name;
        EXPECT_EQ(a.section, ref.first) << name;
        EXPECT_EQ(a.components * n, static_cast<int>(ref.second.size())) << name;
        EXPECT_TRUE(same) << name;
    }

    // Von Mises and maximum principal stress from their definitions
    double scale = 0, errMises = 0, errPrincipal = 0;
    for (const Mat3& s : sigma) scale = std::max(scale, s.cwiseAbs().maxCoeff());
    const std::vector<double> mises = f.arrays.at("vonMises").as<double>();
    const std::vector<double> principal = f.arrays.at("maxPrincipalStress").as<double>();
    ASSERT_EQ(static_cast<int>(mises.size()), ne);
    ASSERT_EQ(static_cast<int>(principal.size()), ne);
    for (int e = 0; e < ne; ++e) {
        const Mat3 s = 0.5 * (sigma[e] + sigma[e].transpose());
        const double vm = std::sqrt(
            0.5 * (std::pow(s(0, 0) - s(1, 1), 2) + std::pow(s(1, 1) - s(2, 2), 2) +
                   std::pow(s(2, 2) - s(0, 0), 2)) +
            3 * (s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(0, 2) * s(0, 2)));
        const double norm = std::max(scale, std::numeric_limits<double>::min());
        errMises = std::max(errMises, std::abs(mises[e] - vm) / norm);
        errPrincipal = std::max(errPrincipal, std::abs(principal[e] - maxEigenvalue(s)) / norm);
    }
    const double tol = 1e-12;
    std::printf("  vonMises, maxPrincipalStress: largest difference / max |sigma_ij| (%.3e) "
                "%.2e, %.2e (tolerance %.0e)\n",
                scale, errMises, errPrincipal, tol);
    if (deformed) EXPECT_GT(scale, 0.0);
    EXPECT_LT(errMises, tol);
    EXPECT_LT(errPrincipal, tol);

    // Cells: connectivity from the mesh, offsets 4, 8, ..., all VTK_TETRA (10)
    const std::vector<std::int64_t> conn = f.arrays.at("connectivity").as<std::int64_t>();
    const std::vector<std::int64_t> offsets = f.arrays.at("offsets").as<std::int64_t>();
    const std::vector<std::uint8_t> types = f.arrays.at("types").as<std::uint8_t>();
    ASSERT_EQ(static_cast<int>(conn.size()), 4 * ne);
    ASSERT_EQ(static_cast<int>(offsets.size()), ne);
    ASSERT_EQ(static_cast<int>(types.size()), ne);
    int wrong = 0;
    for (int e = 0; e < ne; ++e) {
        for (int k = 0; k < 4; ++k) wrong += conn[4 * e + k] != mesh.elements()[e][k];
        wrong += offsets[e] != 4 * (e + 1);
        wrong += types[e] != 10;
    }
    std::printf("  connectivity, offsets, types (Int64, Int64, UInt8) of %d tets: %d wrong "
                "entries (expected 0)\n",
                ne, wrong);
    EXPECT_EQ(f.arrays.at("connectivity").type, "Int64");
    EXPECT_EQ(f.arrays.at("offsets").type, "Int64");
    EXPECT_EQ(f.arrays.at("types").type, "UInt8");
    EXPECT_EQ(wrong, 0);
}

}  // namespace

// Every array of every written .vtu decoded and compared with the solver's,
// and the .pvd lists each file with its time
TEST(Output, VtuSeriesWritesFieldsAndCollection)
{
    // RFC 4648 test vectors for the decoder itself
    const auto str = [](const std::vector<unsigned char>& v) {
        return std::string(v.begin(), v.end());
    };
    EXPECT_EQ(str(base64Decode("Zg==")), "f");
    EXPECT_EQ(str(base64Decode("Zm8=")), "fo");
    EXPECT_EQ(str(base64Decode("Zm9v")), "foo");
    EXPECT_EQ(str(base64Decode("Zm9vYmFy")), "foobar");

    ExplicitSolid solid = smallBeam();
    const std::string dir = test::tempDir() + "/vtu";
    VtuSeries series(dir, "beam");
    std::vector<double> times;

    series.write(solid);
    times.push_back(solid.time());
    std::printf("%s/beam_000000.vtu at t = %.17g\n", dir.c_str(), solid.time());
    checkVtu(dir + "/beam_000000.vtu", solid, {}, false);

    // a nodal load, as the FSI coupling sets it, so externalForce is non-zero
    for (int i = 0; i < solid.mesh().nNodes(); ++i) {
        solid.externalForce()[i] = 1e-3 * Vec3(1, -2, 0.5) * solid.mesh().coordinates()[i].x();
    }
    solid.advance(20 * solid.stableTimeStep());
    std::vector<double> cp(solid.mesh().nNodes()), n3(3 * solid.mesh().nNodes());
    for (int i = 0; i < solid.mesh().nNodes(); ++i) {
        cp[i] = 1.5 + 0.25 * i;  // distinct values, so a misordering shows
        for (int k = 0; k < 3; ++k) n3[3 * i + k] = i + 0.1 * k;
    }
    const VtuSeries::NodalFields extra = {{"contactPressure", cp}, {"nodeVector", n3}};
    series.write(solid, extra);
    times.push_back(solid.time());
    std::printf("%s/beam_000001.vtu at t = %.17g\n", dir.c_str(), solid.time());
    checkVtu(dir + "/beam_000001.vtu", solid, extra, true);
    EXPECT_EQ(series.count(), 2);

    // The collection: one DataSet per write, in order, with its time. The
    // writer prints times with the stream's default 6 significant digits, so
    // the tolerance is half a unit of the 6th digit, 5e-6 |t|
    const std::string pvd = readFile(dir + "/beam.pvd");
    std::vector<std::pair<std::string, std::string>> sets;  // (timestep, file)
    for (std::size_t pos = pvd.find("<DataSet"); pos != std::string::npos;
         pos = pvd.find("<DataSet", pos + 1)) {
        const std::string tag = pvd.substr(pos, pvd.find('>', pos) - pos);
        sets.emplace_back(attribute(tag, "timestep"), attribute(tag, "file"));
    }
    ASSERT_EQ(sets.size(), times.size());
    for (std::size_t k = 0; k < sets.size(); ++k) {
        const auto& [written, file] = sets[k];
        char expected[32];
        std::snprintf(expected, sizeof expected, "beam_%06zu.vtu", k);
        const double tol = 5e-6 * std::abs(times[k]);
        const double t = std::stod(written);
        std::printf("beam.pvd DataSet %zu: file %s (expected %s), timestep \"%s\" = %.17g, "
                    "solver time %.17g, difference %.2e (tolerance %.2e)\n",
                    k, file.c_str(), expected, written.c_str(), t, times[k],
                    std::abs(t - times[k]), tol);
        EXPECT_EQ(file, expected);
        EXPECT_LE(std::abs(t - times[k]), tol);
    }
}

// Fibre directions in the output: per element F_e a0 / |F_e a0| and |F_e a0|
// for a homogeneous deformation F (u = (F - I) X) against the closed form
TEST(Output, VtuWritesFibreDirectionAndStretch)
{
    const TetMesh mesh = TetMesh::box(3, 2, 2, [](const Vec3& x) { return x; });
    ExplicitSolid solid(mesh, std::make_shared<HolzapfelGasserOgden>(1000.0, 0.0, 5000.0, 3.0, 2e4, 1000.0));
    std::vector<Vec3> a0(mesh.nElements());
    for (int e = 0; e < mesh.nElements(); ++e) a0[e] = Vec3(1.0, 0.1 * e, 0.3).normalized();
    solid.setFibreDirections(a0);
    Mat3 F;
    F << 1.3, 0.2, 0.0, -0.1, 0.9, 0.05, 0.0, 0.1, 1.1;
    solid.setInitialDisplacement([&](double, const Vec3& X) { return Vec3((F - Mat3::Identity()) * X); });
    VtuSeries vtu(test::tempDir() + "/fibreOutput", "solid");
    vtu.write(solid);
    const VtuFile f = readVtu(test::tempDir() + "/fibreOutput/solid_000000.vtu");
    const std::vector<double> dir = f.arrays.at("fibreDirection").as<double>();
    const std::vector<double> stretch = f.arrays.at("fibreStretch").as<double>();
    ASSERT_EQ(static_cast<int>(stretch.size()), mesh.nElements());
    double worst = 0;
    for (int e = 0; e < mesh.nElements(); ++e) {
        const Vec3 a = F * a0[e];
        worst = std::max({worst, std::abs(stretch[e] - a.norm()),
                          (Vec3(dir[3 * e], dir[3 * e + 1], dir[3 * e + 2]) - a.normalized()).norm()});
    }
    std::printf("fibreDirection, fibreStretch of %d elements against F a0: largest difference "
                "%.1e (tolerance 1e-12)\n", mesh.nElements(), worst);
    EXPECT_LT(worst, 1e-12);
    EXPECT_EQ(f.arrays.at("fibreDirection").section, "CellData");
}

// Files named by a caller's label (an OpenFOAM time name); a restarted run
// resumes the collection: data sets up to the restart time kept, later ones
// dropped, the new ones appended
TEST(Output, VtuSeriesLabelsAndResume)
{
    ExplicitSolid solid = smallBeam();
    const std::string dir = test::tempDir() + "/vtuResume";
    auto entries = [&] {
        std::ifstream is(dir + "/beam.pvd");
        std::vector<std::string> files;
        std::string line;
        while (std::getline(is, line)) {
            const auto f = line.find("file=\"");
            if (f != std::string::npos) files.push_back(line.substr(f + 6, line.find('"', f + 6) - f - 6));
        }
        return files;
    };
    {
        VtuSeries series(dir, "beam");
        series.write(solid, {}, "0.1", 0.1);
        series.write(solid, {}, "0.2", 0.2);
        series.write(solid, {}, "0.3", 0.3);
    }
    EXPECT_EQ(entries(), (std::vector<std::string>{"beam_0.1.vtu", "beam_0.2.vtu", "beam_0.3.vtu"}));
    {
        VtuSeries series(dir, "beam");
        series.resume(0.2);
        EXPECT_EQ(series.count(), 2);
        series.write(solid, {}, "0.25", 0.25);
    }
    EXPECT_EQ(entries(), (std::vector<std::string>{"beam_0.1.vtu", "beam_0.2.vtu", "beam_0.25.vtu"}));
    std::ifstream vtu(dir + "/beam_0.25.vtu");
    EXPECT_TRUE(vtu.good());

    // Not a collection: a clear error naming the file
    {
        std::ofstream bad(dir + "/other.pvd");
        bad << "something else\ntimestep=\"1\" file=\"x\"\n";
    }
    VtuSeries other(dir, "other");
    try {
        other.resume(1.0);
        ADD_FAILURE() << "no error for a file that is not a collection";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("other.pvd"), std::string::npos) << e.what();
    }
}
