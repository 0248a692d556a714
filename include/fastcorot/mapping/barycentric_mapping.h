// BarycentricMapping<Real>: points (a visual surface) that follow a tetrahedral mesh, each as a
// fixed barycentric combination of the four vertices of one tetrahedron, as SOFA's
// BarycentricMapping with a tetrahedral input topology (its BarycentricMapperTetrahedronSetTopology)
// places them: the tetrahedron that contains the point, the point deepest inside when several do
// (the largest smallest barycentric coordinate), else the tetrahedron whose centre is nearest,
// searched among the tetrahedra whose bounding boxes meet the point's cell of a grid of the mesh's
// mean edge length (and the 26 cells around it when the point lies far from that choice), as SOFA
// searches. A point inside the mesh follows it exactly; a point outside follows the nearest
// tetrahedron's affine motion (coordinates outside [0, 1]).
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/topology/tet_mesh.h"

#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
struct BarycentricMapping {
  std::vector<Index> tetrahedron;            // per mapped point
  std::vector<Vec3<Real>> coordinates;       // SOFA's baryCoords f: weights (1 - f0 - f1 - f2, f0, f1, f2)

  std::size_t size() const { return tetrahedron.size(); }
  // out[i] = sum_j weight_ij x[tetrahedron_i[j]] (out has size() points).
  void apply(const TetMesh& mesh, std::span<const Vec3<Real>> x, std::span<Vec3<Real>> out) const;
};

// How the candidate tetrahedra of a point are found: SOFA's TetrahedronSetTopologyContainer mapper
// searches a grid (above); its MeshTopology mapper tries every tetrahedron, with the same rule.
enum class TetrahedronSearch { grid, exhaustive };

// The mapping of `points` onto `mesh` at positions `x` (the input state when the mapping is made:
// SOFA's init). Throws fastcorot::Error for a mesh without tetrahedra or a non-finite point.
template <class Real>
BarycentricMapping<Real> map_onto_tetrahedra(const TetMesh& mesh, std::span<const Vec3<Real>> x,
                                             std::span<const Vec3<Real>> points,
                                             TetrahedronSearch search = TetrahedronSearch::grid);

}  // namespace fastcorot
