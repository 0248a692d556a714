// The springs SOFA's RegularGridSpringForceField makes on a RegularGridTopology: along the grid's
// lines (x, then y, then z), across each face of each cell (both diagonals, in the xy, xz, yz planes
// in turn) and across each cell (its four diagonals). Each kind whose stiffness or damping is not
// zero is made; the rest length is that of the grid's spacing vectors (dx, dy, dz and their sums),
// not of the state's positions, and each spring's stiffness and damping are the kind's values
// divided by that rest length. The order is SOFA's, so that the springs, their forces and tangents
// are the ones SOFA computes in its addForce.
#pragma once

#include "fastcorot/fem/spring_force_field.h"
#include "fastcorot/topology/regular_grid.h"

#include <vector>

namespace fastcorot {

// RegularGridSpringForceField's per-kind values (SOFA's defaults: stiffness 100, damping 5 each;
// its `stiffness` and `damping` set all three kinds).
template <class Real>
struct RegularGridSpringParameters {
  Real lines_stiffness = 100, lines_damping = 5;
  Real quads_stiffness = 100, quads_damping = 5;
  Real cubes_stiffness = 100, cubes_damping = 5;
};

// The grid's springs on points numbered as RegularGridTopology numbers them (i + nx (j + ny k)).
// Throws fastcorot::Error for an invalid grid (validate) or a non-finite or negative value.
template <class Real>
std::vector<Spring<Real>> regular_grid_springs(const RegularGrid& grid, const RegularGridSpringParameters<Real>& parameters);

}  // namespace fastcorot
