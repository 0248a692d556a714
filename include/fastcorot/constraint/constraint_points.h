// Where Lagrangian constraints act: ConstraintPoints, the points of one MechanicalObject (a
// simulated object's own points, or a mapped state that follows them), and ConstraintRows, the rows
// of H they write, carried down to the simulated objects' blocks through the points' mapping (SOFA's
// buildConstraintMatrix then applyJT on the constraint Jacobian, MechanicalAccumulateMatrixDeriv).
// Design: docs/constraints.md.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/sim/mechanical_state.h"

#include <Eigen/SparseCore>

#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

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
  int rows_ = 0;
  std::vector<std::vector<Entry>> entries_;
  mutable std::vector<std::pair<Index, Mat3<Real>>> row_blocks_;
};

}  // namespace fastcorot
