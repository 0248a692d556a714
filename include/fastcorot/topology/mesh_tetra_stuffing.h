// SOFA's MeshTetraStuffing: a tetrahedral volume mesh of the inside of a closed triangle surface by
// isosurface stuffing (F. Labelle and J. R. Shewchuk, "Isosurface Stuffing: Fast Tetrahedral Meshes
// with Good Dihedral Angles", SIGGRAPH 2007), computed as SOFA's engine computes it (master
// 2a278d891f, Engine/Generate/MeshTetraStuffing.cpp): a body-centred cubic lattice (a grid of cell
// `size` and a second grid at its cell centres) over the bounding box; each lattice point is
// classed inside or outside by votes along the lattice's 7 line directions, each line traced
// through the surface once; optionally points close to the surface (closer than alphaLong / alphaShort
// of an edge) are snapped onto it and the tetrahedra crossing the surface are cut at the
// crossings; then the lattice's tetrahedra (4 around each edge of the first grid, in grid order)
// that touch the inside are kept and the unused points dropped, in SOFA's order. As in SOFA, whose
// ray tracing goes through an octree over [-800, 800]^3, triangles reaching beyond that cube are
// not seen.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <vector>

namespace fastcorot {

struct TetraStuffingOptions {
  // SOFA's vbbox (min, max): used as given when min.x < max.x, else the input's bounding box grown
  // by 1% of its size on each side.
  std::array<Vec3<double>, 2> bbox = {Vec3<double>::Zero(), Vec3<double>::Zero()};
  // Cell size; negative: -(number of cells) across the largest extent of the box.
  double size = -8;
  double alpha_long = 0.24999;   // snapping threshold on the grids' own edges, in edge lengths
  double alpha_short = 0.42978;  // snapping threshold on the edges between the two grids
  bool snap_points = false;
  bool split_tetrahedra = false;
};

struct TetraStuffing {
  std::vector<Vec3<double>> points;      // #V×3
  std::vector<Tetrahedron> tetrahedra;   // #T×4, positive volume
  std::array<Vec3<double>, 2> bbox;      // the box used (SOFA writes it back to vbbox)
  double cell_size = 0;
};

// `triangles` and `quads` index `points` (a quad a b c d counts as the triangles a b c and a c d,
// after the triangles). Throws fastcorot::Error for an empty surface, an index out of range, a zero
// or non-finite size, or a lattice too large to store.
TetraStuffing stuff_tetrahedra(const std::vector<Vec3<double>>& points, const std::vector<Triangle>& triangles,
                               const std::vector<std::array<Index, 4>>& quads, const TetraStuffingOptions& options);

}  // namespace fastcorot
