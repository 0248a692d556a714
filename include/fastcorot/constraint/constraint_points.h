// Where Lagrangian constraints act: ConstraintPoints, the points of one MechanicalObject (a
// simulated object's own points, or a mapped state that follows them), and ConstraintRows, the rows
// of H they write, carried down to the simulated objects' blocks through the points' mapping (SOFA's
// buildConstraintMatrix then applyJT on the constraint Jacobian, MechanicalAccumulateMatrixDeriv).
// Design: docs/constraints.md.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/sim/linear_movement.h"
#include "fastcorot/sim/mechanical_state.h"
#include "fastcorot/state/rigid_blocks.h"

#include <Eigen/SparseCore>

#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

// How the points of a state no ODE solver integrates move: SOFA's FreeMotionAnimationLoop projects
// every state's positions at a step's end (at the step's start time, before time advances) and then
// applies the mappings, so a LinearMovementProjectiveConstraint on such a state, or on the rigid
// bodies that carry it, moves it. `state` holds the moved blocks (the points themselves, or each
// rigid's centre and angular block, with `frames` their orientations); carried points are
// `local` in rigid `rigid[i]`'s frame (SOFA's RigidMapping: centre + q.rotate(local)).
template <class Real>
struct PrescribedMotion {
  LinearMovement<Real> movement;
  MechanicalState<Real> state;
  std::shared_ptr<RigidBlocks<Real>> frames;  // null: `state` is the points
  std::vector<std::size_t> rigid;
  std::vector<Vec3<Real>> local;

  // Moves `state` to where the movement puts it at `time` and writes the points into `points`.
  void apply(double time, std::vector<Vec3<Real>>& points);
};

template <class Real>
struct ConstraintPoints {
  std::size_t object = 0;  // the simulated object (its index in the simulation)
  // Own points: point i is block blocks[i] of the object's state (mapping null). Mapped points:
  // point i is the mapping's child point i.
  std::vector<Index> blocks;
  std::shared_ptr<MechanicalMapping<Real>> mapping;
  std::vector<Vec3<Real>> rest_position;  // the MechanicalObject's rest positions, one per point
  // A MechanicalObject no ODE solver integrates (as in SOFA, nothing moves its points and rows on
  // it reach no correction): its points stay at `position` (= free_position, set when built, free
  // velocities zero); H gets no entries on it; `object` and `blocks` are unused.
  bool unsimulated = false;
  // Unsimulated points that a prescribed movement moves (null: they stay put): the loop moves them
  // at each step's end.
  std::shared_ptr<PrescribedMotion<Real>> motion;
  // Where the constraint forces on these points go after each solve, when something reads them
  // (null otherwise): Σ_rows c λ / h per point, SOFA's λ vector on the state divided by the step as
  // its next step starts, which a DistanceMapping's geometric stiffness reads. Shared by every
  // constraint on the state; the loop zeroes it before adding each solve's forces.
  std::shared_ptr<std::vector<Vec3<Real>>> constraint_force;

  // Filled each step by prepare(): where the points were when the step began, and where the free
  // motion takes them. Mapped points move as SOFA moves them: x + h J v_free, J at the step's start.
  std::vector<Vec3<Real>> position, free_position, free_velocity;

  std::size_t size() const { return unsimulated ? position.size() : mapping ? mapping->size() : blocks.size(); }
  // From the object's start (x, v) and free (x_f, v_f) states, h the step.
  void prepare(const MechanicalState<Real>& start, const MechanicalState<Real>& free, Real h);
};

// The rows of one step's constraints: for each simulated object, the entries of H on its blocks.
template <class Real>
class ConstraintRows {
 public:
  explicit ConstraintRows(std::size_t objects) : entries_(objects) {}
  int size() const { return rows_; }
  // Reserves `count` new rows; returns the first.
  int add_rows(int count) {
    const int first = rows_;
    rows_ += count;
    return first;
  }
  // H(row, point i of `points`) += cᵀ: on the point's block, or through its mapping (Jᵀ c on each
  // parent block the point reads); nothing on unsimulated points.
  void add(int row, const ConstraintPoints<Real>& points, std::size_t i, const Vec3<Real>& c);
  // H(row, b) += Mᵀ c for each (b, M) of `blocks`: a point of simulated object `object` whose rows of
  // J on the object's blocks are given (a contact point on a collision model).
  void add_blocks(int row, std::size_t object, std::span<const std::pair<Index, Mat3<Real>>> blocks, const Vec3<Real>& c) {
    for (const auto& [block, m] : blocks) entries_[object].push_back({row, block, m.transpose() * c});
  }
  // constraint_force[i] += c λ_row / h for every row added on points that keep their constraint
  // forces (the caller zeroes the sinks first, sized to their points).
  void store_constraint_forces(const Real* lambda, Real h) const;
  // Whether object o has any entry.
  bool touches(std::size_t o) const { return !entries_[o].empty(); }
  // Hᵀ restricted to object o's blocks: (3 × points) × rows, column r = row r.
  Eigen::SparseMatrix<Real> transposed(std::size_t o, Index points) const;

 private:
  struct Entry {
    int row;
    Index block;
    Vec3<Real> value;
  };
  struct KeptEntry {
    int row;
    std::vector<Vec3<Real>>* sink;
    std::size_t point;
    Vec3<Real> value;
  };
  int rows_ = 0;
  std::vector<std::vector<Entry>> entries_;
  std::vector<KeptEntry> kept_;
  mutable std::vector<std::pair<Index, Mat3<Real>>> row_blocks_;
};

}  // namespace fastcorot
