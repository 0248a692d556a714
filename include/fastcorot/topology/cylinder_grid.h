// SOFA's CylinderGridTopology: a grid of n = (nx, ny, nz) points in SOFA's grid order (x fastest)
// whose square cross-sections are pressed onto discs of the given radius, stacked along the axis
// over the given length from the centre. Its hexahedra are the regular grid's, so a
// TetrahedronFEMForceField on it splits them as on a RegularGridTopology.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <vector>

namespace fastcorot {

struct CylinderGrid {
  std::array<Index, 3> n{2, 2, 2};
  Vec3<double> center = Vec3<double>::Zero();
  Vec3<double> axis = Vec3<double>::UnitZ();
  double radius = 1;
  double length = 1;
};

// The frame SOFA's cylinder and sphere grids place their points in: Z the unit axis,
// Y = Z x (1, 0, 0) (or Z x (0, 1, 0) when the axis is x), X = Y x Z, each normalised as SOFA does.
std::array<Vec3<double>, 3> grid_axes(const Vec3<double>& axis);

// The points, as SOFA's getPointInGrid computes them: the square coordinate (i 2r/(nx-1) - r,
// j 2r/(ny-1) - r) scaled by max(|x|, |y|) / |(x, y)| (a square ring onto a circle), k l/(nz-1)
// along the axis (0 when nz = 1), in the frame X = (Y x Z), Y = Z x (1, 0, 0) (or (0, 1, 0) when
// the axis is x), Z the unit axis. Throws fastcorot::Error for a count below 2 across the axis, a
// count below 1 along it, a zero or non-finite axis, or a radius or length that is not finite.
std::vector<Vec3<double>> cylinder_grid_points(const CylinderGrid& grid);

}  // namespace fastcorot
