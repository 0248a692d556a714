// Regular grid points and their split into tetrahedra, numbered as SOFA numbers them.
//
// Where each convention comes from (sofa-framework/sofa, current master; facts in our own words):
//
// * Point order. Sofa/Component/Topology/Container/Grid/src/sofa/component/topology/container/grid/
//   GridTopology.cpp, GridTopology::getIndex: point (i, j, k) has index i + nx * (j + ny * k), so x
//   varies fastest and z slowest; getPoint(index) inverts this with % and / in the same order.
//
// * Point positions. RegularGridTopology.cpp in the same folder, setPos and getPointInGrid: the
//   step along an axis is (max - min) / (n - 1) for that axis, stored as a vector that is zero on
//   the two other axes; the origin p0 is min; a point is evaluated as p0 + dx * i + dy * j + dz * k
//   with Vec3 arithmetic, left to right. The MechanicalObject reads its rest positions from these
//   (getPX/getPY/getPZ go through getPoint). We evaluate the same sums in the same order, zero
//   components included, so the result is bitwise SOFA's (the zero terms only turn -0 into +0).
//
// * Hexahedron corner order. GridTopology.cpp, GridUpdate::updateHexas and getHexahedron(x, y, z):
//   cell (x, y, z) lists its corners as the bottom face (z) counter-clockwise seen from +z,
//   starting at the cell's own lowest point, then the top face (z + 1) in the same order:
//     0 (x,y,z)  1 (x+1,y,z)  2 (x+1,y+1,z)  3 (x,y+1,z)  4..7 = 0..3 shifted by +1 in z.
//   Old SOFA had a second, "binary" order (0 (x,y,z) 1 (x+1,y,z) 2 (x,y+1,z) 3 (x+1,y+1,z) ...)
//   behind the SOFA_NEW_HEXA switch; master has dropped the switch and only the order above
//   remains. Cells are listed x fastest, then y, then z (GridTopology::hexa gives
//   x + (nx-1)*(y + (ny-1)*z)).
//
// * Which corners the split sees. Sofa/Component/Topology/Mapping/src/sofa/component/topology/
//   mapping/Hexa2TetraTopologicalMapping.cpp, init(): each hexahedron is fetched with
//   getHexahedron(i), which for a grid is MeshTopology::getHexahedron, i.e. entry i of the
//   hexahedron array built by updateHexas
//   (Sofa/Component/Topology/Container/Constant/.../MeshTopology.cpp).
//   So the split tables index corners in the order above; the old binary-order build used a
//   different table and is gone from master.
//
// * The split (same file). Every hexahedron gives 6 tetrahedra, appended cell after cell. With
//   corners c[0..7] in the order above, the tetrahedra are
//     (c0,c5,c1,c6) (c0,c1,c3,c6) (c1,c3,c6,c2) (c6,c3,c0,c7) (c6,c7,c0,c5) (c7,c5,c4,c0).
//   Each has volume 1/6 of the cell and positive orientation when min < max. Four of them share
//   the body diagonal c0-c6; the bottom face is cut along c1-c3, the top along c5-c7, the y faces
//   along c0-c5 / c3-c6 and the x faces along c0-c7 / c1-c6. Every face is cut in the same
//   direction as its translate in the neighbour cell, so without swapping the mesh is conforming
//   (a translation-invariant pattern).
//
// * swapping="true" (same file). Before splitting, the corner list of cell (x, y, z) is mirrored:
//   along x when x is EVEN (exchange c0<->c1, c3<->c2, c4<->c5, c7<->c6), along y when y is ODD
//   (c0<->c3, c1<->c2, c4<->c7, c5<->c6), along z when z is ODD (c0<->c4, c1<->c5, c2<->c6,
//   c3<->c7). SOFA derives x, y, z from the linear cell index i as i % cx, (i / cx) % cy and
//   i / (cx * cy) with cx, cy the cell counts (n - 1) along x and y, which are exactly the cell's
//   coordinates. Each mirror flips a flag; when an odd number of mirrors was applied (equivalently
//   when x + y + z is even) the mirrored table is used, which is the table above with the last
//   two entries of every tetrahedron exchanged, so that orientation stays positive. Neighbour cells
//   mirror each other across their shared face, so this split is conforming as well.
//   Sofa/Component/Topology/Mapping/tests/Hexa2TetraTopologicalMapping_test.cpp checks the single
//   hexahedron (cell 0, mirrored along x) against the same rule.
#include "fastcorot/topology/regular_grid.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace fastcorot {
namespace {

// Offsets (dx, dy, dz) of the eight corners of a cell, in SOFA's hexahedron order.
constexpr std::array<std::array<Index, 3>, 8> kCornerOffset{{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
}};

// Corner permutations of the three mirrors: mirrored[c] = corners[kMirrorX[c]], etc.
constexpr std::array<int, 8> kMirrorX{1, 0, 3, 2, 5, 4, 7, 6};
constexpr std::array<int, 8> kMirrorY{3, 2, 1, 0, 7, 6, 5, 4};
constexpr std::array<int, 8> kMirrorZ{4, 5, 6, 7, 0, 1, 2, 3};

// Six tetrahedra per cell as local corner numbers; the second table is the first with the last two
// corners of each tetrahedron exchanged, used after an odd number of mirrors.
using SplitTable = std::array<std::array<int, 4>, 6>;
constexpr SplitTable kSplit{{
    {0, 5, 1, 6}, {0, 1, 3, 6}, {1, 3, 6, 2}, {6, 3, 0, 7}, {6, 7, 0, 5}, {7, 5, 4, 0},
}};
constexpr SplitTable kSplitMirrored{{
    {0, 5, 6, 1}, {0, 1, 6, 3}, {1, 3, 2, 6}, {6, 3, 7, 0}, {6, 7, 5, 0}, {7, 5, 0, 4},
}};

constexpr int kTetrahedraPerCell = 6;

std::array<Index, 8> permuted(const std::array<Index, 8>& corners, const std::array<int, 8>& p) {
  std::array<Index, 8> out{};
  for (int c = 0; c < 8; ++c) out[c] = corners[p[c]];
  return out;
}

// Corner indices of cell (i, j, k), no range check.
std::array<Index, 8> corners_unchecked(const RegularGrid& grid, Index i, Index j, Index k) {
  const Index nx = grid.n[0];
  const Index ny = grid.n[1];
  std::array<Index, 8> corners{};
  for (int c = 0; c < 8; ++c) {
    const auto& o = kCornerOffset[c];
    corners[c] = (i + o[0]) + nx * ((j + o[1]) + ny * (k + o[2]));
  }
  return corners;
}

bool finite(const Vec3<double>& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

}  // namespace

void validate(const RegularGrid& grid) {
  const auto& n = grid.n;
  if (n[0] < 1 || n[1] < 1 || n[2] < 1) {
    throw make_error("RegularGrid: n = (", n[0], ", ", n[1], ", ", n[2],
                     "): each count must be at least 1");
  }
  // Points and tetrahedra are numbered with Index; their counts must fit in it.
  const std::int64_t points = std::int64_t{n[0]} * n[1] * n[2];
  const std::int64_t tetrahedra =
      std::int64_t{kTetrahedraPerCell} * (n[0] - 1) * std::int64_t{n[1] - 1} * (n[2] - 1);
  if (points > std::numeric_limits<Index>::max() ||
      tetrahedra > std::numeric_limits<Index>::max()) {
    throw make_error("RegularGrid: n = (", n[0], ", ", n[1], ", ", n[2], "): ", points,
                     " points and ", tetrahedra, " tetrahedra exceed the index range (",
                     std::numeric_limits<Index>::max(), ")");
  }
  const auto& lo = grid.min;
  const auto& hi = grid.max;
  if (!finite(lo)) {
    throw make_error("RegularGrid: min = (", lo.x(), ", ", lo.y(), ", ", lo.z(),
                     "): each coordinate must be finite");
  }
  if (!finite(hi)) {
    throw make_error("RegularGrid: max = (", hi.x(), ", ", hi.y(), ", ", hi.z(),
                     "): each coordinate must be finite");
  }
  if (grid.p0 && !finite(*grid.p0)) {
    throw make_error("RegularGrid: p0 = (", grid.p0->x(), ", ", grid.p0->y(), ", ", grid.p0->z(),
                     "): each coordinate must be finite");
  }
  // SOFA accepts max < min (a mirrored grid, tetrahedra of negative orientation) but a zero extent
  // makes every tetrahedron flat, which the force field cannot use (an axis with one point has no
  // extent to speak of).
  constexpr char kAxis[3] = {'x', 'y', 'z'};
  for (int a = 0; a < 3; ++a) {
    if (n[static_cast<std::size_t>(a)] > 1 && !(lo[a] != hi[a])) {
      throw make_error("RegularGrid: min.", kAxis[a], " = max.", kAxis[a], " = ", lo[a],
                       ": the box has zero extent along ", kAxis[a]);
    }
  }
}

void validate_cells(const RegularGrid& grid) {
  validate(grid);
  const auto& n = grid.n;
  if (n[0] < 2 || n[1] < 2 || n[2] < 2) {
    throw make_error("RegularGrid: n = (", n[0], ", ", n[1], ", ", n[2],
                     "): a grid with a single point along an axis is flat and has no cells (each count must be at "
                     "least 2 for hexahedra or tetrahedra)");
  }
}

template <class Real>
std::vector<Vec3<Real>> grid_points(const RegularGrid& grid) {
  validate(grid);
  const auto& n = grid.n;
  // SOFA's computation in its own scalar: min and max are held in Real, the step is the extent
  // divided by the cell count, and a point is p0 + dx*i + dy*j + dz*k with steps as axis vectors.
  // An axis with a single point (a flat grid: SOFA's setPos) puts it midway between min and max
  // along x and y, at min along z, unless p0 places it; its step is never used.
  Vec3<Real> p0 = grid.origin().template cast<Real>();
  const Vec3<Real> extent = grid.max.template cast<Real>() - grid.min.template cast<Real>();
  for (int a = 0; a < 2; ++a) {
    if (n[static_cast<std::size_t>(a)] == 1 && !grid.p0) p0[a] = (Real(grid.max[a]) + Real(grid.min[a])) / Real(2);
  }
  const auto step = [&](int a) { return n[static_cast<std::size_t>(a)] > 1 ? extent[a] / Real(n[static_cast<std::size_t>(a)] - 1) : Real(0); };
  const Vec3<Real> dx(step(0), Real(0), Real(0));
  const Vec3<Real> dy(Real(0), step(1), Real(0));
  const Vec3<Real> dz(Real(0), Real(0), step(2));

  std::vector<Vec3<Real>> points;
  points.reserve(static_cast<std::size_t>(grid.num_points()));
  for (Index k = 0; k < n[2]; ++k) {
    for (Index j = 0; j < n[1]; ++j) {
      for (Index i = 0; i < n[0]; ++i) {
        const Vec3<Real> p = p0 + dx * Real(i) + dy * Real(j) + dz * Real(k);
        points.push_back(p);
      }
    }
  }
  return points;
}

std::array<Index, 8> grid_cell_corners(const RegularGrid& grid, Index i, Index j, Index k) {
  const auto& n = grid.n;
  if (i < 0 || j < 0 || k < 0 || i >= n[0] - 1 || j >= n[1] - 1 || k >= n[2] - 1) {
    throw make_error("RegularGrid: cell (", i, ", ", j, ", ", k, ") is outside the grid of (",
                     n[0] - 1, ", ", n[1] - 1, ", ", n[2] - 1, ") cells");
  }
  return corners_unchecked(grid, i, j, k);
}

std::vector<Edge> grid_edges(const RegularGrid& grid) {
  validate(grid);
  const auto& n = grid.n;
  const auto point = [&](Index x, Index y, Index z) { return x + n[0] * (y + n[1] * z); };
  std::vector<Edge> edges;
  edges.reserve(static_cast<std::size_t>((n[0] - 1) * n[1] * n[2] + n[0] * (n[1] - 1) * n[2] + n[0] * n[1] * (n[2] - 1)));
  for (int axis = 0; axis < 3; ++axis) {
    const std::array<Index, 3> step{axis == 0, axis == 1, axis == 2};
    for (Index z = 0; z < n[2] - step[2]; ++z) {
      for (Index y = 0; y < n[1] - step[1]; ++y) {
        for (Index x = 0; x < n[0] - step[0]; ++x) edges.push_back({point(x, y, z), point(x + step[0], y + step[1], z + step[2])});
      }
    }
  }
  return edges;
}

std::vector<std::array<Index, 4>> grid_quads(const RegularGrid& grid) {
  validate(grid);
  const auto& n = grid.n;
  const auto point = [&](Index x, Index y, Index z) { return x + n[0] * (y + n[1] * z); };
  std::vector<std::array<Index, 4>> quads;
  for (Index z = 0; z < n[2]; ++z) {  // normal to z
    for (Index y = 0; y < n[1] - 1; ++y) {
      for (Index x = 0; x < n[0] - 1; ++x) quads.push_back({point(x, y, z), point(x + 1, y, z), point(x + 1, y + 1, z), point(x, y + 1, z)});
    }
  }
  for (Index z = 0; z < n[2] - 1; ++z) {  // normal to y
    for (Index y = 0; y < n[1]; ++y) {
      for (Index x = 0; x < n[0] - 1; ++x) quads.push_back({point(x, y, z), point(x + 1, y, z), point(x + 1, y, z + 1), point(x, y, z + 1)});
    }
  }
  for (Index z = 0; z < n[2] - 1; ++z) {  // normal to x
    for (Index y = 0; y < n[1] - 1; ++y) {
      for (Index x = 0; x < n[0]; ++x) quads.push_back({point(x, y, z), point(x, y + 1, z), point(x, y + 1, z + 1), point(x, y, z + 1)});
    }
  }
  return quads;
}

namespace {

// The split of every cell, mirrored as `swapping` says; `follow_mirror` chooses the mirrored split
// table for mirrored cells (Hexa2TetraTopologicalMapping) or keeps the plain one
// (TetrahedronFEMForceField's own tessellation).
std::vector<Tetrahedron> split_cells(const RegularGrid& grid, bool swapping, bool follow_mirror);

}  // namespace

std::vector<Tetrahedron> grid_tetrahedra(const RegularGrid& grid, bool swapping) {
  return split_cells(grid, swapping, true);
}

std::vector<Tetrahedron> tetrahedron_fem_grid_tetrahedra(const RegularGrid& grid) {
  return split_cells(grid, true, false);
}

namespace {

std::vector<Tetrahedron> split_cells(const RegularGrid& grid, bool swapping, bool follow_mirror) {
  validate_cells(grid);
  const auto& n = grid.n;
  std::vector<Tetrahedron> tetrahedra;
  tetrahedra.reserve(static_cast<std::size_t>(kTetrahedraPerCell) *
                     static_cast<std::size_t>(grid.num_cells()));
  for (Index k = 0; k < n[2] - 1; ++k) {
    for (Index j = 0; j < n[1] - 1; ++j) {
      for (Index i = 0; i < n[0] - 1; ++i) {
        std::array<Index, 8> c = corners_unchecked(grid, i, j, k);
        bool mirrored = false;
        if (swapping) {
          // SOFA's parities: x mirrors on even cells, y and z on odd ones.
          if (i % 2 == 0) {
            c = permuted(c, kMirrorX);
            mirrored = !mirrored;
          }
          if (j % 2 == 1) {
            c = permuted(c, kMirrorY);
            mirrored = !mirrored;
          }
          if (k % 2 == 1) {
            c = permuted(c, kMirrorZ);
            mirrored = !mirrored;
          }
        }
        const SplitTable& split = mirrored && follow_mirror ? kSplitMirrored : kSplit;
        for (const auto& t : split) {
          tetrahedra.push_back(Tetrahedron{c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
        }
      }
    }
  }
  return tetrahedra;
}

}  // namespace

std::vector<Tetrahedron> split_hexahedra(std::span<const std::array<Index, 8>> hexahedra, Index cells_x, Index cells_y,
                                         bool swapping, bool follow_mirror) {
  if (cells_x < 1 || cells_y < 1) throw make_error("split_hexahedra: ", cells_x, " x ", cells_y, " cells per layer");
  std::vector<Tetrahedron> tetrahedra;
  tetrahedra.reserve(static_cast<std::size_t>(kTetrahedraPerCell) * hexahedra.size());
  for (std::size_t h = 0; h < hexahedra.size(); ++h) {
    std::array<Index, 8> c = hexahedra[h];
    const auto cell = static_cast<Index>(h);
    bool mirrored = false;
    if (swapping) {
      // SOFA's parities from the hexahedron's index, as in split_cells.
      if ((cell % cells_x) % 2 == 0) {
        c = permuted(c, kMirrorX);
        mirrored = !mirrored;
      }
      if ((cell / cells_x) % cells_y % 2 == 1) {
        c = permuted(c, kMirrorY);
        mirrored = !mirrored;
      }
      if ((cell / (cells_x * cells_y)) % 2 == 1) {
        c = permuted(c, kMirrorZ);
        mirrored = !mirrored;
      }
    }
    const SplitTable& split = mirrored && follow_mirror ? kSplitMirrored : kSplit;
    for (const auto& t : split) tetrahedra.push_back(Tetrahedron{c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
  }
  return tetrahedra;
}

template std::vector<Vec3<float>> grid_points<float>(const RegularGrid& grid);
template std::vector<Vec3<double>> grid_points<double>(const RegularGrid& grid);

}  // namespace fastcorot
