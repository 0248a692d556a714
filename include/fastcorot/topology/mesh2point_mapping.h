// SOFA's Mesh2PointTopologicalMapping: an output point set made of points placed relative to each
// element of an input mesh (its points, edges, triangles, quads, tetrahedra, hexahedra), for
// collision spheres or markers that follow a mesh. Only the initial placement is computed here.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <span>
#include <vector>

namespace fastcorot {

struct Mesh2PointInput {
  std::span<const Vec3<double>> points;
  std::span<const Edge> edges;
  std::span<const Triangle> triangles;
  std::span<const std::array<Index, 4>> quads;
  std::span<const Tetrahedron> tetrahedra;
  std::span<const std::array<Index, 8>> hexahedra;
};

// The coordinates of each output point inside its element (SOFA's data of the same names).
struct Mesh2PointCoords {
  std::vector<Vec3<double>> point, edge, triangle, quad, tetra, hexa;
};

// The output points in SOFA's order: for each input point, then each edge, triangle, quad,
// tetrahedron and hexahedron (element by element, one point per coordinate of that kind):
//   point:       p + c (an offset)
//   edge:        p0 (1-cx) + p1 cx
//   triangle:    p0 (1-cx-cy) + p1 cx + p2 cy
//   quad:        p0 (1-cx)(1-cy) + p1 cx (1-cy) + p2 (1-cx) cy + p3 cx cy (SOFA's corners in quad
//                order, so p2 and p3 are not the bilinear pair: kept as SOFA computes it)
//   tetrahedron: p0 (1-cx-cy-cz) + p1 cx + p2 cy + p3 cz
//   hexahedron:  trilinear over corners 0 1 3 2 4 5 7 6 (x, y, z from corner 0)
// Throws fastcorot::Error naming the element when one of its indices is outside the points.
std::vector<Vec3<double>> mesh2point_points(const Mesh2PointInput& input, const Mesh2PointCoords& coords);

}  // namespace fastcorot
