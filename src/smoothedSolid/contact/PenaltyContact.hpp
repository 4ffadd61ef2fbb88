// Frictionless normal penalty contact (paper Eq. 43: only the normal
// contact force, no friction): node-to-surface between distinct parts, self
// contact within a part, and against rigid triangulated surfaces supplied by
// the caller. Candidate triangles come from a spatial hash of their bounding
// boxes (never all pairs), kept per node as a Verlet list: the list holds
// the triangles within depth + skin of the node and is rebuilt only once a
// boundary node has moved by more than skin/2 since the last build (so no
// pair can come within the search depth unseen; skin = search depth).
//
// Each boundary node p is tested against the boundary triangles T of the
// other parts (and of its own part, away from its own elements, with self
// contact) and against rigid surfaces, in the current configuration. Among
// the triangles facing p (node normal . n_T < -facingCosine) within the
// search depth, the closest one (distance to its closest point q on the
// face, an edge or a vertex; Ericson 2005, Sect. 5.1.5) is taken; the gap is
// g = n_T.(p - q). When g < 0 the pair gets a spring and a normal dashpot,
//   f_n = max(0, -k g - 2 zeta sqrt(k m_eff) v_n),
// acting on p along n_T and, as the reaction, on T's nodes by the
// barycentric weights of q. The spring fades out linearly with the lateral
// offset of p beyond T's edge (over the search depth), so that the force is
// continuous where p slides over a crease of the other surface (a pressed
// plate makes a bowl, and a penetrating node can lie beyond the creases of
// both faces there) or off its edge, and a node exactly above an edge or a
// vertex of the other mesh (matching meshes) is held.
// Nominal stiffness k_p = beta M A_p / h: wave modulus M = K + 4 mu/3,
// tributary area A_p of the node, smallest element height h.
// Stability: a pair (p, T) adds k b b^T (x) n n^T with b = (1, -w_0, -w_1,
// -w_2) to the stiffness. Each step, the pairs found are scaled down where
// needed so that every node's Gershgorin bound of M^-1 K_contact,
//   (1/m_i) sum_pairs k |b_i| sum_j |b_j|,
// stays below the budget the step dt leaves beside the elements' own bound
// omega_i^2 of the same node (dynamics/StableStep.hpp, current configuration):
//   omega_c,i^2 <= (2 s / dt)^2 - omega_i^2,  s = 0.9,
// so that the Gershgorin bound of the sum, M^-1 (K_elements + K_contact), stays
// below (2 s / dt)^2. This matters for light nodes (corners) of a deformable
// surface that collect the reactions of several heavier nodes of the other
// body. While anything is near contact (a candidate within the search
// reach), the stable step is the contact-free one times stepFraction (0.5:
// the paper halves the step in contact): there the budget is at least
// (0.9^2/(0.5 x 0.8)^2 - 1) max omega^2 = 4 max omega^2 with the default
// safety 0.8, which rarely limits the nominal springs. At the contact-free
// step (contact that starts within a longer step, or a caller that keeps
// the step fixed) the budget is 0.27 max omega^2 and the springs are softer.
// The dashpot (zeta = 0.1 by default) removes the energy that the explicit
// step can otherwise add when contact starts between two steps (up to a few
// percent of the impact energy without it).
#pragma once

#include "mesh/TetMesh.hpp"

#include <array>
#include <istream>
#include <memory>
#include <ostream>
#include <vector>

namespace smoothedSolid {

struct RigidSurface {
    std::vector<Vec3> points;
    std::vector<Tri> triangles;  // normals (x1-x0)x(x2-x0) toward the solid's side
};

// Options; PenaltyContact's constructor checks each range and names the
// option it rejects
struct ContactOptions {
    bool betweenParts = true;
    bool selfContact = false;
    double penaltyScale = 2.0;  // beta, > 0
    double depthFraction = 0.5; // search depth = fraction * smallest element height, (0, 2]
    double facingCosine = 0.2;  // contact only if n_node . n_triangle < -facingCosine, [0, 1)
    double dampingRatio = 0.1;  // normal dashpot, fraction of critical, [0, 1]
    double stepFraction = 0.5;  // stable step with contact / without (paper: halved), (0, 1)
    // A solid carried by a fluid (ExplicitSolid::constrainCarriedVelocity):
    // the pairs limit the nodes' velocities instead of acting by springs
    // (PenaltyContact::constrainVelocities)
    bool kinematic = false;
    // With kinematic: no element's volume ratio J = V/V0 falls below this
    // in a carried step, to first order in the step ([0, 1); 0: no limit).
    // A solid thinner than the fluid's cells cannot show the fluid its
    // stiffness through its thickness: a node stopped at a wall while the
    // fluid carries the nodes behind it on crushes the elements between
    // them (PenaltyContact::constrainVelocities)
    double volumeLimit = 0.0;
};

// What PenaltyContact::constrainVelocities did
struct KinematicContact {
    int pairs = 0;           // pairs within the search depth
    int held = 0;            // of them, constrained at the end
    int sweeps = 0;          // Gauss-Seidel sweeps
    double maxChange = 0;    // largest change of a node's velocity
    double minGap = 0;       // smallest gap of the pairs (before the step)
    int elements = 0;        // elements whose volume limit was checked
    int volumeHeld = 0;      // of them, held at the end
    double minVolumeRatio = 1;  // smallest J of those checked (before the step)
};

class PenaltyContact {
public:
    // hMin: smallest element height; waveModulus, density: M = K + 4 mu/3
    // and rho of the material; mass: lumped nodal masses. Options out of
    // range throw naming the option. depthFraction is capped at 2: a body
    // with two element layers through its thickness is at least 2 h_min
    // thick, so with self contact its two faces never see each other.
    PenaltyContact(const TetMesh& mesh, double hMin, double waveModulus, double density,
                   const std::vector<double>& mass, ContactOptions options);

    const ContactOptions& options() const { return options_; }

    void addRigidSurface(RigidSurface surface);
    const std::vector<RigidSurface>& rigidSurfaces() const { return rigid_; }

    // Nodes held still (all three components fixed at zero displacement):
    // they get no pairs with rigid surfaces, whose force would be discarded
    // and which would keep the step at stepFraction for good (e.g. a
    // leaflet's attachment, fixed on the wall it is attached to: its face
    // nodes lie on or behind the wall by construction). Pairs with the
    // solid's own triangles stay (their reactions move the other body).
    // One entry per mesh node; the candidate lists are built again.
    void setStillNodes(std::vector<char> still);

    // Add contact forces for current coordinates x (velocities v) to f for
    // a step dt; omega2: the elements' Gershgorin bound per node (the
    // springs' budget); pressure per node (|force|/tributary area) into
    // 'pressure'. Returns the largest penetration depth found.
    double addForces(const TetMesh& mesh, const std::vector<Vec3>& x,
                     const std::vector<Vec3>& velocity, double dt,
                     const std::vector<double>& omega2, std::vector<Vec3>& f,
                     std::vector<double>& pressure) const;

    // Kinematic contact (options().kinematic) for a solid that moves with
    // velocities it is given (a solid carried by a fluid): at the carrying
    // fluid's step the springs get almost no stiffness (their budget is set
    // by the nodes' own mass), and two leaflets in one fluid cell, or a
    // leaflet by a wall, move with one interpolated velocity in which
    // nothing keeps them apart. Each pair (boundary node p and its closest
    // facing triangle T within the search depth, found as addForces()
    // finds them, at any gap g below the depth, but a rigid triangle need
    // not face the node: a leaflet's edge reaches the wall edge on; nodes
    // held still have no rigid pairs) is a unilateral constraint on the relative normal
    // velocity v_n = n.(v_p - sum_j w_j v_j) (w: the barycentric weights of
    // p's closest point on T, n: T's unit normal):
    //     v_n >= -g/dt        (g >= 0: the step closes at most the gap),
    //     v_n >= -g/(2 dt)    (g < 0: half the depth recovered per step),
    // met by impulses along n, +lambda on p and -lambda w_j on T's nodes
    // (none on a rigid surface), lambda >= 0 accumulated per pair by
    // projected Gauss-Seidel sweeps over the pairs (sequential impulses:
    // Moreau, Unilateral contact and dry friction in finite freedom
    // dynamics, CISM Courses 302, 1988; Jean, Comput Methods Appl Mech Eng
    // 177:235, 1999): the impulses are equal and opposite, so the solid's
    // momentum is kept, and a pair only pushes. invMass: per node, the
    // inverse of its mass, 0 where the node may not change (held). At most
    // 'sweeps' sweeps, until no constraint is violated by more than
    // 1e-9 m/s plus 1e-3 of the largest velocity (where the two sides'
    // pairs, node to triangle both ways, are nearly redundant, as where two
    // surfaces lie on each other, the sweeps converge slowly: a step then
    // leaves a gap's error of at most that velocity times dt). v is
    // corrected in place.
    //
    // With options().volumeLimit = Jmin > 0 each element e whose volume
    // ratio J = V/V0 could come near Jmin in the step (J, or J at the end
    // of the step at the given velocities, below (1 + Jmin)/2, or a node in
    // a contact pair; after the sweeps the other elements are checked again
    // at the corrected velocities, up to three more times) is a unilateral
    // constraint in the same sweeps (before the pairs in each) on the rate
    // of its volume, dV/dt = sum_a g_a . v_a, g_a = dV/dx_a (the area
    // vector of the face opposite node a over 3, pointing from that face
    // toward a):
    //     dV/dt >= (Jmin V0 - V)/dt         (V >= Jmin V0),
    //     dV/dt >= (Jmin V0 - V)/(2 dt)     (V <  Jmin V0: half recovered),
    // met by impulses lambda g_a on its nodes, lambda >= 0: the impulse of
    // a pressure in the element, which pushes its nodes apart and, as
    // sum_a g_a = 0, keeps the solid's momentum. V is linear in each node's
    // position, so the limit is exact for one node's motion and first
    // order in the step otherwise. A carried solid is then incompressible
    // below Jmin where the fluid cannot resolve it: a node the contact stops
    // at a wall holds the nodes behind it off (or the wall, through the
    // contact, holds them).
    //
    // The volume constraints are scaled by V0^(2/3), so their tolerance is
    // a velocity as the pairs'.
    KinematicContact constrainVelocities(const TetMesh& mesh, const std::vector<Vec3>& x,
                                         std::vector<Vec3>& v,
                                         const std::vector<double>& invMass, double dt,
                                         int sweeps = 100) const;

    // The candidate search for coordinates x (addForces makes it too): the
    // lists are rebuilt only once a boundary node has moved by skin/2
    void search(const TetMesh& mesh, const std::vector<Vec3>& x) const;
    bool searched() const { return built_; }
    // Anything near contact (a candidate within the search reach) at the
    // last search: then the stable step is stepFraction of the contact-free one
    bool nearContact() const { return !cand_.empty(); }

    // How often the candidate lists were built (the first build included)
    long candidateBuilds() const { return builds_; }

    // The search state that decides the next forces and steps (candidate
    // lists and where they were built), for exact restarts
    struct State {
        bool built;
        long builds;
        std::vector<int> candStart, cand;
        std::vector<Vec3> xBuild;
    };
    void writeState(std::ostream& os) const;
    // Reads and checks a state written by writeState (file: for messages)
    std::unique_ptr<State> readState(std::istream& is, const std::string& file) const;
    void setState(State state);

private:
    ContactOptions options_;
    std::vector<int> slaveNodes_;
    std::vector<double> k_, area_;
    std::vector<double> mass_;
    std::vector<int> triPart_;            // part of each boundary triangle
    std::vector<int> nodePart_;
    std::vector<char> still_;            // per node: held still (no rigid pairs)
    std::vector<std::vector<int>> neighbours_;  // nodes sharing an element
    std::vector<int> nodeFaceStart_, nodeFaces_;  // boundary faces (CSR, into boundaryFaces())
    std::vector<RigidSurface> rigid_;
    std::vector<std::array<int, 2>> rigidTri_;  // (surface, triangle) for id -1 - i
    double depth_ = 0;
    static constexpr double safety_ = 0.9;

    struct Pair {
        int node, id;  // id: boundary triangle (>= 0) or rigid (-1 - index)
        double k, gap;
        Vec3 direction;
        double w[3];
    };
    mutable std::vector<Pair> pairs_;
    mutable std::vector<double> load_;  // zero between calls

    // Slave node s's closest facing candidate triangle within the search
    // depth (false: none): its id, the gap along its unit normal, the
    // lateral offset beyond its edges and the closest point's weights.
    // facingRigid false: a rigid triangle need not face the node (a rigid
    // surface has one side, its normal's: a thin body's edge, whose nodes'
    // normals lie along the wall, reaches it edge on)
    struct Nearest {
        int id;
        double gap, lateral;
        Vec3 normal;
        double w[3];
    };
    bool nearest(const TetMesh& mesh, const std::vector<Vec3>& x, int s, Nearest& r,
                 bool facingRigid) const;

    // Verlet candidate lists: per slave node (CSR over slaveNodes_)
    void buildCandidates(const TetMesh& mesh, const std::vector<Vec3>& x) const;
    void triangle(const TetMesh& mesh, const std::vector<Vec3>& x, int id, Vec3& a, Vec3& b,
                  Vec3& c) const;
    double skin_ = 0;
    mutable bool built_ = false;
    mutable long builds_ = 0;
    mutable std::vector<int> candStart_, cand_;
    mutable std::vector<Vec3> xBuild_;  // slave node positions at the last build
};

}  // namespace smoothedSolid
