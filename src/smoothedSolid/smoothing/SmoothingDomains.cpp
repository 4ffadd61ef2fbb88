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

}  // namespace

std::vector<DomainUse> domainUses(Formulation f)
{
    switch (f) {
        case Formulation::FEM_T4: return {{DomainKind::Element, StressPart::Full}};
        case Formulation::NS_FEM: return {{DomainKind::Node, StressPart::Full}};
        case Formulation::FS_FEM: return {{DomainKind::Face, StressPart::Full}};
        case Formulation::Selective:
            return {{DomainKind::Face, StressPart::Deviatoric},
                    {DomainKind::Node, StressPart::Volumetric}};
    }
    return {};
}

Smoothing::Smoothing(const TetMesh& mesh)
    : Smoothing(std::shared_ptr<const TetMesh>(&mesh, [](const TetMesh*) {}))
{
}

Smoothing::Smoothing(std::shared_ptr<const TetMesh> meshPtr) : mesh_(std::move(meshPtr))
{
    const TetMesh& mesh = *mesh_;
    const int ne = mesh.nElements();
    const int nn = mesh.nNodes();
    elemGrad_.resize(ne);
    quarterVolume_.resize(ne);
    for (int e = 0; e < ne; ++e) {
        elemGrad_[e] = elementGradients(mesh, e);
        quarterVolume_[e] = 0.25 * mesh.elementVolume(e);
    }
    const auto& faces = mesh.faces();
    faceWeight_.resize(faces.size());
    faceVolume_.resize(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Face& fc = faces[f];
        const double vo = quarterVolume_[fc.owner];
        const double vn = fc.neighbour >= 0 ? quarterVolume_[fc.neighbour] : 0.0;
        faceWeight_[f] = {vo / (vo + vn), vn / (vo + vn)};
        faceVolume_[f] = vo + vn;
    }
    const auto& start = mesh.nodeElementStart();
    const auto& elems = mesh.nodeElements();
    nodeWeight_.resize(elems.size());
    nodeLocal_.resize(elems.size());
    nodeVolume_.assign(nn, 0.0);
    for (int k = 0; k < nn; ++k) {
        if (start[k] == start[k + 1]) {
            throw Error("node " + std::to_string(k) + " belongs to no element");
        }
        double V = 0;
        for (int i = start[k]; i < start[k + 1]; ++i) V += quarterVolume_[elems[i]];
        nodeVolume_[k] = V;
        for (int i = start[k]; i < start[k + 1]; ++i) {
            nodeWeight_[i] = quarterVolume_[elems[i]] / V;
            const Tet& t = mesh.elements()[elems[i]];
            nodeLocal_[i] = static_cast<std::uint8_t>(std::find(t.begin(), t.end(), k) - t.begin());
        }
    }
}

int Smoothing::size(DomainKind kind) const
{
    switch (kind) {
        case DomainKind::Element: return mesh_->nElements();
        case DomainKind::Face: return static_cast<int>(faceVolume_.size());
        case DomainKind::Node: return mesh_->nNodes();
    }
    return 0;
}

double Smoothing::volume(DomainKind kind, int d) const
{
    switch (kind) {
        case DomainKind::Element: return 4.0 * quarterVolume_[d];
        case DomainKind::Face: return faceVolume_[d];
        case DomainKind::Node: return nodeVolume_[d];
    }
    return 0;
}

void Smoothing::elementF(const std::vector<Vec3>& u, std::vector<Mat3>& Fe) const
{
    const auto& tets = mesh_->elements();
    const int ne = mesh_->nElements();
    Fe.resize(ne);
#pragma omp parallel for schedule(static)
    for (int e = 0; e < ne; ++e) {
        const Tet& t = tets[e];
        const Gradients& g = elemGrad_[e];
        Mat3 F = Mat3::Identity();
        for (int a = 0; a < 4; ++a) F.noalias() += u[t[a]] * g.row(a);
        Fe[e] = F;
    }
}

Mat3 Smoothing::domainF(DomainKind kind, int d, const std::vector<Mat3>& Fe) const
{
    switch (kind) {
        case DomainKind::Element: return Fe[d];
        case DomainKind::Face: {
            const Face& fc = mesh_->faces()[d];
            const auto& w = faceWeight_[d];
            Mat3 F = w[0] * Fe[fc.owner];
            if (fc.neighbour >= 0) F.noalias() += w[1] * Fe[fc.neighbour];
            return F;
        }
        case DomainKind::Node: {
            const auto& start = mesh_->nodeElementStart();
            const auto& elems = mesh_->nodeElements();
            Mat3 F = Mat3::Zero();
            for (int i = start[d]; i < start[d + 1]; ++i) F.noalias() += nodeWeight_[i] * Fe[elems[i]];
            return F;
        }
    }
    return Mat3::Identity();
}

void Smoothing::domainF(DomainKind kind, const std::vector<Mat3>& Fe, std::vector<Mat3>& Fd) const
{
    const int n = size(kind);
    Fd.resize(n);
#pragma omp parallel for schedule(static)
    for (int d = 0; d < n; ++d) Fd[d] = domainF(kind, d, Fe);
}

void Smoothing::domainDirections(DomainKind kind, const std::vector<Vec3>& a,
                                 std::vector<Vec3>& ad) const
{
    if (static_cast<int>(a.size()) != mesh_->nElements()) {
        throw Error("domainDirections: " + std::to_string(a.size()) + " directions for " +
                    std::to_string(mesh_->nElements()) + " elements");
    }
    const int n = size(kind);
    ad.resize(n);
    // sign-aligned weighted sum over (element, weight) pairs, reference: the
    // heaviest element (the first of equal ones)
    auto combine = [&](auto forEach) {
        int ref = -1;
        double wRef = -1;
        forEach([&](int e, double w) {
            if (w > wRef) wRef = w, ref = e;
        });
        Vec3 s = Vec3::Zero();
        forEach([&](int e, double w) { s += (a[e].dot(a[ref]) < 0 ? -w : w) * a[e]; });
        return Vec3(s.normalized());
    };
    const auto& faces = mesh_->faces();
    const auto& start = mesh_->nodeElementStart();
    const auto& elems = mesh_->nodeElements();
    for (int d = 0; d < n; ++d) {
        switch (kind) {
            case DomainKind::Element: ad[d] = a[d]; break;
            case DomainKind::Face:
                ad[d] = combine([&](auto f) {
                    f(faces[d].owner, faceWeight_[d][0]);
                    if (faces[d].neighbour >= 0) f(faces[d].neighbour, faceWeight_[d][1]);
                });
                break;
            case DomainKind::Node:
                ad[d] = combine([&](auto f) {
                    for (int i = start[d]; i < start[d + 1]; ++i) f(elems[i], nodeWeight_[i]);
                });
                break;
        }
    }
}

void Smoothing::gatherForce(const std::vector<Mat3>& Pbar, std::vector<Vec3>& f) const
{
    const int nn = mesh_->nNodes();
    f.resize(nn);
    const auto& start = mesh_->nodeElementStart();
    const auto& elems = mesh_->nodeElements();
#pragma omp parallel for schedule(static)
    for (int k = 0; k < nn; ++k) {
        Vec3 fk = Vec3::Zero();
        for (int i = start[k]; i < start[k + 1]; ++i) {
            const int e = elems[i];
            fk.noalias() += Pbar[e] * elemGrad_[e].row(nodeLocal_[i]).transpose();
        }
        f[k] = fk;
    }
}

// The merged view: each domain's nodes with the weighted sum of its
// elements' gradients, b_I = sum_e w_e g_eI (the weights above)
SmoothingDomains Smoothing::merged(DomainKind kind) const
{
    SmoothingDomains sd;
    DomainBuilder b;
    const TetMesh& mesh = *mesh_;
    auto add = [&](int e, double vol) { b.add(mesh, e, elemGrad_[e], vol); };
    switch (kind) {
        case DomainKind::Element:
            for (int e = 0; e < mesh.nElements(); ++e) {
                add(e, 4.0 * quarterVolume_[e]);
                b.flush(sd);
            }
            break;
        case DomainKind::Face:
            for (const Face& f : mesh.faces()) {
                add(f.owner, quarterVolume_[f.owner]);
                if (f.neighbour >= 0) add(f.neighbour, quarterVolume_[f.neighbour]);
                b.flush(sd);
            }
            break;
        case DomainKind::Node: {
            const auto& start = mesh.nodeElementStart();
            const auto& elems = mesh.nodeElements();
            for (int k = 0; k < mesh.nNodes(); ++k) {
                for (int i = start[k]; i < start[k + 1]; ++i) add(elems[i], quarterVolume_[elems[i]]);
                b.flush(sd);
            }
            break;
        }
    }
    return sd;
}

SmoothingDomains elementDomains(const TetMesh& mesh)
{
    return Smoothing(mesh).merged(DomainKind::Element);
}

SmoothingDomains nodeDomains(const TetMesh& mesh)
{
    return Smoothing(mesh).merged(DomainKind::Node);
}

SmoothingDomains faceDomains(const TetMesh& mesh)
{
    return Smoothing(mesh).merged(DomainKind::Face);
}

}  // namespace smoothedSolid
