// SOFA's GenerateGrid engine: a box [min, max] cut into resolution = (L, W, H) cells, as points and
// hexahedra split into tetrahedra (H > 0) or, for a flat grid (H = 0), quads split into triangles,
// each numbered exactly as SOFA's GenerateGrid numbers them (its cells run x slowest, z fastest,
// unlike RegularGridTopology's).
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <vector>

namespace fastcorot {

using Quad = std::array<Index, 4>;
using Hexahedron = std::array<Index, 8>;

struct GeneratedGrid {
  std::vector<Vec3<double>> points;    // (L+1)(W+1)(H+1) points
  std::vector<Hexahedron> hexahedra;   // L W H when H > 0, else none
  std::vector<Tetrahedron> tetrahedra; // 6 per hexahedron, tetrahedra 6c..6c+5 from hexahedron c
  std::vector<Quad> quads;             // L W when H = 0, else none
  std::vector<Triangle> triangles;     // 2 per quad
};

// Point (i, j, k) is i + (L+1) (j + (W+1) k) at min + (i (max-min).x / L, j (max-min).y / W,
// k (max-min).z / H) (z = min.z when H = 0). Hexahedron (i, j, k), i slowest and k fastest, has the
// corners of grid_cell_corners (regular_grid.h): (i,j,k) (i+1,j,k) (i+1,j+1,k) (i,j+1,k), then the
// same four at k+1, and the tetrahedra (0 5 1 6) (0 1 3 6) (1 3 6 2) (6 3 0 7) (6 7 0 5) (7 5 4 0)
// of its corners. Quad (i, j), i slowest, is (i,j) (i+1,j) (i+1,j+1) (i,j+1) and its triangles
// (0 1 3) (3 1 2). Throws fastcorot::Error for L or W below 1, H below 0 (SOFA replaces a zero L
// or W by 1 after an error message), non-finite corners, or more points than Index holds.
GeneratedGrid generate_grid(const Vec3<double>& min, const Vec3<double>& max, const std::array<long long, 3>& resolution);

}  // namespace fastcorot
