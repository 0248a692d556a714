// VisualSurface: a visual model of SOFA (an OglModel in a child node of a simulated object) whose
// points follow the object's points through a mapping: BarycentricMapping (onto the tetrahedra, or,
// when the object's first topology is a RegularGridTopology, trilinearly onto its cells, as SOFA
// chooses) or IdentityMapping. Display only: the physics never reads it. PointMapping is the
// mapping in one form for all three: each mapped point a weighted sum of up to eight points.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/sim/barycentric_mapping.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tet_mesh.h"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
struct PointMapping {
  static constexpr int kSlots = 8;
  std::vector<std::array<Index, kSlots>> vertices;  // unused slots: vertex 0, weight 0
  std::vector<std::array<Real, kSlots>> weights;

  std::size_t size() const { return vertices.size(); }
  // out[i] = sum_k weights[i][k] x[vertices[i][k]]; throws for a wrong output size.
  void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> out) const;

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

struct VisualSurface {
  std::string path;                      // the visual model: node path / name
  std::vector<Vec3<double>> rest_points;  // the model's points as loaded and placed
  std::vector<Triangle> triangles;
  std::array<float, 4> color{0.8f, 0.8f, 0.8f, 1.0f};
  std::string mapping;  // "BarycentricMapping (tetrahedra)", ... for messages and docs
  PointMapping<double> map;

  // The surface's points for the object's positions x.
  std::vector<Vec3<double>> points(std::span<const Vec3<double>> x) const;
};

}  // namespace fastcorot
