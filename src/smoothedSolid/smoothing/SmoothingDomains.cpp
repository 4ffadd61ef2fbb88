#include "smoothing/SmoothingDomains.hpp"

#include <algorithm>
#include <cctype>

namespace smoothedSolid {

Formulation formulationFromString(const std::string& name)
{
    std::string s;
    for (char c : name) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (s == "fem-t4" || s == "fem") return Formulation::FEM_T4;
    if (s == "ns-fem" || s == "ns") return Formulation::NS_FEM;
    if (s == "fs-fem" || s == "fs") return Formulation::FS_FEM;
    if (s == "selective" || s == "fs/ns-fem") return Formulation::Selective;
    throw Error("unknown formulation '" + name +
                "': use FEM-T4, NS-FEM, FS-FEM or selective");
}

std::string toString(Formulation f)
{
    switch (f) {
        case Formulation::FEM_T4: return "FEM-T4";
        case Formulation::NS_FEM: return "NS-FEM";
        case Formulation::FS_FEM: return "FS-FEM";
        case Formulation::Selective: return "selective FS/NS-FEM";
    }
    return "?";
}

Eigen::Matrix<double, 4, 3> elementGradients(const TetMesh& mesh, int e)
{
    const auto& X = mesh.coordinates();
    const Tet& t = mesh.elements()[e];
    Mat3 J;  // columns: edges from node 0
    J.col(0) = X[t[1]] - X[t[0]];
    J.col(1) = X[t[2]] - X[t[0]];
    J.col(2) = X[t[3]] - X[t[0]];
    const Mat3 Jinv = J.inverse();  // rows: gradients of shape functions 1..3
    Eigen::Matrix<double, 4, 3> g;
    g.row(1) = Jinv.row(0);
    g.row(2) = Jinv.row(1);
    g.row(3) = Jinv.row(2);
    g.row(0) = -(g.row(1) + g.row(2) + g.row(3));
    return g;
}

namespace {

// Accumulates weighted element gradients into one domain, merging nodes
struct DomainBuilder {
    std::vector<int> nodes;
    std::vector<Vec3> grads;
    double volume = 0;

    void add(const TetMesh& mesh, int e, const Eigen::Matrix<double, 4, 3>& g, double w)
    {
        const Tet& t = mesh.elements()[e];
        for (int a = 0; a < 4; ++a) {
            auto it = std::find(nodes.begin(), nodes.end(), t[a]);
            if (it == nodes.end()) {
                nodes.push_back(t[a]);
                grads.push_back(w * g.row(a).transpose());
            } else {
                grads[it - nodes.begin()] += w * g.row(a).transpose();
            }
        }
        volume += w;
    }

    void flush(SmoothingDomains& sd)
    {
        for (std::size_t k = 0; k < nodes.size(); ++k) {
            sd.node.push_back(nodes[k]);
            sd.grad.push_back(grads[k] / volume);
        }
        sd.volume.push_back(volume);
        sd.start.push_back(static_cast<int>(sd.node.size()));
        nodes.clear();
        grads.clear();
        volume = 0;
    }
};

std::vector<Eigen::Matrix<double, 4, 3>> allGradients(const TetMesh& mesh)
{
    std::vector<Eigen::Matrix<double, 4, 3>> g(mesh.nElements());
    for (int e = 0; e < mesh.nElements(); ++e) g[e] = elementGradients(mesh, e);
    return g;
}

}  // namespace

SmoothingDomains elementDomains(const TetMesh& mesh)
{
    SmoothingDomains sd;
    DomainBuilder b;
    for (int e = 0; e < mesh.nElements(); ++e) {
        b.add(mesh, e, elementGradients(mesh, e), mesh.elementVolume(e));
        b.flush(sd);
    }
    return sd;
}

SmoothingDomains nodeDomains(const TetMesh& mesh)
{
    const auto g = allGradients(mesh);
    SmoothingDomains sd;
    DomainBuilder b;
    const auto& start = mesh.nodeElementStart();
    const auto& elems = mesh.nodeElements();
    for (int k = 0; k < mesh.nNodes(); ++k) {
        if (start[k] == start[k + 1]) {
            throw Error("node " + std::to_string(k) + " belongs to no element");
        }
        for (int i = start[k]; i < start[k + 1]; ++i) {
            const int e = elems[i];
            b.add(mesh, e, g[e], 0.25 * mesh.elementVolume(e));
        }
        b.flush(sd);
    }
    return sd;
}

SmoothingDomains faceDomains(const TetMesh& mesh)
{
    const auto g = allGradients(mesh);
    SmoothingDomains sd;
    DomainBuilder b;
    for (const Face& f : mesh.faces()) {
        b.add(mesh, f.owner, g[f.owner], 0.25 * mesh.elementVolume(f.owner));
        if (f.neighbour >= 0) {
            b.add(mesh, f.neighbour, g[f.neighbour], 0.25 * mesh.elementVolume(f.neighbour));
        }
        b.flush(sd);
    }
    return sd;
}

}  // namespace smoothedSolid
