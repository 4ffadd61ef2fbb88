#include "io/SurfaceFile.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>
#include <unordered_map>

namespace smoothedSolid {

namespace {

// Merges equal vertices into RigidSurface points
class Builder {
public:
    explicit Builder(std::string file) : file_(std::move(file)) {}
    int vertex(const Vec3& x)
    {
        const auto key = std::make_tuple(x.x(), x.y(), x.z());
        auto it = index_.find(key);
        if (it != index_.end()) return it->second;
        const int i = static_cast<int>(s_.points.size());
        s_.points.push_back(x);
        index_.emplace(key, i);
        return i;
    }
    void triangle(const Vec3& a, const Vec3& b, const Vec3& c)
    {
        s_.triangles.push_back({vertex(a), vertex(b), vertex(c)});
    }
    RigidSurface finish(bool flip)
    {
        if (s_.triangles.empty()) {
            throw Error("surface file '" + file_ +
                        "' holds no triangles: give a triangulated surface (STL facets, or "
                        "gmsh 3-node triangles: mesh it with gmsh -2)");
        }
        for (std::size_t t = 0; t < s_.triangles.size(); ++t) {
            Tri& tr = s_.triangles[t];
            const Vec3& x0 = s_.points[tr[0]];
            const double A = (s_.points[tr[1]] - x0).cross(s_.points[tr[2]] - x0).norm();
            if (!(A > 0) || !std::isfinite(A)) {
                throw Error("surface file '" + file_ + "': triangle " + std::to_string(t) +
                            " is degenerate (zero area or non-finite coordinates)");
            }
            if (flip) std::swap(tr[1], tr[2]);
        }
        return std::move(s_);
    }

private:
    std::string file_;
    RigidSurface s_;
    std::map<std::tuple<double, double, double>, int> index_;
};

RigidSurface readStl(const std::string& file, bool flip)
{
    std::ifstream is(file, std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
    if (!is.eof() && is.fail()) throw Error("cannot read surface file '" + file + "'");
    Builder b(file);
    std::uint32_t n = 0;
    if (data.size() >= 84) std::memcpy(&n, data.data() + 80, 4);
    if (data.size() >= 84 && data.size() == 84 + 50 * std::uint64_t(n)) {
        // binary: 80-byte header, count, per facet 12 floats + 2 bytes
        for (std::uint32_t t = 0; t < n; ++t) {
            float v[12];
            std::memcpy(v, data.data() + 84 + 50 * std::size_t(t), sizeof v);
            b.triangle(Vec3(v[3], v[4], v[5]), Vec3(v[6], v[7], v[8]), Vec3(v[9], v[10], v[11]));
        }
        return b.finish(flip);
    }
    // ASCII: solid name / facet normal nx ny nz / outer loop / vertex x y z (x3)
    // / endloop / endfacet / endsolid
    std::istringstream in(data);
    std::string word;
    if (!(in >> word) || word != "solid") {
        throw Error("surface file '" + file +
                    "' is not an STL file (neither ASCII, starting with 'solid', nor binary of "
                    "84 + 50 n bytes)");
    }
    std::vector<Vec3> loop;
    int line = 0;  // facets read, for messages
    while (in >> word) {
        if (word == "vertex") {
            Vec3 x;
            if (!(in >> x.x() >> x.y() >> x.z())) {
                throw Error("surface file '" + file + "': facet " + std::to_string(line) +
                            ": 'vertex' needs three numbers");
            }
            loop.push_back(x);
        } else if (word == "endloop") {
            if (loop.size() != 3) {
                throw Error("surface file '" + file + "': facet " + std::to_string(line) +
                            " has " + std::to_string(loop.size()) +
                            " vertices; STL facets are triangles");
            }
            b.triangle(loop[0], loop[1], loop[2]);
            loop.clear();
            ++line;
        }
    }
    if (!loop.empty()) {
        throw Error("surface file '" + file + "': facet " + std::to_string(line) +
                    " has no 'endloop' (the file is cut short?)");
    }
    return b.finish(flip);
}

RigidSurface readMsh(const std::string& file, bool flip)
{
    initializeGmsh();
    gmsh::clear();
    struct Clear {
        ~Clear() { gmsh::clear(); }
    } clear;
    try {
        gmsh::open(file);
    } catch (...) {
        // a failed read can leave gmsh unusable: start it afresh
        gmsh::finalize();
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        throw Error("gmsh could not read surface file '" + file + "' (corrupt or not a mesh file)");
    }
    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, false, false);
    std::unordered_map<std::size_t, Vec3> X;
    for (std::size_t i = 0; i < tags.size(); ++i) {
        X.emplace(tags[i], Vec3(coord[3 * i], coord[3 * i + 1], coord[3 * i + 2]));
    }
    std::vector<std::size_t> elemTags, nodeTags;
    gmsh::model::mesh::getElementsByType(2, elemTags, nodeTags, -1);
    Builder b(file);
    for (std::size_t e = 0; e < elemTags.size(); ++e) {
        Vec3 x[3];
        for (int k = 0; k < 3; ++k) {
            auto it = X.find(nodeTags[3 * e + k]);
            if (it == X.end()) {
                throw Error("surface file '" + file + "': triangle " + std::to_string(elemTags[e]) +
                            " refers to unknown node " + std::to_string(nodeTags[3 * e + k]));
            }
            x[k] = it->second;
        }
        b.triangle(x[0], x[1], x[2]);
    }
    return b.finish(flip);
}

}  // namespace

RigidSurface readRigidSurface(const std::string& fileName, bool flip)
{
    {
        std::ifstream probe(fileName);
        if (!probe) {
            throw Error("cannot open surface file '" + fileName +
                        "': check the path (case files: relative to the case directory)");
        }
    }
    std::string ext = std::filesystem::path(fileName).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".stl") return readStl(fileName, flip);
    if (ext == ".msh") return readMsh(fileName, flip);
    throw Error("surface file '" + fileName + "': unknown extension '" + ext +
                "'; give an STL (.stl, ASCII or binary) or gmsh (.msh) surface");
}

}  // namespace smoothedSolid
