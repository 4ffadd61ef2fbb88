#include "mesh/TetMesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <fstream>
#include <mutex>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace smoothedSolid {

namespace {

double signedVolume(const std::vector<Vec3>& X, const Tet& t)
{
    return (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]).dot(X[t[3]] - X[t[0]]) / 6.0;
}

// Local faces of a tet, each ordered so that its normal points outward for
// a positively oriented tet
constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

std::uint64_t faceKey(Tri t)
{
    std::sort(t.begin(), t.end());
    return (std::uint64_t(t[0]) << 42) ^ (std::uint64_t(t[1]) << 21) ^ std::uint64_t(t[2]);
}

template <class M>
std::string namesOf(const M& m)
{
    std::string s;
    for (const auto& kv : m) s += (s.empty() ? "" : ", ") + kv.first;
    return s.empty() ? "(none)" : s;
}

}  // namespace

TetMesh::TetMesh(std::vector<Vec3> coordinates, std::vector<Tet> elements, bool reorient)
    : X_(std::move(coordinates)), tets_(std::move(elements))
{
    if (tets_.empty()) throw Error("TetMesh: no tetrahedra");
    const int n = nNodes();
    for (std::size_t e = 0; e < tets_.size(); ++e) {
        for (int v : tets_[e]) {
            if (v < 0 || v >= n) {
                throw Error("TetMesh: element " + std::to_string(e) + " refers to node " +
                            std::to_string(v) + ", outside 0.." + std::to_string(n - 1));
            }
        }
    }
    // Characteristic size for the degeneracy test
    Vec3 lo = X_[0], hi = X_[0];
    for (const Vec3& x : X_) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    const double L = (hi - lo).norm();
    for (std::size_t e = 0; e < tets_.size(); ++e) {
        const double v = signedVolume(X_, tets_[e]);
        if (std::abs(v) <= 1e-14 * L * L * L) {
            throw Error("TetMesh: element " + std::to_string(e) +
                        " has zero volume (degenerate); fix or remesh the geometry");
        }
        if (v < 0) {
            if (!reorient) {
                throw Error("TetMesh: element " + std::to_string(e) +
                            " is inverted (negative volume " + std::to_string(v) +
                            "); check the node order of the mesh");
            }
            std::swap(tets_[e][2], tets_[e][3]);
        }
    }
    build();
}

void TetMesh::build()
{
    const int ne = nElements();
    const int nn = nNodes();

    // Faces and adjacency
    std::unordered_map<std::uint64_t, int> index;
    index.reserve(static_cast<std::size_t>(ne) * 3);
    faces_.clear();
    elementFaces_.assign(ne, {-1, -1, -1, -1});
    for (int e = 0; e < ne; ++e) {
        for (int l = 0; l < 4; ++l) {
            const auto& lf = kTetFaces[l];
            const Tri t{tets_[e][lf[0]], tets_[e][lf[1]], tets_[e][lf[2]]};
            const auto key = faceKey(t);
            auto it = index.find(key);
            if (it == index.end()) {
                elementFaces_[e][l] = static_cast<int>(faces_.size());
                index.emplace(key, static_cast<int>(faces_.size()));
                faces_.push_back({t, e, -1});
            } else {
                elementFaces_[e][l] = it->second;
                Face& f = faces_[it->second];
                if (f.neighbour >= 0) {
                    throw Error("TetMesh: a face of element " + std::to_string(e) +
                                " is shared by more than two elements (non-manifold mesh)");
                }
                f.neighbour = e;
            }
        }
    }
    boundaryFaces_.clear();
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
        if (faces_[f].neighbour < 0) boundaryFaces_.push_back(f);
    }

    // Node -> elements
    nodeElemStart_.assign(nn + 1, 0);
    for (const Tet& t : tets_) {
        for (int v : t) ++nodeElemStart_[v + 1];
    }
    std::partial_sum(nodeElemStart_.begin(), nodeElemStart_.end(), nodeElemStart_.begin());
    nodeElem_.resize(nodeElemStart_.back());
    std::vector<int> fill(nodeElemStart_.begin(), nodeElemStart_.end() - 1);
    for (int e = 0; e < ne; ++e) {
        for (int v : tets_[e]) nodeElem_[fill[v]++] = e;
    }

    // Parts: connected components through faces
    elementPart_.assign(ne, -1);
    std::vector<std::vector<int>> nbr(ne);
    for (const Face& f : faces_) {
        if (f.neighbour >= 0) {
            nbr[f.owner].push_back(f.neighbour);
            nbr[f.neighbour].push_back(f.owner);
        }
    }
    nParts_ = 0;
    std::vector<int> stack;
    for (int e = 0; e < ne; ++e) {
        if (elementPart_[e] >= 0) continue;
        elementPart_[e] = nParts_;
        stack.push_back(e);
        while (!stack.empty()) {
            const int c = stack.back();
            stack.pop_back();
            for (int d : nbr[c]) {
                if (elementPart_[d] < 0) {
                    elementPart_[d] = nParts_;
                    stack.push_back(d);
                }
            }
        }
        ++nParts_;
    }
}

double TetMesh::elementVolume(int e) const { return signedVolume(X_, tets_[e]); }

double TetMesh::elementHeight(int e) const
{
    const Tet& t = tets_[e];
    double maxArea = 0;
    for (const auto& lf : kTetFaces) {
        const double a = 0.5 * (X_[t[lf[1]]] - X_[t[lf[0]]])
                                   .cross(X_[t[lf[2]]] - X_[t[lf[0]]])
                                   .norm();
        maxArea = std::max(maxArea, a);
    }
    return 3.0 * elementVolume(e) / maxArea;
}

const std::vector<int>& TetMesh::nodeSet(const std::string& name) const
{
    auto it = nodeSets_.find(name);
    if (it == nodeSets_.end()) {
        throw Error("unknown node set '" + name + "'; the mesh has: " + namesOf(nodeSets_));
    }
    return it->second;
}

const std::vector<Tri>& TetMesh::faceSet(const std::string& name) const
{
    auto it = faceSets_.find(name);
    if (it == faceSets_.end()) {
        throw Error("unknown face set '" + name + "'; the mesh has: " + namesOf(faceSets_));
    }
    return it->second;
}

const std::vector<int>& TetMesh::elementSet(const std::string& name) const
{
    auto it = elementSets_.find(name);
    if (it == elementSets_.end()) {
        throw Error("unknown element set '" + name + "'; the mesh has: " +
                    namesOf(elementSets_));
    }
    return it->second;
}

std::vector<std::string> TetMesh::nodeSetNames() const
{
    std::vector<std::string> names;
    for (const auto& kv : nodeSets_) names.push_back(kv.first);
    return names;
}

void TetMesh::addNodeSet(const std::string& name, std::vector<int> nodes)
{
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (int v : nodes) {
        if (v < 0 || v >= nNodes()) {
            throw Error("node set '" + name + "': node " + std::to_string(v) + " out of range");
        }
    }
    nodeSets_[name] = std::move(nodes);
}

void TetMesh::addFaceSet(const std::string& name, const std::vector<Tri>& tris)
{
    std::unordered_map<std::uint64_t, int> boundary;
    for (int f : boundaryFaces_) boundary.emplace(faceKey(faces_[f].nodes), f);
    std::vector<Tri> oriented;
    oriented.reserve(tris.size());
    for (const Tri& t : tris) {
        auto it = boundary.find(faceKey(t));
        if (it == boundary.end()) {
            throw Error("face set '" + name + "': triangle (" + std::to_string(t[0]) + " " +
                        std::to_string(t[1]) + " " + std::to_string(t[2]) +
                        ") is not a boundary face of the tetrahedra");
        }
        oriented.push_back(faces_[it->second].nodes);
    }
    faceSets_[name] = std::move(oriented);
}

void TetMesh::addElementSet(const std::string& name, std::vector<int> elements)
{
    for (int e : elements) {
        if (e < 0 || e >= nElements()) {
            throw Error("element set '" + name + "': element " + std::to_string(e) +
                        " out of range");
        }
    }
    elementSets_[name] = std::move(elements);
}

// ---------------------------------------------------------------------------

namespace {

// Clear the model after use
struct GmshSession {
    GmshSession()
    {
        initializeGmsh();
        gmsh::clear();
    }
    ~GmshSession() { gmsh::clear(); }
};

}  // namespace

void initializeGmsh()
{
    static std::once_flag once;
    std::call_once(once, [] {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
    });
}

TetMesh TetMesh::fromGmsh(const std::string& fileName)
{
    {
        std::ifstream probe(fileName);
        if (!probe) {
            throw Error("cannot open mesh file '" + fileName +
                        "': check the path (relative paths are from the working directory)");
        }
    }
    GmshSession session;
    // A failed read can leave gmsh's global state unusable for the next
    // file: start gmsh afresh after one
    auto restartGmsh = [] {
        gmsh::finalize();
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
    };
    try {
        gmsh::open(fileName);
    } catch (const std::exception& ex) {
        restartGmsh();
        throw Error("gmsh could not read '" + fileName + "': " + ex.what());
    } catch (...) {
        restartGmsh();
        throw Error("gmsh could not read '" + fileName + "' (corrupt or not a mesh file)");
    }

    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, false, false);
    if (tags.empty()) {
        throw Error("'" + fileName + "' holds no mesh nodes: mesh it first (gmsh -3)");
    }
    std::unordered_map<std::size_t, int> local;
    std::vector<Vec3> X(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i) {
        local.emplace(tags[i], static_cast<int>(i));
        X[i] = Vec3(coord[3 * i], coord[3 * i + 1], coord[3 * i + 2]);
    }
    auto toLocal = [&](std::size_t tag) {
        auto it = local.find(tag);
        if (it == local.end()) {
            throw Error("'" + fileName + "': element refers to unknown node " +
                        std::to_string(tag));
        }
        return it->second;
    };

    // Linear tets, remembering which volume entity each came from
    std::vector<Tet> tets;
    std::map<int, std::vector<int>> entityTets;
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    for (const auto& [dim, tag] : volumes) {
        std::vector<std::size_t> elemTags, nodeTags;
        gmsh::model::mesh::getElementsByType(4, elemTags, nodeTags, tag);
        for (std::size_t e = 0; e < elemTags.size(); ++e) {
            entityTets[tag].push_back(static_cast<int>(tets.size()));
            tets.push_back({toLocal(nodeTags[4 * e]), toLocal(nodeTags[4 * e + 1]),
                            toLocal(nodeTags[4 * e + 2]), toLocal(nodeTags[4 * e + 3])});
        }
    }
    if (tets.empty()) {
        throw Error("'" + fileName +
                    "' has no linear tetrahedra (gmsh element type 4): mesh the volume "
                    "with first-order tets (gmsh -3, Mesh.ElementOrder = 1)");
    }

    // Keep only nodes used by tets (drop geometry-only points)
    std::vector<int> renumber(X.size(), -1);
    std::vector<Vec3> used;
    for (Tet& t : tets) {
        for (int& v : t) {
            if (renumber[v] < 0) {
                renumber[v] = static_cast<int>(used.size());
                used.push_back(X[v]);
            }
            v = renumber[v];
        }
    }
    TetMesh mesh(std::move(used), std::move(tets));

    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    for (const auto& [dim, tag] : groups) {
        std::string name;
        gmsh::model::getPhysicalName(dim, tag, name);
        if (name.empty()) name = std::to_string(dim) + "_" + std::to_string(tag);

        std::vector<std::size_t> nodeTags;
        std::vector<double> c;
        gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, nodeTags, c);
        std::vector<int> nodes;
        for (std::size_t t : nodeTags) {
            const int v = renumber[toLocal(t)];
            if (v >= 0) nodes.push_back(v);
        }
        mesh.addNodeSet(name, nodes);

        std::vector<int> entities;
        gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
        if (dim == 3) {
            std::vector<int> elems;
            for (int ent : entities) {
                const auto& v = entityTets[ent];
                elems.insert(elems.end(), v.begin(), v.end());
            }
            mesh.addElementSet(name, elems);
        } else if (dim == 2) {
            std::vector<Tri> tris;
            for (int ent : entities) {
                std::vector<std::size_t> elemTags, triNodes;
                gmsh::model::mesh::getElementsByType(2, elemTags, triNodes, ent);
                for (std::size_t e = 0; e < elemTags.size(); ++e) {
                    tris.push_back({renumber[toLocal(triNodes[3 * e])],
                                    renumber[toLocal(triNodes[3 * e + 1])],
                                    renumber[toLocal(triNodes[3 * e + 2])]});
                }
            }
            try {
                mesh.addFaceSet(name, tris);
            } catch (const Error& ex) {
                throw Error("'" + fileName + "', physical surface '" + name + "': " + ex.what());
            }
        }
    }
    return mesh;
}

}  // namespace smoothedSolid
