// The triangles and edges of a tetrahedral mesh as SOFA numbers them: TetrahedronSetTopologyContainer's
// triangle array (each tetrahedron's faces in the order (1 2 3), (0 3 2), (1 3 0), (0 2 1), each
// rotated to start at its smallest vertex, kept the first time it appears in either orientation),
// and Tetra2TriangleTopologicalMapping's boundary (those of the array that bound one tetrahedron,
// in the array's order); the container's edge array (each tetrahedron's edges (0 1), (0 2), (0 3),
// (1 2), (1 3), (2 3), each written smallest vertex first, kept the first time it appears).
#pragma once

#include "fastcorot/core/types.h"

#include <span>
#include <vector>

namespace fastcorot {

std::vector<Triangle> tetrahedron_set_triangles(std::span<const Tetrahedron> tetrahedra);
std::vector<Edge> tetrahedron_set_edges(std::span<const Tetrahedron> tetrahedra);

// flip_normals: each triangle written (a, c, b), as the mapping's flipNormals does.
std::vector<Triangle> boundary_triangles(std::span<const Tetrahedron> tetrahedra, bool flip_normals = false);

}  // namespace fastcorot
