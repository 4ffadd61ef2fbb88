// Explicit dynamics of a hyperelastic solid discretised by smoothed FEM
// (paper Sect. 4.2): central difference (Eqs. 53-55 of the paper's
// procedure; Belytschko, Liu & Moran, Nonlinear Finite Elements, Sect. 6.2),
// lumped mass, internal force by the chosen smoothing formulation (Eq. 31),
// external forces (Eq. 43) from the caller, follower pressure and body
// force, optional mass-proportional damping for quasi-static runs and
// stiffness-proportional damping of the mesh's fastest modes.
#pragma once

#include "contact/PenaltyContact.hpp"
#include "dynamics/StableStep.hpp"
#include "material/Material.hpp"
#include "mesh/TetMesh.hpp"
#include "smoothing/SmoothingDomains.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <vector>

namespace smoothedSolid {

struct SolidOptions {
    Formulation formulation = Formulation::Selective;
    double safety = 0.9;   // fraction of the stable step bound (dynamics/StableStep.hpp)
    double damping = 0.0;  // mass-proportional damping coefficient [1/s]
    // Stiffness-proportional (Rayleigh) damping coefficient beta [s]: the
    // internal force is taken at u + beta v, f_int(u) + beta K v to first
    // order, a Kelvin-Voigt viscosity beta C : dE/dt. A mode of angular
    // frequency omega gets the damping ratio beta omega / 2: a beta of the
    // order of the stable step damps the element-scale modes (omega near
    // 2/dt) strongly and the structural ones (omega orders of magnitude
    // lower) by that ratio only. The stable step shrinks by
    // sqrt(1 + z^2) - z, z = beta omega_max / 2 (see stableTimeStep()).
    double stiffnessDamping = 0.0;
};

class ExplicitSolid {
public:
    using VectorFunction = std::function<Vec3(double t, const Vec3& X)>;
    using ScalarFunction = std::function<double(double t)>;

    ExplicitSolid(TetMesh mesh, std::shared_ptr<const Material> material,
                  SolidOptions options = {});

    const TetMesh& mesh() const { return *mesh_; }
    const Material& material() const { return *material_; }
    const SolidOptions& options() const { return options_; }
    void setDamping(double c) { options_.damping = c; }
    void setStiffnessDamping(double beta);

    // --- boundary conditions and loads -----------------------------------
    // Components: mask of x, y, z
    void fix(const std::string& nodeSet, std::array<bool, 3> components = {true, true, true});
    void prescribeDisplacement(const std::string& nodeSet, VectorFunction u,
                               std::array<bool, 3> components = {true, true, true});
    void prescribeVelocity(const std::string& nodeSet, VectorFunction v,
                           std::array<bool, 3> components = {true, true, true});
    // Pressure p(t) on a face set, acting against the current outward normal
    void addFollowerPressure(const std::string& faceSet, ScalarFunction p);
    // Body force per unit mass (acceleration), e.g. gravity
    void setBodyForce(const Vec3& g) { bodyForce_ = g; }
    // Nodal external forces set by a caller (the FSI force comes in here);
    // held constant during advance() unless a load update (below) changes them
    std::vector<Vec3>& externalForce() { return fext_; }
    const std::vector<Vec3>& externalForce() const { return fext_; }
    // Called at the start of every step (also every sub-step of advance())
    // with the step's start time, to update time-dependent loads through
    // externalForce() and setBodyForce(); none by default
    void setLoadUpdate(std::function<void(double t)> update) { loadUpdate_ = std::move(update); }
    // Added mass per node (non-negative, one per node; empty: none): the
    // velocity update divides the force by lumpedMass() + addedMass, while
    // body force, damping force and kinetic energy keep the solid's own
    // mass. A partitioned fluid-structure coupling uses it to stabilise an
    // explicit (Dirichlet-Neumann) scheme against added-mass instability,
    // the caller adding addedMass * (its estimate of the acceleration) to
    // the external force so that the steady state is unchanged. The stable
    // step keeps the solid's own mass (conservative). Not part of the
    // saved state: set it again before loadState().
    void setAddedMass(std::vector<double> m);
    const std::vector<double>& addedMass() const { return addedMass_; }
    // Velocity correction at the end of the last step of length dt: dv is
    // added to the velocity and dt*dv to the displacement of every node
    // component that no constraint holds (an impulse over that step, as a
    // projection's pressure correction: the semi-implicit coupling of the
    // fluid's pressure with the solid's inertia). Components held by
    // fix(), prescribeDisplacement() or prescribeVelocity() are left as
    // the constraints set them. Throws on a wrong size or non-finite value.
    void correctVelocity(const std::vector<Vec3>& dv, double dt);
    // Per node, 1 for each component no constraint holds, else 0
    std::vector<Vec3> freeComponents() const;

    // --- the fluid carrying the solid (IFEM) --------------------------------
    // For an immersed coupling in which the fluid carries the solid's mass
    // and the solid moves with the fluid's velocity (immersed finite element
    // method: Zhang, Gerstenberger, Wang & Liu, CMAME 193:2051, 2004, Eqs.
    // 8-10; the paper's Eq. 4 with the fictitious fluid as dense as the
    // solid). interactionForce() is the force the solid's stress, its loads
    // and contact exert at the current state, f_ext + m g - f_int(u + beta v)
    // + f_contact (Eq. 42 without the inertia), zero in the components a
    // constraint holds (the support takes it). dt: the carrying fluid's step; the contact springs
    // are bounded by it with the nodes' own mass, not by the elements'
    // stable step, which the fluid's larger mass makes irrelevant (with the
    // elements' bound, the springs would get no budget at a step longer
    // than the solid's own stable step, and contact would do nothing).
    std::vector<Vec3> interactionForce(double dt);
    // Moves every node component no constraint holds by dt v and sets its
    // velocity to v; constrained components follow their constraint. Time
    // and step count advance by dt and one step. Throws naming the node on
    // a wrong size or a non-finite velocity (the state unchanged). An
    // element the motion inverts is reported by the next force evaluation
    // (interactionForce()), which names it: the motion does not evaluate
    // the stress a second time.
    void moveWith(const std::vector<Vec3>& v, double dt);
    // With contact's kinematic option, the velocities v a carried solid is
    // about to move with over dt, corrected in place so that no contact
    // pair within the search depth closes below zero gap in the step
    // (PenaltyContact::constrainVelocities, at the current coordinates;
    // nodes that a constraint holds in any component do not change).
    // Without it, nothing. Throws on a wrong size.
    KinematicContact constrainCarriedVelocity(std::vector<Vec3>& v, double dt) const;

    // --- fibre directions (fibre-reinforced materials) --------------------
    // One direction per element in the reference configuration (normalised
    // here; a zero or non-finite one throws naming the element). Each
    // smoothing domain the formulation integrates over takes the
    // sign-aligned, volume-weighted mean of its elements' directions
    // (Smoothing::domainDirections). A material with hasFibres() needs them
    // before the first force evaluation; an isotropic one rejects them. They
    // are set up like the mesh, not stored in state files: set them again
    // before loadState().
    void setFibreDirections(std::vector<Vec3> a0);
    const std::vector<Vec3>& fibreDirections() const { return fibreElement_; }

    // --- contact (paper Eq. 43) ------------------------------------------
    // Frictionless penalty contact between parts / within a part; the
    // stable time step then accounts for the penalty springs
    void enableContact(ContactOptions options = {});
    // A rigid triangulated surface (e.g. a wall), normals toward the solid
    void addRigidSurface(RigidSurface surface);
    // Contact pressure per node and the largest penetration of the last step
    const std::vector<double>& contactPressure() const { return contactPressure_; }
    // The contact, if enabled (else null)
    const PenaltyContact* contact() const { return contact_.get(); }
    double maxPenetration() const { return maxPenetration_; }

    // Initial velocity field v0(X) and displacement u0(X) (e.g. a
    // prestretched state); only before the first step
    void setInitialVelocity(const VectorFunction& v0);
    void setInitialDisplacement(const VectorFunction& u0);

    // --- time stepping ----------------------------------------------------
    // Stable time step: safety * 2 / omega_max, omega_max from the bound of
    // dynamics/StableStep.hpp in the current configuration (re-evaluated
    // during the run, see stableStepInterval()), times sqrt(1 + z^2) - z
    // with stiffness damping (z = beta omega_max / 2: the central
    // difference with the damping force at v^{n-1/2}, Belytschko, Liu &
    // Moran, Nonlinear Finite Elements, Sect. 6.2), times the contact step
    // fraction while contact is near
    double stableTimeStep() const;
    // The same bound, without contact, for any displacement u (evaluated now)
    double stableTimeStep(const std::vector<Vec3>& u) const;
    // Sub-steps between two evaluations of the bound: adapts between 1 and
    // kMaxStableStepInterval so that omega_max^2 changes by about
    // kStableStepDrift (10 %) between evaluations at the rate seen over the
    // last interval (at most doubling each time)
    int stableStepInterval() const { return boundInterval_; }
    static constexpr int kMaxStableStepInterval = 128;
    static constexpr double kStableStepDrift = 0.10;
    // Evaluations of the bound and the wall time they took, since this
    // object was made (diagnostics; not part of the saved state)
    long boundEvaluations() const { return boundEvaluations_; }
    double boundSeconds() const { return boundSeconds_; }
    // omega_I^2 per node of the last evaluation (its maximum sets the step)
    const std::vector<double>& nodeOmega2() const { return nodeOmega2_; }
    // One central-difference step of size dt (positive, finite). Throws,
    // leaving the state as it was, when the forces stop being finite or a
    // smoothing domain inverts, naming time, step and node or element.
    void step(double dt);
    // Advance by dt (positive, finite) with as many stable sub-steps as
    // needed (re-chosen after each sub-step); returns their number. Throws
    // when the remaining interval would take more than kMaxSubSteps
    // sub-steps (a blown-up solid), the state of the last sub-step kept
    int advance(double dt);
    static constexpr double kMaxSubSteps = 1e7;

    // --- state -------------------------------------------------------------
    double time() const { return t_; }
    long steps() const { return nSteps_; }
    const std::vector<Vec3>& displacement() const { return u_; }
    // Velocity v^{n+1/2} of the last step (central difference half step);
    // the initial velocity before the first step
    const std::vector<Vec3>& velocity() const { return vHalf_; }
    const std::vector<double>& lumpedMass() const { return mass_; }
    std::vector<Vec3> currentCoordinates() const;

    // Internal nodal forces f_int(u) and strain energy for displacement u
    std::vector<Vec3> internalForce(const std::vector<Vec3>& u) const;
    double strainEnergy(const std::vector<Vec3>& u) const;
    // Kinetic energy of velocity()
    double kineticEnergy() const;

    // Cauchy stress and J per element, from the smoothing domains that
    // overlap it (selective: deviatoric part from its 4 face domains,
    // volumetric part from its 4 node domains)
    void elementStress(std::vector<Mat3>& sigma, std::vector<double>& J) const;

    // Full state for an exact restart: time, step counters, u, v, external
    // force, the stable step bound and its schedule, the contact candidate
    // lists. The file carries a format tag and version, node and element
    // counts, formulation and material; loading a truncated or mismatched
    // file throws naming the file and the mismatch.
    void saveState(const std::string& fileName) const;
    void loadState(const std::string& fileName);
    // The same on a stream (e.g. an in-memory snapshot for the sub-
    // iterations of an implicit coupling); 'name' names it in errors
    void saveState(std::ostream& os, const std::string& name) const;
    void loadState(std::istream& is, const std::string& name);

private:
    struct Constraint {
        std::vector<int> nodes;
        std::array<bool, 3> components;
        VectorFunction value;
        bool isVelocity;
        bool still = false;  // fix(): held at zero displacement
    };
    // Nodes held still in all three components by fix() go to the contact
    // (no rigid-surface pairs for them: neither side can move)
    void passStillNodesToContact();
    struct Pressure {
        std::vector<Tri> faces;
        ScalarFunction p;
    };

    void accelerationForces(std::vector<Vec3>& f, double dt);  // f_ext - f_int (+ contact) at t_
    void applyConstraints(double dt);
    // Fe_ and the domain F's of every DomainUse for displacement u
    void deformationGradients(const std::vector<Vec3>& u) const;
    void refreshBound();
    // The fibre directions of use k's domains when its stress part needs
    // them (null for isotropic materials and the volumetric part)
    const std::vector<Vec3>* fibres(std::size_t k) const;

    std::shared_ptr<const TetMesh> mesh_;
    std::shared_ptr<const Material> material_;
    SolidOptions options_;

    // The smoothing (one representation: element gradients and domain
    // weights) and the domains the formulation integrates over
    Smoothing smoothing_;
    std::vector<DomainUse> uses_;
    // Scratch: element F, per use the domain F and stress, element stress sums
    mutable std::vector<Mat3> Fe_, Pbar_;
    mutable std::vector<std::vector<Mat3>> Fd_, Pd_;

    // Fibre directions per element and, per use, per domain
    std::vector<Vec3> fibreElement_;
    std::vector<std::vector<Vec3>> fibreDomain_;

    std::vector<double> mass_;
    std::vector<double> addedMass_;
    StableStepBound bound_;
    std::vector<double> nodeOmega2_;
    double omega2Max_ = 0;
    int boundAge_ = 0, boundInterval_ = 1;
    long boundEvaluations_ = 0;
    double boundSeconds_ = 0;

    std::vector<Vec3> u_, vHalf_, fext_;
    mutable std::vector<Vec3> work_;
    std::vector<Vec3> x_;  // current coordinates, for the contact search
    std::vector<Vec3> uDamped_;  // u + beta v (stiffness damping)
    bool carried_ = false;         // interactionForce(): contact springs not
                                   // bounded by the elements' stable step
    std::vector<double> zeroOmega2_;
    // the stable step of omega_max^2 with safety and stiffness damping
    double stepOfOmega2(double omega2) const;
    std::vector<Constraint> constraints_;
    std::vector<Pressure> pressures_;
    std::unique_ptr<PenaltyContact> contact_;
    std::vector<double> contactPressure_;
    double maxPenetration_ = 0;
    Vec3 bodyForce_ = Vec3::Zero();
    std::function<void(double)> loadUpdate_;
    double t_ = 0, dtLast_ = 0, hMin_ = 0;
    long nSteps_ = 0;
};

}  // namespace smoothedSolid
