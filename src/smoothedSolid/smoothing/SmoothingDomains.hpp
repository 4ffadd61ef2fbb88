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
#pragma once

#include "mesh/TetMesh.hpp"

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

SmoothingDomains elementDomains(const TetMesh& mesh);
SmoothingDomains nodeDomains(const TetMesh& mesh);
SmoothingDomains faceDomains(const TetMesh& mesh);

// Shape function gradients of element e (rows: local nodes)
Eigen::Matrix<double, 4, 3> elementGradients(const TetMesh& mesh, int e);

}  // namespace smoothedSolid
