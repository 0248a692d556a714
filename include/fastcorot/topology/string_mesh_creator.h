// SOFA's StringMeshCreator: a one-dimensional mesh of `resolution` points evenly spaced from
// (0, 0, 0) to (1, 0, 0) joined by edges (e-1, e). The scene places it as any loader (scale,
// rotation, translation).
#pragma once

#include "fastcorot/core/types.h"

#include <vector>

namespace fastcorot {

struct StringMesh {
  std::vector<Vec3<double>> points;  // point x at (x / (resolution - 1), 0, 0)
  std::vector<Edge> edges;           // resolution - 1 edges, (x - 1, x)
};

// resolution = 0 gives an empty mesh, as in SOFA; 1 is refused (SOFA divides by zero: a NaN point).
// Throws fastcorot::Error for a negative resolution, 1, or more points than Index holds.
StringMesh string_mesh(long long resolution);

}  // namespace fastcorot
