// Linear tetrahedral mesh in the reference configuration (total Lagrangian),
// with named node, face and element sets and the face adjacency that the
// face-based smoothing domains need (paper Sect. 3.1).
#pragma once

#include "Types.hpp"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace smoothedSolid {

using Tet = std::array<int, 4>;
using Tri = std::array<int, 3>;

// A triangular face of the mesh. owner/neighbour: the elements on either
// side (neighbour -1 on the boundary); nodes ordered so that the normal
// (x1-x0)x(x2-x0) points out of the owner.
struct Face {
    Tri nodes;
    int owner;
    int neighbour;
};

class TetMesh {
public:
    // Build from coordinates and connectivity. Degenerate (zero volume)
    // elements throw; negatively oriented (inverted) ones throw too, unless
    // reorient is set, which swaps two of their nodes instead.
    TetMesh(std::vector<Vec3> coordinates, std::vector<Tet> elements, bool reorient = false);

    // Read linear tetrahedra (gmsh element type 4) through the gmsh API.
    // Physical groups become named sets: volumes -> element and node sets,
    // surfaces -> face and node sets, curves/points -> node sets.
    static TetMesh fromGmsh(const std::string& fileName);

    // Structured mesh of the unit cube [0,1]^3 split in nx*ny*nz hexahedra,
    // each into 6 tetrahedra, mapped by 'map'. Node sets xmin, xmax, ymin,
    // ymax, zmin, zmax and the same face sets are defined.
    template <class Map>
    static TetMesh box(int nx, int ny, int nz, Map map);

    int nNodes() const { return static_cast<int>(X_.size()); }
    int nElements() const { return static_cast<int>(tets_.size()); }
    const std::vector<Vec3>& coordinates() const { return X_; }
    const std::vector<Tet>& elements() const { return tets_; }
    const std::vector<Face>& faces() const { return faces_; }
    // The 4 faces of each element (indices into faces())
    const std::vector<std::array<int, 4>>& elementFaces() const { return elementFaces_; }
    // Indices into faces() of the boundary faces
    const std::vector<int>& boundaryFaces() const { return boundaryFaces_; }
    // Elements around each node (CSR)
    const std::vector<int>& nodeElementStart() const { return nodeElemStart_; }
    const std::vector<int>& nodeElements() const { return nodeElem_; }

    double elementVolume(int e) const;
    // Smallest height of element e (3 V / largest face area)
    double elementHeight(int e) const;

    // Named sets; unknown names throw, listing the names that exist.
    const std::vector<int>& nodeSet(const std::string& name) const;
    const std::vector<Tri>& faceSet(const std::string& name) const;
    const std::vector<int>& elementSet(const std::string& name) const;
    bool hasNodeSet(const std::string& name) const { return nodeSets_.count(name) > 0; }
    std::vector<std::string> nodeSetNames() const;

    void addNodeSet(const std::string& name, std::vector<int> nodes);
    // Triangles must be boundary faces; they are oriented outward.
    void addFaceSet(const std::string& name, const std::vector<Tri>& tris);
    void addElementSet(const std::string& name, std::vector<int> elements);

    // Parts: connected components of the element graph (through faces)
    const std::vector<int>& elementPart() const { return elementPart_; }
    int nParts() const { return nParts_; }

private:
    void build();

    std::vector<Vec3> X_;
    std::vector<Tet> tets_;
    std::vector<Face> faces_;
    std::vector<int> boundaryFaces_;
    std::vector<std::array<int, 4>> elementFaces_;
    std::vector<int> nodeElemStart_, nodeElem_;
    std::vector<int> elementPart_;
    int nParts_ = 0;
    std::map<std::string, std::vector<int>> nodeSets_;
    std::map<std::string, std::vector<Tri>> faceSets_;
    std::map<std::string, std::vector<int>> elementSets_;
};

// gmsh is a process-wide library: initialise it once (also for callers that
// use the gmsh API themselves next to this library)
void initializeGmsh();

// ---------------------------------------------------------------------------

template <class Map>
TetMesh TetMesh::box(int nx, int ny, int nz, Map map)
{
    if (nx < 1 || ny < 1 || nz < 1) {
        throw Error("TetMesh::box: cell counts must be positive");
    }
    auto id = [=](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
    std::vector<Vec3> X;
    X.reserve(static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1)));
    for (int k = 0; k <= nz; ++k) {
        for (int j = 0; j <= ny; ++j) {
            for (int i = 0; i <= nx; ++i) {
                X.push_back(map(Vec3(double(i) / nx, double(j) / ny, double(k) / nz)));
            }
        }
    }
    // Kuhn (Freudenthal) split of each hexahedron along its main diagonal:
    // conforming between neighbouring hexahedra
    static const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                    {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    std::vector<Tet> tets;
    tets.reserve(static_cast<std::size_t>(6 * nx * ny * nz));
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                for (const auto& p : paths) {
                    int c[3] = {i, j, k};
                    Tet t;
                    t[0] = id(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[p[s]];
                        t[s + 1] = id(c[0], c[1], c[2]);
                    }
                    tets.push_back(t);
                }
            }
        }
    }
    TetMesh mesh(std::move(X), std::move(tets), true);

    const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    const int n[3] = {nx, ny, nz};
    for (int d = 0; d < 3; ++d) {
        for (int side = 0; side < 2; ++side) {
            std::vector<int> nodes;
            for (int k = 0; k <= nz; ++k) {
                for (int j = 0; j <= ny; ++j) {
                    for (int i = 0; i <= nx; ++i) {
                        const int c[3] = {i, j, k};
                        if (c[d] == side * n[d]) nodes.push_back(id(i, j, k));
                    }
                }
            }
            std::vector<char> on(mesh.nNodes(), 0);
            for (int v : nodes) on[v] = 1;
            std::vector<Tri> tris;
            for (int f : mesh.boundaryFaces()) {
                const Tri& t = mesh.faces()[f].nodes;
                if (on[t[0]] && on[t[1]] && on[t[2]]) tris.push_back(t);
            }
            mesh.addNodeSet(names[2 * d + side], nodes);
            mesh.addFaceSet(names[2 * d + side], tris);
        }
    }
    return mesh;
}

}  // namespace smoothedSolid
