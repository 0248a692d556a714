// RigidMapping<Real>: points carried by rigid bodies, SOFA's RigidMapping<Rigid3, Vec3>
// (Sofa/Component/Mapping/NonLinear/src/sofa/component/mapping/nonlinear/RigidMapping.inl).
// Each mapped point i has local coordinates p_i in the frame of one rigid k(i) and follows it:
//   apply:    r_i = rotate(q_k, p_i),  y_i = c_k + r_i
//   apply_j:  v_i = v_k + ω_k × r_i
//   apply_jt: f_k += f_i,  τ_k += r_i × f_i   (accumulated)
// r_i are the rotated offsets of the last `apply`: J is the linearisation there, as in SOFA, where
// init and every propagation of positions run apply first. No geometric stiffness (SOFA's
// `geometricStiffness` default 0). Rigid derivatives are two Vec3 blocks per rigid
// [v0, ω0, v1, ω1, ...] in the world frame (state/rigid3.h).
//
// Local points, as SOFA's init: `initialPoints` when given; else with `useX0` the child's rest
// positions as they are; else the child's positions, as they are (`globalToLocalCoords` false,
// SOFA's default: the child's positions ARE local coordinates), or brought into the frame of their
// rigid at its initial position, p_i = inverse_rotate(q_k, x_i - c_k) (`globalToLocalCoords` true).
// Rigid of each point: `rigidIndexPerPoint` (one per point) else `index` (counted from the last
// rigid with `indexFromEnd`). SOFA silently falls back to `index` when rigidIndexPerPoint has the
// wrong size; this refuses it.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/state/rigid3.h"

#include <Eigen/SparseCore>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
struct RigidMappingOptions {
  std::optional<std::vector<Vec3<Real>>> initial_points;  // `initialPoints` (local coordinates)
  Index index = 0;                                        // `index`
  bool index_from_end = false;                            // `indexFromEnd`
  std::vector<Index> rigid_index_per_point;               // `rigidIndexPerPoint` (empty: unused)
  bool global_to_local_coords = false;                    // `globalToLocalCoords`
  bool use_x0 = false;                                    // `useX0`
};

template <class Real>
class RigidMapping {
 public:
  using SparseMatrix = Eigen::SparseMatrix<Real, Eigen::RowMajor>;

  // `where` names the mapping in errors (file:line and type, as c.where() gives). `rigids`: the
  // input state's positions at init; `child_positions`, `child_rest_positions`: the output state's
  // (the rest positions are read only with use_x0). An empty initial_points counts as not given
  // (SOFA fills an empty list from the child). Throws fastcorot::Error naming `where` and the
  // attribute for a rigidIndexPerPoint whose size is not the number of points, an index out of
  // [0, #rigids), points without rigids, or non-finite local points. Runs apply at `rigids`.
  RigidMapping(std::string where, std::span<const RigidCoord<Real>> rigids,
               std::span<const Vec3<Real>> child_positions, std::span<const Vec3<Real>> child_rest_positions,
               const RigidMappingOptions<Real>& options);

  std::size_t size() const { return local_points_.size(); }     // mapped points (may differ from the
                                                                 // child's count with initialPoints:
                                                                 // SOFA resizes the child)
  std::size_t rigid_count() const { return rigid_count_; }
  std::span<const Vec3<Real>> local_points() const { return local_points_; }
  std::span<const Index> rigid_of_point() const { return rigid_of_point_; }
  std::span<const Vec3<Real>> rotated_points() const { return rotated_; }  // r_i of the last apply

  // y_i = c_k + rotate(q_k, p_i) for the rigid positions (#rigids), into out (size() points);
  // records r_i for apply_j, apply_jt and jacobian.
  void apply(std::span<const RigidCoord<Real>> rigids, std::span<Vec3<Real>> out);
  std::vector<Vec3<Real>> apply(std::span<const RigidCoord<Real>> rigids);

  // v_i = v_k + ω_k × r_i; rigid_derivs is 2 #rigids blocks, out size() points.
  void apply_j(std::span<const Vec3<Real>> rigid_derivs, std::span<Vec3<Real>> out) const;
  std::vector<Vec3<Real>> apply_j(std::span<const Vec3<Real>> rigid_derivs) const;

  // rigid_blocks[2k] += Σ f_i, rigid_blocks[2k+1] += Σ r_i × f_i over the points of rigid k.
  void apply_jt(std::span<const Vec3<Real>> point_forces, std::span<Vec3<Real>> rigid_blocks) const;

  // J (3 size() × 6 #rigids): row block i, column block k(i) = [I₃ | -[r_i]×]; the rows' pattern is
  // fixed (the identity and the two off-diagonal entries of the skew part; SOFA's getJs stores the
  // nonzero ones only).
  SparseMatrix jacobian() const;

 private:
  void check_rigid_count(std::size_t rigids, const char* what) const;

  std::string where_;
  std::size_t rigid_count_ = 0;
  std::vector<Vec3<Real>> local_points_;
  std::vector<Index> rigid_of_point_;
  std::vector<Vec3<Real>> rotated_;
};

}  // namespace fastcorot
