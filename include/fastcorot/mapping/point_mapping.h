// PointMapping<Real>: a linear mapping from a parent's points to a child's, each child point a
// weighted sum of up to eight parent points: y_i = sum_k w_ik x[v_ik]. It is the one form of SOFA's
// IdentityMapping, SubsetMapping and BarycentricMapping (tetrahedral: four weights; trilinear on a
// RegularGridTopology: eight), so its Jacobian J is the weights themselves (times the 3×3
// identity), constant in time. A mapping carries positions and velocities down (apply: y = J x,
// v_y = J v_x) and forces back up (apply_jt: f_x += Jᵀ f_y), as SOFA's Mapping::apply, applyJ and
// applyJT do (docs/mechanical-graph.md).
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/barycentric_mapping.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tet_mesh.h"

#include <Eigen/SparseCore>

#include <array>
#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
struct PointMapping {
  static constexpr int kSlots = 8;
  std::vector<std::array<Index, kSlots>> vertices;  // unused slots: vertex 0, weight 0
  std::vector<std::array<Real, kSlots>> weights;

  std::size_t size() const { return vertices.size(); }
  // out[i] = sum_k weights[i][k] x[vertices[i][k]] (SOFA's apply, and applyJ: the mapping is
  // linear); throws for a wrong output size.
  void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> out) const;
  // parent_forces += Jᵀ forces: each child point's force goes to its parents, weighted (SOFA's
  // applyJT). Child points are visited in order, so the sums are the same bits on every run.
  void apply_jt(std::span<const Vec3<Real>> forces, std::span<Vec3<Real>> parent_forces) const;
  // The largest parent index used plus one (0 for an empty mapping).
  Index parent_extent() const;
  // J as a scalar matrix (size() × parent_count), one weight per (child, parent) pair (repeated
  // parents of one child summed); the 3D Jacobian is J ⊗ I3.
  Eigen::SparseMatrix<Real, Eigen::RowMajor> matrix(Index parent_count) const;

  // This mapping applied after `inner` (a chain parent → inner's children → this mapping's): the
  // child i of the result is sum_k w_ik sum_l inner.w_{v_ik, l} parent[inner.v_{v_ik, l}]. Throws
  // fastcorot::Error when a point would depend on more than kSlots parent points.
  PointMapping after(const PointMapping& inner) const;

  static PointMapping identity(std::size_t count);
  // Point i is x[indices[i]] (SOFA's SubsetMapping).
  static PointMapping subset(std::span<const Index> indices);
  // The weights (1 - f0 - f1 - f2, f0, f1, f2) of each point's tetrahedron.
  static PointMapping from_barycentric(const TetMesh& mesh, const BarycentricMapping<Real>& mapping);
  // SOFA's BarycentricMapperRegularGridTopology: each point in the cell of `grid` that contains it
  // (located with the grid's own geometry, not the state's positions, as SOFA does), else in the
  // nearest cell by clamping, with the trilinear weights of its fractional coordinates (which lie
  // outside [0, 1] for a point outside the grid).
  static PointMapping trilinear(const RegularGrid& grid, std::span<const Vec3<Real>> points);
};

}  // namespace fastcorot
