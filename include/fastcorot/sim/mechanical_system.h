// MechanicalSystem<Real>: everything an ODE solver acts on for one object (the contents of a SOFA
// node under one solver): the state, the force fields, the mass, fixed points, constant forces and
// gravity. It offers the operations SOFA's mechanical visitors provide: the total force, the
// product (m M + b B + k K) dx with projective constraints applied, and the same matrix assembled.
// K is df/dx of the force fields' last linearisation (their last add_force); B = 0 except through
// the force fields' own Rayleigh stiffness.
#pragma once

#include "fastcorot/core/phase_times.h"
#include "fastcorot/core/types.h"
#include "fastcorot/fem/force_field.h"
#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/sim/linear_movement.h"
#include "fastcorot/sim/mass.h"
#include "fastcorot/sim/mechanical_state.h"
#include "fastcorot/sim/rigid_mapped_mass.h"
#include "fastcorot/state/rigid_blocks.h"
#include "fastcorot/topology/tet_mesh.h"
#include "fastcorot/topology/topology_change.h"

#include <Eigen/SparseCore>

#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

// Forces held constant in time (SOFA's ConstantForceField): forces[i] applies to indices[i].
template <class Real>
struct ConstantForce {
  std::vector<Index> indices;
  std::vector<Vec3<Real>> forces;
};

// A point whose motion is restricted to a subspace (SOFA's PartialFixed-, FixedPlane-, Plane- and
// LineProjectiveConstraint): its displacements, forces and right-hand sides are multiplied by
// `projector` (SOFA's projectResponse), and assembled matrices become P A P + (I - P) blockwise.
template <class Real>
struct PointProjection {
  Index point = 0;
  Mat3<Real> projector = Mat3<Real>::Identity();
};

// What a projective constraint does to a point at the end of each step (SOFA's projectPosition and
// projectVelocity): x <- origin + projector (x - origin), and v <- velocity_projector v.
template <class Real>
struct PointPlacement {
  Index point = 0;
  Mat3<Real> projector = Mat3<Real>::Identity();
  Vec3<Real> origin = Vec3<Real>::Zero();
  Mat3<Real> velocity_projector = Mat3<Real>::Identity();
};

// A point moved along a straight line in time (SOFA's AffineMovementProjectiveConstraint) at the end
// of the step that starts at time t: x = ((end - start) t + start t1 - end t0) / (t1 - t0) for
// t0 < t <= t1, x = end after t1; its increments and velocity are projected to zero.
template <class Real>
struct PointMotion {
  Index point = 0;
  Vec3<Real> start = Vec3<Real>::Zero();
  Vec3<Real> end = Vec3<Real>::Zero();
  double begin_time = 0;
  double end_time = 0;
};

// Two points tied together (SOFA's AttachProjectiveConstraint on 3D points): `first` is object1's
// point, `second` object2's. Increments and forces: one way, the second's are zeroed; two ways,
// each moves towards the other by `response` (SOFA's 0.5 responseFactor constraintFactor) times
// their difference. At the end of each step, the second point's position moves towards the first
// by `position` times their difference (the first stays), and both velocities towards each other
// by `velocity` times theirs, one way or two (SOFA's projectPosition and projectVelocity).
template <class Real>
struct PointCoupling {
  Index first = 0;
  Index second = 0;
  bool two_way = false;
  Real response = Real(0.5);
  Real position = Real(0.5);
  Real velocity = Real(0.5);
};

// How the ranks of a distributed run (sim/distribution.h) complete per-point sums: each rank
// computes forces and products from its own tetrahedra only, so a point on the boundary between
// ranks holds a partial sum on each; sum_shared() makes every copy the full sum (the same bits on
// every rank). sum() adds a number over the ranks. Collective: every rank calls them together.
template <class Real>
class PointExchange {
 public:
  virtual ~PointExchange() = default;
  virtual void sum_shared(std::span<Vec3<Real>> values) const = 0;
  virtual Real sum(Real value) const = 0;
};

// Factors of the system matrix m M + b B + k K.
template <class Real>
struct MatrixFactors {
  Real m = 0;
  Real b = 0;
  Real k = 0;
};

template <class Real>
class MechanicalSystem {
 public:
  MechanicalState<Real> state;
  std::vector<std::shared_ptr<ForceField<Real>>> force_fields;  // any of fem/*_force_field.h
  Mass<Real> mass;                   // empty (size 0) when the object has no mass component
  std::vector<Index> fixed;          // fixed point indices, sorted, unique
  // Points whose velocity is zeroed after each step (FixedProjectiveConstraint's
  // activate_projectVelocity); SOFA otherwise leaves their velocity alone.
  std::vector<Index> zero_velocity;
  // Partial projections, one entry per point after finalize() (entries of one point are combined
  // in the order given: the later projector applies after the earlier one). Points in `fixed`
  // need none.
  std::vector<PointProjection<Real>> projections;
  // Coupled points, applied before the projections in the order given (SOFA applies the
  // constraints of a parent node, where a pair constraint sits, before those of its children).
  std::vector<PointCoupling<Real>> couplings;
  // End-of-step placements, applied in the order given after the couplings' (apply_placements).
  std::vector<PointPlacement<Real>> placements;
  std::vector<PointMotion<Real>> motions;  // applied after the placements
  // LinearMovementProjectiveConstraints, applied after the motions; while one moves its points
  // (begin_step), they are held like fixed points (`moving`).
  std::vector<LinearMovement<Real>> linear_movements;
  std::vector<Index> moving;
  std::vector<ConstantForce<Real>> constant_forces;
  Vec3<Real> gravity = Vec3<Real>::Zero();
  // Points that lost their last tetrahedron and have no mass (cutting): nothing determines their
  // motion, so they are held where they are, like fixed points (sorted). SOFA deletes them; here
  // points stay so that indices into the state never change.
  std::vector<Index> isolated;
  // Rigid bodies (SOFA's Rigid3 states): which blocks of the state are rigids' [linear, angular]
  // pairs, and their orientations (null: none, the deformable objects' case). The solvers add to
  // the angular blocks as to any other; Simulation folds them into the orientations after each
  // step (RigidBlocks::rebase). Shared with the visual models and mapped states that follow them.
  std::shared_ptr<RigidBlocks<Real>> rigids;
  // Masses on points the rigids carry (null: none): `mass` is then recomputed from it at the
  // positions each step starts from (update_mass), as their Jacobian turns with the rigids.
  std::shared_ptr<const RigidMappedMass<Real>> rigid_mapped_mass;
  // Set in distributed runs (null otherwise): compute_force and multiply complete their sums at the
  // points shared with other ranks, and the energies add over the ranks.
  std::shared_ptr<const PointExchange<Real>> exchange;

  Index size() const { return state.size(); }

  // Sorts and de-duplicates `fixed` and checks every index against the state size; throws
  // fastcorot::Error naming the bad index, or when a constant force has not one force per index,
  // the mass or the velocities / rest positions (filled from the positions when empty) do not
  // match the state size. Call after filling the system.
  void finalize();

  // f = total force at positions x and velocities v (force fields, weight, constant forces;
  // v empty: the state's velocities); overwrites f. The force fields record their linearisation at x.
  void compute_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, std::span<const Vec3<Real>> v = {});

  // Recomputes `mass` from rigid_mapped_mass at the current positions (nothing without one).
  void update_mass() {
    if (rigid_mapped_mass) mass = rigid_mapped_mass->at(state.position, size());
  }

  // out = (m M + b B + k K) dx, then projected (fixed entries zero).
  void multiply(const MatrixFactors<Real>& factors, std::span<const Vec3<Real>> dx,
                std::span<Vec3<Real>> out) const;
  // The same product from this process's own masses and elements only, not projected: in a
  // distributed run, partial at the points shared with other ranks (multiply() completes it).
  void multiply_own_part(const MatrixFactors<Real>& factors, std::span<const Vec3<Real>> dx,
                         std::span<Vec3<Real>> out) const;

  // The same matrix assembled (3#V × 3#V); each fixed point's rows and columns are cleared and its
  // diagonal set to 1, as SOFA's projective constraints do to an assembled matrix. Compressed; held
  // by the system until the next call (copy it to keep it longer).
  const Eigen::SparseMatrix<Real>& assemble(const MatrixFactors<Real>& factors) const;

  // The 3×3 diagonal blocks of the same matrix, one per point, as assemble() has them (identity for
  // fixed and isolated points); overwrites `blocks` (#V blocks). For block-Jacobi preconditioning.
  // At a point coupled two ways, the matrix blocks between the two points are left out (they are
  // zero when no element joins them, as between two objects).
  void diagonal_blocks(const MatrixFactors<Real>& factors, std::span<Mat3<Real>> blocks) const;

  // Applies the couplings and the partial projections and zeroes the entries of fixed, isolated
  // and moving points (SOFA's projectResponse).
  void project(std::span<Vec3<Real>> v) const;
  // SOFA's projectPosition and projectVelocity after the step that started at `time` (SOFA's
  // context time): the couplings, the placements, the motions, then the linear movements, on the state.
  void apply_placements(double time = 0);
  // Before the step that starts at `time`: the points the linear movements hold during it (`moving`).
  void begin_step(double time);

  // Topological changes of `mesh` (the mesh of one or more of the force fields, or of the mass):
  // the mesh changes, and the force fields and the mass on it follow, at a cost proportional to
  // the change. Throws fastcorot::Error (nothing changed) for a bad index or, when adding, a
  // (near) zero rest volume.
  TopologyChange remove_tetrahedra(TetMesh& mesh, std::span<const Index> indices);
  TopologyChange add_tetrahedra(TetMesh& mesh, std::span<const Tetrahedron> tetrahedra);

  // Elastic energy of the force fields plus the potential of gravity and constant forces, at x.
  Real potential_energy(std::span<const Vec3<Real>> x) const;
  Real kinetic_energy() const;

  // Threads for the force fields and the solvers' vector work (applied to the force fields here
  // and again by finalize); results are bitwise the same for any count.
  void set_threads(int threads);
  int threads() const { return threads_; }
  // After state.rest_position (and rigids->rest_orientation) changed between steps: the force
  // fields that read the rest positions at every step in SOFA take them again (follow_rest); the
  // number that did.
  int follow_rest_positions() {
    int followed = 0;
    for (const auto& field : force_fields) followed += field->follow_rest(state.rest_position) ? 1 : 0;
    return followed;
  }
  // Where the force fields, the products and the solvers add their time (null: not timed).
  void set_phase_times(PhaseTimes* times);
  PhaseTimes* phase_times() const { return times_; }
  // Slot of `times` for a phase, or null when not timed (for PhaseTimer).
  double* timer_slot(double PhaseTimes::*phase) const { return times_ ? &(times_->*phase) : nullptr; }

 private:
  void follow(const TetMesh& mesh, const TopologyChange& change);

  int threads_ = 1;
  PhaseTimes* times_ = nullptr;
  mutable PatternedAssembly<Real> assembly_;  // assemble()'s matrix, its pattern kept between calls
  mutable TripletSink<Real> sink_;             // assemble()'s entries (cleared, its capacity kept)
  mutable Eigen::SparseMatrix<Real> projected_;  // assemble()'s matrix when projections apply
};

}  // namespace fastcorot
