// SOFA's SphereGridTopology: a grid of n = (nx, ny, nz) points in SOFA's grid order (x fastest)
// whose cube [-r, r]^3 is pressed onto the ball of radius r: each square shell around the centre
// goes to a sphere. Its hexahedra are the regular grid's (grid_cell_corners), so the force fields
// use it as a RegularGridTopology of those point counts.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <vector>

namespace fastcorot {

struct SphereGrid {
  std::array<Index, 3> n{2, 2, 2};
  Vec3<double> center = Vec3<double>::Zero();
  Vec3<double> axis = Vec3<double>::UnitZ();
  double radius = 1;
};

// The points, as SOFA's SphereGridTopology::getPointInGrid computes them: the cube coordinate
// p = (i 2r/(nx-1) - r, j 2r/(ny-1) - r, k 2r/(nz-1) - r), scaled by max(|px|, |py|, |pz|) / |p|
// when |p| > 1e-7, placed at center + X px + Y py + Z pz in the frame of grid_axes (cylinder_grid.h).
// #points = nx ny nz, point (i, j, k) at i + nx (j + ny k). Throws fastcorot::Error for a count
// below 2, a zero or non-finite axis, or a centre or radius that is not finite.
std::vector<Vec3<double>> sphere_grid_points(const SphereGrid& grid);

}  // namespace fastcorot
