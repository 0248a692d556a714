// A regular grid of hexahedral cells split into tetrahedra, numbered exactly as SOFA numbers them:
// points in RegularGridTopology order and tetrahedra in Hexa2TetraTopologicalMapping order (with or
// without its `swapping` option). Scenes use it for RegularGridTopology; tests and benchmarks use it
// to build named meshes such as the 40×10×10 cantilever beam.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <optional>
#include <span>
#include <vector>

namespace fastcorot {

// SOFA's RegularGridTopology: n = (nx, ny, nz) points per axis (each >= 2 for a grid of cells),
// spanning the box [min, max]. Point (i, j, k) has index i + nx * (j + ny * k) and position
// p0 + (i * (max-min).x / (nx-1), ...) per axis, where p0 (SOFA's attribute of that name: where
// point 0 goes, the box keeping its size) defaults to min.
struct RegularGrid {
  std::array<Index, 3> n{2, 2, 2};
  Vec3<double> min{0.0, 0.0, 0.0};
  Vec3<double> max{1.0, 1.0, 1.0};
  std::optional<Vec3<double>> p0;

  Vec3<double> origin() const { return p0 ? *p0 : min; }

  Index num_points() const { return n[0] * n[1] * n[2]; }
  Index num_cells() const { return (n[0] - 1) * (n[1] - 1) * (n[2] - 1); }
};

// Throws fastcorot::Error when a count is below 1, min/max are not finite, min equals max along an
// axis with several points, or the point or tetrahedron count does not fit in Index. (A count of 1
// makes a flat grid: points, lines and quads, as SOFA's target grids use, but no cells; max < min
// is accepted, as SOFA accepts it, and mirrors the grid.)
void validate(const RegularGrid& grid);
// validate, and every count at least 2: what hexahedra and tetrahedra need.
void validate_cells(const RegularGrid& grid);

// #points positions in RegularGridTopology order, evaluated in Real exactly as SOFA evaluates them
// in its own scalar (step = (max-min)/(n-1), point = min + step.x*i + step.y*j + step.z*k; an axis
// with one point puts it at the middle of x's or y's range, at z's min), so Real = double reproduces
// SOFA's double build bitwise. Validates the grid first.
template <class Real>
std::vector<Vec3<Real>> grid_points(const RegularGrid& grid);

// The eight corner point indices of cell (i, j, k), in SOFA's hexahedron vertex order: bottom face
// (k) counter-clockwise seen from +z starting at point (i, j, k), then the top face (k+1) the same
// way: (i,j,k) (i+1,j,k) (i+1,j+1,k) (i,j+1,k), then the same four at k+1. Throws fastcorot::Error
// when the cell is outside 0 <= i < nx-1 (and likewise for j, k).
std::array<Index, 8> grid_cell_corners(const RegularGrid& grid, Index i, Index j, Index k);

// The grid's lines (SOFA's GridTopology edges): those along x, then y, then z, each family with x
// fastest, then y, then z; and its quads: the faces normal to z (corners (x,y) (x+1,y) (x+1,y+1)
// (x,y+1)), then to y, then to x, in the same loop order. Validates first.
std::vector<Edge> grid_edges(const RegularGrid& grid);
std::vector<std::array<Index, 4>> grid_quads(const RegularGrid& grid);

// Tetrahedra of Hexa2TetraTopologicalMapping applied to the grid's hexahedra (cells in SOFA's
// hexahedron order, x fastest): 6 per cell, tetrahedra 6c..6c+5 from cell c, all positively
// oriented when min < max, and a conforming mesh. `swapping` as SOFA's attribute of that name:
// cell (i, j, k) is mirrored along x when i is even, along y when j is odd and along z when k is
// odd before it is split. The tables and their sources are in regular_grid.cpp. Validates first.
std::vector<Tetrahedron> grid_tetrahedra(const RegularGrid& grid, bool swapping);

// The tetrahedra TetrahedronFEMForceField makes itself from a grid's hexahedra when its topology
// has no tetrahedra (its init): cells mirrored as with `swapping`, but always split with the plain
// table, so that mirrored cells give negatively oriented tetrahedra (which it accepts: it uses |V|).
std::vector<Tetrahedron> tetrahedron_fem_grid_tetrahedra(const RegularGrid& grid);

// The same splits for any list of hexahedra (corners in SOFA's order), as SOFA's
// Hexa2TetraTopologicalMapping (follow_mirror = true) and TetrahedronFEMForceField (swapping = true,
// follow_mirror = false) apply them to a topology that is not a grid: hexahedron h is
// taken as cell (h % cells_x, (h / cells_x) % cells_y, h / (cells_x cells_y)) for the parities,
// with SOFA's cells_x = 2, cells_y = 1 for a topology that is not a grid. `swapping` mirrors as
// above; `follow_mirror` uses the mirrored table after an odd number of mirrors (the mapping), else
// the plain table always (TetrahedronFEMForceField, which mirrors with swapping = true). Throws
// fastcorot::Error when cells_x or cells_y is below 1.
std::vector<Tetrahedron> split_hexahedra(std::span<const std::array<Index, 8>> hexahedra, Index cells_x, Index cells_y,
                                         bool swapping, bool follow_mirror);

}  // namespace fastcorot
