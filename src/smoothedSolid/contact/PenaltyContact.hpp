// Frictionless normal penalty contact (paper Eq. 43: only the normal
// contact force, no friction): node-to-surface between distinct parts, self
// contact within a part, and against rigid triangulated surfaces supplied by
// the caller. Candidate triangles come from a spatial hash of their bounding
// boxes (never all pairs).
//
// A boundary node p is in contact with a boundary triangle T (current
// configuration, outward unit normal n) when its projection falls inside T,
// the two face each other (node normal . n < -facingCosine) and its gap
// g = (p - x_T).n is negative but above -depth; the penalty force
// -k g n acts on p and its reaction on T's nodes (by barycentric weights).
// k_p = beta M A_p / h: wave modulus M = K + 4 mu/3, tributary area A_p of
// the node, smallest element height h: the contact frequency sqrt(k/m) is of
// the order of the element's, and the stable time step is reduced
// accordingly (stableTimeStepFactor): about halved with the default beta,
// as the paper does while in contact.
// Known limitation: between two deformable bodies, reactions of several
// slave springs on a light master node are not counted in the time step
// (see the closing note of the solid issue).
#pragma once

#include "mesh/TetMesh.hpp"

#include <vector>

namespace smoothedSolid {

struct RigidSurface {
    std::vector<Vec3> points;
    std::vector<Tri> triangles;  // normals (x1-x0)x(x2-x0) toward the solid's side
};

struct ContactOptions {
    bool betweenParts = true;
    bool selfContact = false;
    double penaltyScale = 2.0;  // beta
    double depthFraction = 0.5; // search depth = fraction * smallest element height
    double facingCosine = 0.2;  // contact only if n_node . n_triangle < -facingCosine
};

class PenaltyContact {
public:
    PenaltyContact(const TetMesh& mesh, double waveModulus, const std::vector<double>& mass,
                   ContactOptions options);

    void addRigidSurface(RigidSurface surface);
    const std::vector<RigidSurface>& rigidSurfaces() const { return rigid_; }

    // Add contact forces for current coordinates x to f; pressure per node
    // (|force|/tributary area) into 'pressure'. Returns the largest
    // penetration depth found.
    double addForces(const TetMesh& mesh, const std::vector<Vec3>& x, std::vector<Vec3>& f,
                     std::vector<double>& pressure) const;

    // Ratio of the stable step with contact springs to the one without:
    // omega^2 = omega_e^2 + k/m, omega_e = 2/dt_e -> 1/sqrt(1 + max_i k_i dt_e^2/(4 m_i))
    double stableTimeStepFactor(double dtElement) const;

    double penaltyStiffness(int node) const { return k_[node]; }
    double depth() const { return depth_; }

private:
    ContactOptions options_;
    std::vector<int> slaveNodes_;
    std::vector<double> k_, area_;
    std::vector<double> mass_;
    std::vector<int> triPart_;            // part of each boundary triangle
    std::vector<int> nodePart_;
    std::vector<std::vector<int>> neighbours_;  // nodes sharing an element
    std::vector<RigidSurface> rigid_;
    double depth_ = 0, hMin_ = 0;
};

}  // namespace smoothedSolid
