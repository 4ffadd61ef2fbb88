// Smoothing domains in the reference configuration and their smoothed shape
// function gradients (paper Eqs. 20-23).
//
// With the Heaviside smoothing function (Eq. 21) the smoothed gradient of a
// domain is the boundary integral of Eq. 22. For linear tetrahedra, whose
// shape function gradients are constant per element, that boundary integral
// equals the volume-weighted average of the element gradients over the parts
// of the elements that make up the domain:
//   node-based (NS-FEM): domain of node k = 1/4 of every element around k;
//   face-based (FS-FEM): domain of face f = 1/4 of each of the (one or two)
//                        elements sharing f;
//   element (FEM-T4):    the element itself.
// This is what is built here; the patch test checks it.
//
// One representation: class Smoothing holds that element-wise data (element
// gradients, quarter volumes, the weights of each element in each face and
// node domain). The internal force, the strain energy, the stress output
// and the stable time step bound of ExplicitSolid all take their domain
// deformation gradients from it (F_domain = sum_e w_e F_e). The merged,
// per-node view of a domain (SmoothingDomains below: its nodes and smoothed
// gradients b_I) is built from the same weights; the stable step bound uses
// the norms of its gradients and the patch test checks both views agree.
#pragma once

#include "mesh/TetMesh.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace smoothedSolid {

enum class Formulation { FEM_T4, NS_FEM, FS_FEM, Selective };

// Parse "FEM-T4", "NS-FEM", "FS-FEM", "selective" (case-insensitive)
Formulation formulationFromString(const std::string& name);
std::string toString(Formulation f);

// A set of smoothing domains, stored CSR-like: domain d supports nodes
// node[start[d] .. start[d+1]) with smoothed gradients grad[...] (d Phi/d X).
struct SmoothingDomains {
    std::vector<int> start{0};
    std::vector<int> node;
    std::vector<Vec3> grad;
    std::vector<double> volume;

    int size() const { return static_cast<int>(volume.size()); }

    // Smoothed deformation gradient F = I + sum_I u_I (x) b_I (Eq. 23)
    Mat3 deformationGradient(int d, const std::vector<Vec3>& u) const
    {
        Mat3 F = Mat3::Identity();
        for (int k = start[d]; k < start[d + 1]; ++k) F += u[node[k]] * grad[k].transpose();
        return F;
    }
};

// Which smoothing domains a formulation integrates over, and which part of
// the stress each carries (selective: deviatoric on faces, volumetric on
// nodes, Sect. 3.2)
enum class DomainKind { Element, Face, Node };
enum class StressPart { Full, Deviatoric, Volumetric };
struct DomainUse {
    DomainKind kind;
    StressPart part;
};
std::vector<DomainUse> domainUses(Formulation f);

class Smoothing {
public:
    using Gradients = Eigen::Matrix<double, 4, 3>;

    explicit Smoothing(std::shared_ptr<const TetMesh> mesh);
    // Non-owning: the mesh must outlive this object
    explicit Smoothing(const TetMesh& mesh);

    const TetMesh& mesh() const { return *mesh_; }
    int size(DomainKind kind) const;
    double volume(DomainKind kind, int d) const;

    // Element deformation gradients F_e = I + sum_a u_a (x) g_ea (parallel)
    void elementF(const std::vector<Vec3>& u, std::vector<Mat3>& Fe) const;
    // Smoothed F of domain d: weighted mean of the F_e of its elements (Eq. 23)
    Mat3 domainF(DomainKind kind, int d, const std::vector<Mat3>& Fe) const;
    // All domains of a kind (parallel)
    void domainF(DomainKind kind, const std::vector<Mat3>& Fe, std::vector<Mat3>& Fd) const;

    const Gradients& gradients(int e) const { return elemGrad_[e]; }
    double quarterVolume(int e) const { return quarterVolume_[e]; }

    // One unit direction per domain from unit directions per element (e.g.
    // fibre directions, referential): the domain's elements in the weights
    // of Eq. 23 (their volumes in it), each flipped if needed to point the
    // way of the domain's heaviest element (directions are axes: a and -a
    // are the same fibre), summed and normalised,
    //   a_d = s_d / |s_d|,  s_d = sum_e w_e sign(a_e . a_ref) a_e.
    // s_d . a_ref >= w_ref > 0, so s_d never vanishes.
    void domainDirections(DomainKind kind, const std::vector<Vec3>& perElement,
                          std::vector<Vec3>& perDomain) const;

    // f_I = sum_{e around I} Pbar_e g_eI (gather form, parallel)
    void gatherForce(const std::vector<Mat3>& Pbar, std::vector<Vec3>& f) const;

    // The merged per-node view of the domains of a kind
    SmoothingDomains merged(DomainKind kind) const;

private:
    std::shared_ptr<const TetMesh> mesh_;
    std::vector<Gradients> elemGrad_;
    std::vector<double> quarterVolume_;              // V_e/4
    std::vector<std::array<double, 2>> faceWeight_;  // owner, neighbour
    std::vector<double> nodeWeight_;                 // per mesh.nodeElements() entry
    std::vector<std::uint8_t> nodeLocal_;            // per mesh.nodeElements() entry
    std::vector<double> faceVolume_, nodeVolume_;
};

SmoothingDomains elementDomains(const TetMesh& mesh);
SmoothingDomains nodeDomains(const TetMesh& mesh);
SmoothingDomains faceDomains(const TetMesh& mesh);

// Shape function gradients of element e (rows: local nodes)
Eigen::Matrix<double, 4, 3> elementGradients(const TetMesh& mesh, int e);

}  // namespace smoothedSolid
