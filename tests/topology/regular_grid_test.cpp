// Tests of the regular grid: SOFA's point order and positions (checked bitwise against positions
// SOFA itself wrote, tests/data/sofa_reference), SOFA's hexahedron corner order, and the
// Hexa2TetraTopologicalMapping split with and without `swapping` (hand-derived tables below, plus
// property checks: positive volumes that exactly fill each cell, conforming faces, the parity
// rule).
#include "fastcorot/topology/regular_grid.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

RegularGrid make_grid(Index nx, Index ny, Index nz, Vec3<double> lo, Vec3<double> hi) {
  RegularGrid grid;
  grid.n = {nx, ny, nz};
  grid.min = lo;
  grid.max = hi;
  return grid;
}

RegularGrid unit_grid(Index nx, Index ny, Index nz) {
  return make_grid(nx, ny, nz, Vec3<double>(0, 0, 0), Vec3<double>(1, 1, 1));
}

// The grid of every beam of four_beams.scn: min="-5 -5 0" max="5 5 40" n="5 5 20".
RegularGrid four_beams_grid() {
  return make_grid(5, 5, 20, Vec3<double>(-5, -5, 0), Vec3<double>(5, 5, 40));
}

double signed_volume(const std::vector<Vec3<double>>& x, const Tetrahedron& t) {
  const Vec3<double> a = x[t[1]] - x[t[0]];
  const Vec3<double> b = x[t[2]] - x[t[0]];
  const Vec3<double> c = x[t[3]] - x[t[0]];
  return a.dot(b.cross(c)) / 6.0;
}

// The message of the fastcorot::Error that `f` throws, or "" if it throws none.
template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Grids the property tests run on: one cell, even and odd cell counts on each axis, non-cubic
// cells, a box away from the origin, and the four-beam grid.
std::vector<RegularGrid> property_grids() {
  return {
      unit_grid(2, 2, 2),
      unit_grid(3, 3, 2),
      make_grid(4, 3, 5, Vec3<double>(-1.5, 2.0, 0.25), Vec3<double>(2.0, 3.5, 7.0)),
      make_grid(3, 4, 4, Vec3<double>(10, -20, 30), Vec3<double>(11, -17, 31.5)),
      four_beams_grid(),
  };
}

// ---------------------------------------------------------------------------------------------
// Points

TEST(RegularGridTest, PointIndexIsXFastestThenYThenZ) {
  const RegularGrid grid =
      make_grid(3, 4, 5, Vec3<double>(-1.0, 2.0, 0.5), Vec3<double>(2.0, 3.0, 7.0));
  const auto x = grid_points<double>(grid);
  ASSERT_EQ(x.size(), 60u);
  ASSERT_EQ(grid.num_points(), 60);
  const double sx = (2.0 - -1.0) / 2;
  const double sy = (3.0 - 2.0) / 3;
  const double sz = (7.0 - 0.5) / 4;
  for (Index k = 0; k < 5; ++k) {
    for (Index j = 0; j < 4; ++j) {
      for (Index i = 0; i < 3; ++i) {
        const Index id = i + 3 * (j + 4 * k);
        EXPECT_EQ(x[id].x(), -1.0 + sx * i) << "point " << id;
        EXPECT_EQ(x[id].y(), 2.0 + sy * j) << "point " << id;
        EXPECT_EQ(x[id].z(), 0.5 + sz * k) << "point " << id;
      }
    }
  }
  EXPECT_EQ(x.front(), grid.min);
  EXPECT_NEAR((x.back() - grid.max).norm(), 0.0, 1e-15);
}

// Reference: tests/data/sofa_reference/four_beams_trajectory.json, steps."0"."root/BeamFEM_SMALL",
// the rest positions SOFA master (2a278d891f, double) gave the MechanicalObject after init for
// RegularGridTopology min="-5 -5 0" max="5 5 40" n="5 5 20" (four_beams.scn). Bitwise equality.
TEST(RegularGridTest, PointsMatchSofaFourBeamsBitwise) {
  std::ifstream file(std::string(FASTCOROT_SOFA_REFERENCE_DIR) + "/four_beams_trajectory.json");
  ASSERT_TRUE(file) << "cannot open four_beams_trajectory.json";
  const nlohmann::json reference = nlohmann::json::parse(file);
  const auto& sofa = reference.at("steps").at("0").at("root/BeamFEM_SMALL");

  const auto x = grid_points<double>(four_beams_grid());
  ASSERT_EQ(sofa.size(), x.size());
  ASSERT_EQ(x.size(), 500u);
  for (std::size_t p = 0; p < x.size(); ++p) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(x[p][a], sofa[p][a].get<double>()) << "point " << p << " axis " << a;
    }
  }
}

TEST(RegularGridTest, FloatPointsAreComputedInFloat) {
  const RegularGrid grid = four_beams_grid();
  const auto xf = grid_points<float>(grid);
  const auto xd = grid_points<double>(grid);
  ASSERT_EQ(xf.size(), xd.size());
  const float sz = (40.0f - 0.0f) / 19.0f;
  for (Index k = 0; k < 20; ++k) {
    const Index id = 5 * 5 * k + 3 + 5 * 1;  // point (3, 1, k)
    EXPECT_EQ(xf[id].x(), -5.0f + 2.5f * 3.0f);
    EXPECT_EQ(xf[id].y(), -5.0f + 2.5f * 1.0f);
    EXPECT_EQ(xf[id].z(), 0.0f + sz * float(k));
  }
  for (std::size_t p = 0; p < xf.size(); ++p) {
    EXPECT_NEAR((xf[p].cast<double>() - xd[p]).norm(), 0.0, 1e-5) << "point " << p;
  }
}

// ---------------------------------------------------------------------------------------------
// Cells

// GridTopology::getHexahedron: bottom face counter-clockwise from the cell's lowest point, then the
// top face the same way. For n = (2,2,2), point (i,j,k) = i + 2j + 4k.
TEST(RegularGridTest, CellCornersFollowSofaHexahedronOrder) {
  EXPECT_EQ(grid_cell_corners(unit_grid(2, 2, 2), 0, 0, 0),
            (std::array<Index, 8>{0, 1, 3, 2, 4, 5, 7, 6}));
  // n = (3,3,2): point (i,j,k) = i + 3j + 9k; cell (1,1,0) has its lowest point at 4.
  EXPECT_EQ(grid_cell_corners(unit_grid(3, 3, 2), 1, 1, 0),
            (std::array<Index, 8>{4, 5, 8, 7, 13, 14, 17, 16}));

  // Geometric form of the same order on a non-cubic grid.
  const RegularGrid grid =
      make_grid(4, 3, 5, Vec3<double>(-1.5, 2.0, 0.25), Vec3<double>(2.0, 3.5, 7.0));
  const auto x = grid_points<double>(grid);
  const Vec3<double> step((2.0 + 1.5) / 3, (3.5 - 2.0) / 2, (7.0 - 0.25) / 4);
  const int offset[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (Index k = 0; k < 4; ++k) {
    for (Index j = 0; j < 2; ++j) {
      for (Index i = 0; i < 3; ++i) {
        const auto c = grid_cell_corners(grid, i, j, k);
        EXPECT_EQ(c[0], i + 4 * (j + 3 * k));
        for (int v = 0; v < 8; ++v) {
          const Vec3<double> d = x[c[v]] - x[c[0]];
          for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(d[a], offset[v][a] * step[a], 1e-12) << "corner " << v;
          }
        }
      }
    }
  }
}

TEST(RegularGridTest, CellCornersRejectCellsOutsideTheGrid) {
  const RegularGrid grid = unit_grid(3, 3, 2);
  EXPECT_EQ(error_message([&] { grid_cell_corners(grid, 2, 0, 0); }),
            "RegularGrid: cell (2, 0, 0) is outside the grid of (2, 2, 1) cells");
  EXPECT_THROW(grid_cell_corners(grid, 0, 0, 1), Error);
  EXPECT_THROW(grid_cell_corners(grid, -1, 0, 0), Error);
}

// ---------------------------------------------------------------------------------------------
// Tetrahedra: exact tables derived by hand from SOFA's rule.
//
// Hexa2TetraTopologicalMapping splits corners c0..c7 (SOFA hexahedron order) into
//   plain:    (c0,c5,c1,c6) (c0,c1,c3,c6) (c1,c3,c6,c2) (c6,c3,c0,c7) (c6,c7,c0,c5) (c7,c5,c4,c0)
//   mirrored: (c0,c5,c6,c1) (c0,c1,c6,c3) (c1,c3,c2,c6) (c6,c3,c7,c0) (c6,c7,c5,c0) (c7,c5,c0,c4)
// With swapping, cell (x,y,z) first exchanges its corners: along x if x even (c0c1 c3c2 c4c5 c7c6),
// along y if y odd (c0c3 c1c2 c4c7 c5c6), along z if z odd (c0c4 c1c5 c2c6 c3c7); the mirrored
// table is used when an odd number of exchanges happened.
//
// n = (2,2,2), one cell, c = [0,1,3,2,4,5,7,6].
//   plain:     (0,5,1,7) (0,1,2,7) (1,2,7,3) (7,2,0,6) (7,6,0,5) (6,5,4,0)
//   swapping:  x = 0 is even, so exchange along x: c0'=c1=1, c1'=c0=0, c2'=c3=2, c3'=c2=3,
//              c4'=c5=5, c5'=c4=4, c6'=c7=6, c7'=c6=7, i.e. c' = [1,0,2,3,5,4,6,7]. One exchange,
//              so the mirrored table:
//              (1,4,6,0) (1,0,6,3) (0,3,2,6) (6,3,7,1) (6,7,4,1) (7,4,1,5)
//   SOFA's own test (Sofa/Component/Topology/Mapping/tests/Hexa2TetraTopologicalMapping_test.cpp,
//   SingleHexahedronOutputWithSwapping) expects the same: with hexa = [0,1,3,2,4,5,7,6] its
//   {h1,h4,h7,h0} = (1,4,6,0), {h1,h0,h7,h2} = (1,0,6,3),
//   {h0,h2,h3,h7} = (0,3,2,6), {h7,h2,h6,h1} = (6,3,7,1), {h7,h6,h4,h1} = (6,7,4,1),
//   {h6,h4,h1,h5} = (7,4,1,5).
TEST(RegularGridTest, SingleCellTetrahedraWithoutSwapping) {
  const std::vector<Tetrahedron> expected{
      {0, 5, 1, 7}, {0, 1, 2, 7}, {1, 2, 7, 3}, {7, 2, 0, 6}, {7, 6, 0, 5}, {6, 5, 4, 0},
  };
  EXPECT_EQ(grid_tetrahedra(unit_grid(2, 2, 2), false), expected);
}

TEST(RegularGridTest, SingleCellTetrahedraWithSwapping) {
  const std::vector<Tetrahedron> expected{
      {1, 4, 6, 0}, {1, 0, 6, 3}, {0, 3, 2, 6}, {6, 3, 7, 1}, {6, 7, 4, 1}, {7, 4, 1, 5},
  };
  EXPECT_EQ(grid_tetrahedra(unit_grid(2, 2, 2), true), expected);
}

// n = (3,3,2): point (i,j,k) = i + 3j + 9k; 2 x 2 x 1 cells, cell order (0,0) (1,0) (0,1) (1,1).
//   cell (0,0,0): c = [0,1,4,3,9,10,13,12]
//   cell (1,0,0): c = [1,2,5,4,10,11,14,13]
//   cell (0,1,0): c = [3,4,7,6,12,13,16,15]
//   cell (1,1,0): c = [4,5,8,7,13,14,17,16]
// Without swapping every cell uses the plain table on c.
// With swapping:
//   (0,0,0): x even -> exchange x: c' = [1,0,3,4,10,9,12,13]; one exchange -> mirrored table.
//   (1,0,0): nothing exchanged -> plain table on c.
//   (0,1,0): x even then y odd: after x [4,3,6,7,13,12,15,16], after y [7,6,3,4,16,15,12,13];
//            two exchanges -> plain table.
//   (1,1,0): y odd -> c' = [7,8,5,4,16,17,14,13]; one exchange -> mirrored table.
TEST(RegularGridTest, TwoByTwoCellsTetrahedraWithoutSwapping) {
  const std::vector<Tetrahedron> expected{
      // cell (0,0,0)
      {0, 10, 1, 13}, {0, 1, 3, 13}, {1, 3, 13, 4},
      {13, 3, 0, 12}, {13, 12, 0, 10}, {12, 10, 9, 0},
      // cell (1,0,0)
      {1, 11, 2, 14}, {1, 2, 4, 14}, {2, 4, 14, 5},
      {14, 4, 1, 13}, {14, 13, 1, 11}, {13, 11, 10, 1},
      // cell (0,1,0)
      {3, 13, 4, 16}, {3, 4, 6, 16}, {4, 6, 16, 7},
      {16, 6, 3, 15}, {16, 15, 3, 13}, {15, 13, 12, 3},
      // cell (1,1,0)
      {4, 14, 5, 17}, {4, 5, 7, 17}, {5, 7, 17, 8},
      {17, 7, 4, 16}, {17, 16, 4, 14}, {16, 14, 13, 4},
  };
  EXPECT_EQ(grid_tetrahedra(unit_grid(3, 3, 2), false), expected);
}

TEST(RegularGridTest, TwoByTwoCellsTetrahedraWithSwapping) {
  const std::vector<Tetrahedron> expected{
      // cell (0,0,0), mirrored table on [1,0,3,4,10,9,12,13]
      {1, 9, 12, 0}, {1, 0, 12, 4}, {0, 4, 3, 12},
      {12, 4, 13, 1}, {12, 13, 9, 1}, {13, 9, 1, 10},
      // cell (1,0,0), plain table on [1,2,5,4,10,11,14,13]
      {1, 11, 2, 14}, {1, 2, 4, 14}, {2, 4, 14, 5},
      {14, 4, 1, 13}, {14, 13, 1, 11}, {13, 11, 10, 1},
      // cell (0,1,0), plain table on [7,6,3,4,16,15,12,13]
      {7, 15, 6, 12}, {7, 6, 4, 12}, {6, 4, 12, 3},
      {12, 4, 7, 13}, {12, 13, 7, 15}, {13, 15, 16, 7},
      // cell (1,1,0), mirrored table on [7,8,5,4,16,17,14,13]
      {7, 17, 14, 8}, {7, 8, 14, 4}, {8, 4, 5, 14},
      {14, 4, 13, 7}, {14, 13, 17, 7}, {13, 17, 7, 16},
  };
  EXPECT_EQ(grid_tetrahedra(unit_grid(3, 3, 2), true), expected);
}

// ---------------------------------------------------------------------------------------------
// Tetrahedra: counts and properties.

TEST(RegularGridTest, SixTetrahedraPerCell) {
  // The grid sizes and counts of SOFA's Hexa2TetraTopologicalMapping_test, plus the four beams.
  const std::vector<std::pair<std::array<Index, 3>, std::size_t>> cases{
      {{2, 2, 2}, 6}, {{3, 2, 2}, 12}, {{3, 3, 2}, 24}, {{3, 3, 3}, 48}};
  for (const auto& [n, count] : cases) {
    const RegularGrid grid = unit_grid(n[0], n[1], n[2]);
    EXPECT_EQ(grid_tetrahedra(grid, false).size(), count);
    EXPECT_EQ(grid_tetrahedra(grid, true).size(), count);
  }
  const RegularGrid beams = four_beams_grid();
  EXPECT_EQ(beams.num_points(), 5 * 5 * 20);
  EXPECT_EQ(beams.num_cells(), 4 * 4 * 19);
  EXPECT_EQ(grid_tetrahedra(beams, true).size(), 6u * 4 * 4 * 19);
  EXPECT_EQ(grid_tetrahedra(beams, false).size(), 1824u);
}

// Cell c owns tetrahedra 6c .. 6c+5; they use four distinct corners of that cell, each has positive
// volume (SOFA's tables keep orientation positive when min < max), and their volumes add up to the
// cell's volume.
TEST(RegularGridTest, TetrahedraExactlyFillTheirCells) {
  for (const RegularGrid& grid : property_grids()) {
    const auto x = grid_points<double>(grid);
    const Vec3<double> step((grid.max - grid.min).array() /
                            Eigen::Array3d(grid.n[0] - 1, grid.n[1] - 1, grid.n[2] - 1));
    const double cell_volume = std::abs(step.prod());
    for (bool swapping : {false, true}) {
      const auto tets = grid_tetrahedra(grid, swapping);
      ASSERT_EQ(tets.size(), 6u * static_cast<std::size_t>(grid.num_cells()));
      std::size_t t = 0;
      for (Index k = 0; k + 1 < grid.n[2]; ++k) {
        for (Index j = 0; j + 1 < grid.n[1]; ++j) {
          for (Index i = 0; i + 1 < grid.n[0]; ++i) {
            const auto corners = grid_cell_corners(grid, i, j, k);
            const std::set<Index> cell(corners.begin(), corners.end());
            double sum = 0.0;
            for (int local = 0; local < 6; ++local, ++t) {
              const Tetrahedron& tet = tets[t];
              EXPECT_EQ(std::set<Index>(tet.begin(), tet.end()).size(), 4u) << "tetrahedron " << t;
              for (Index v : tet) EXPECT_TRUE(cell.count(v)) << "tetrahedron " << t;
              const double v = signed_volume(x, tet);
              EXPECT_GT(v, 0.0) << "tetrahedron " << t << " swapping " << swapping;
              EXPECT_NEAR(v, cell_volume / 6.0, 1e-12 * cell_volume) << "tetrahedron " << t;
              sum += std::abs(v);
            }
            EXPECT_NEAR(sum, cell_volume, 1e-12 * cell_volume)
                << "cell (" << i << ", " << j << ", " << k << ") swapping " << swapping;
          }
        }
      }
    }
  }
}

// Every triangle inside the box is shared by exactly two tetrahedra and every triangle on its
// surface belongs to exactly one; the surface holds two triangles per boundary quad. This holds for
// both splits: the plain one repeats the same face diagonals in every cell, the swapped one mirrors
// neighbour cells across their shared face.
TEST(RegularGridTest, FacesAreConforming) {
  for (const RegularGrid& grid : property_grids()) {
    const auto& n = grid.n;
    const std::array<Index, 3> cells{n[0] - 1, n[1] - 1, n[2] - 1};
    const std::size_t boundary_quads =
        2u * static_cast<std::size_t>(cells[0] * cells[1] + cells[0] * cells[2] +
                                      cells[1] * cells[2]);
    for (bool swapping : {false, true}) {
      std::map<Triangle, int> count;
      for (const Tetrahedron& t : grid_tetrahedra(grid, swapping)) {
        for (int skip = 0; skip < 4; ++skip) {
          Triangle f{};
          int m = 0;
          for (int v = 0; v < 4; ++v) {
            if (v != skip) f[m++] = t[v];
          }
          std::sort(f.begin(), f.end());
          ++count[f];
        }
      }
      std::size_t boundary = 0;
      for (const auto& [face, c] : count) {
        // Grid coordinates of the face's points; the face is on the surface iff all three share a
        // first or last coordinate along some axis.
        bool on_surface = false;
        for (int a = 0; a < 3; ++a) {
          for (Index side : {Index{0}, n[a] - 1}) {
            bool all = true;
            for (Index p : face) {
              const Index coord[3] = {p % n[0], (p / n[0]) % n[1], p / (n[0] * n[1])};
              all = all && coord[a] == side;
            }
            on_surface = on_surface || all;
          }
        }
        EXPECT_EQ(c, on_surface ? 1 : 2)
            << "face (" << face[0] << ", " << face[1] << ", " << face[2] << ") swapping "
            << swapping;
        if (on_surface) ++boundary;
      }
      EXPECT_EQ(boundary, 2 * boundary_quads) << "swapping " << swapping;
    }
  }
}

// The parity rule seen geometrically: four of a cell's six tetrahedra share one body diagonal of
// the cell. Without swapping it starts at the cell's lowest corner; with swapping it starts at the
// corner whose local offset is (x even, y odd, z odd) for cell (x, y, z) -- SOFA mirrors even
// cells along x and odd cells along y and z.
TEST(RegularGridTest, BodyDiagonalFollowsSofaParityRule) {
  const RegularGrid grid = unit_grid(4, 5, 4);  // 3 x 4 x 3 cells: both parities on every axis
  const auto& n = grid.n;
  for (bool swapping : {false, true}) {
    const auto tets = grid_tetrahedra(grid, swapping);
    std::size_t t = 0;
    for (Index k = 0; k + 1 < n[2]; ++k) {
      for (Index j = 0; j + 1 < n[1]; ++j) {
        for (Index i = 0; i + 1 < n[0]; ++i, t += 6) {
          const Index ox = swapping && i % 2 == 0 ? 1 : 0;
          const Index oy = swapping && j % 2 == 1 ? 1 : 0;
          const Index oz = swapping && k % 2 == 1 ? 1 : 0;
          const auto point = [&](Index a, Index b, Index c) {
            return (i + a) + n[0] * ((j + b) + n[1] * (k + c));
          };
          const Index from = point(ox, oy, oz);
          const Index to = point(1 - ox, 1 - oy, 1 - oz);
          int sharing = 0;
          for (std::size_t local = t; local < t + 6; ++local) {
            const auto& tet = tets[local];
            const bool has_from = std::find(tet.begin(), tet.end(), from) != tet.end();
            const bool has_to = std::find(tet.begin(), tet.end(), to) != tet.end();
            sharing += has_from && has_to ? 1 : 0;
          }
          EXPECT_EQ(sharing, 4) << "cell (" << i << ", " << j << ", " << k << ") swapping "
                                << swapping;
        }
      }
    }
  }
}

// Cells that SOFA does not mirror (x odd, y even, z even) come out the same with and without
// swapping; all other cells differ.
TEST(RegularGridTest, SwappingChangesOnlyMirroredCells) {
  const RegularGrid grid = unit_grid(5, 4, 4);
  const auto plain = grid_tetrahedra(grid, false);
  const auto swapped = grid_tetrahedra(grid, true);
  std::size_t t = 0;
  for (Index k = 0; k + 1 < grid.n[2]; ++k) {
    for (Index j = 0; j + 1 < grid.n[1]; ++j) {
      for (Index i = 0; i + 1 < grid.n[0]; ++i, t += 6) {
        const bool untouched = i % 2 == 1 && j % 2 == 0 && k % 2 == 0;
        const bool same = std::equal(plain.begin() + t, plain.begin() + t + 6, swapped.begin() + t);
        EXPECT_EQ(same, untouched) << "cell (" << i << ", " << j << ", " << k << ")";
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Validation

TEST(RegularGridTest, ValidateRejectsCountsBelowOneAndCellsOfFlatGrids) {
  EXPECT_EQ(error_message([] { validate(unit_grid(5, 0, 5)); }),
            "RegularGrid: n = (5, 0, 5): each count must be at least 1");
  EXPECT_EQ(error_message([] { validate(unit_grid(5, 5, -3)); }),
            "RegularGrid: n = (5, 5, -3): each count must be at least 1");
  EXPECT_NO_THROW(validate(unit_grid(1, 5, 5)));
  const std::string flat = error_message([] { grid_tetrahedra(unit_grid(2, 2, 1), true); });
  EXPECT_NE(flat.find("RegularGrid: n = (2, 2, 1): a grid with a single point along an axis is flat and has no cells"),
            std::string::npos)
      << flat;
  EXPECT_THROW(tetrahedron_fem_grid_tetrahedra(unit_grid(1, 3, 3)), Error);
  EXPECT_THROW(grid_cell_corners(unit_grid(3, 1, 3), 0, 0, 0), Error);
  EXPECT_NO_THROW(validate(unit_grid(2, 2, 2)));
  EXPECT_NO_THROW(validate(four_beams_grid()));
}

TEST(RegularGridTest, FlatGridPlacesItsSinglePointsAsSofaDoes) {
  // SOFA's RegularGridTopology::setPos: an axis with one point puts it at the middle of the x or y
  // range, at the z minimum; the others step as usual. Zero extent is fine along such an axis.
  const auto z_flat = grid_points<double>(make_grid(4, 4, 1, Vec3<double>(-1, -1, -0.5), Vec3<double>(1, 1, -0.5)));
  ASSERT_EQ(z_flat.size(), 16u);
  EXPECT_EQ(z_flat[0], Vec3<double>(-1, -1, -0.5));
  EXPECT_EQ(z_flat[5], Vec3<double>(-1 + 2.0 / 3, -1 + 2.0 / 3, -0.5));
  EXPECT_EQ(z_flat[15], Vec3<double>(1, 1, -0.5));
  const auto z_range = grid_points<double>(make_grid(2, 2, 1, Vec3<double>(0, 0, 2), Vec3<double>(1, 1, 6)));
  EXPECT_EQ(z_range[3], Vec3<double>(1, 1, 2));  // z at min
  const auto x_flat = grid_points<double>(make_grid(1, 2, 2, Vec3<double>(2, 0, 0), Vec3<double>(6, 1, 1)));
  ASSERT_EQ(x_flat.size(), 4u);
  EXPECT_EQ(x_flat[0], Vec3<double>(4, 0, 0));  // x at the middle
  EXPECT_EQ(x_flat[3], Vec3<double>(4, 1, 1));
  EXPECT_EQ(grid_edges(make_grid(3, 3, 1, Vec3<double>(0, 0, 0), Vec3<double>(1, 1, 0))).size(), 12u);
  EXPECT_EQ(grid_quads(make_grid(3, 3, 1, Vec3<double>(0, 0, 0), Vec3<double>(1, 1, 0))).size(), 4u);
}

TEST(RegularGridTest, ValidateRejectsNonFiniteBox) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_message([&] {
              validate(make_grid(2, 2, 2, Vec3<double>(0, 0, 0), Vec3<double>(1, inf, 1)));
            }),
            "RegularGrid: max = (1, inf, 1): each coordinate must be finite");
  EXPECT_EQ(error_message([&] {
              validate(make_grid(2, 2, 2, Vec3<double>(-inf, 0, 0), Vec3<double>(1, 1, 1)));
            }),
            "RegularGrid: min = (-inf, 0, 0): each coordinate must be finite");
  const std::string nan_message = error_message(
      [&] { validate(make_grid(2, 2, 2, Vec3<double>(nan, 0, 0), Vec3<double>(1, 1, 1))); });
  EXPECT_NE(nan_message.find("RegularGrid: min = ("), std::string::npos) << nan_message;
  EXPECT_NE(nan_message.find("nan"), std::string::npos) << nan_message;
  EXPECT_THROW(grid_tetrahedra(make_grid(2, 2, 2, Vec3<double>(0, 0, 0), Vec3<double>(1, 1, nan)),
                               false),
               Error);
}

TEST(RegularGridTest, ValidateRejectsZeroExtentAndIndexOverflow) {
  EXPECT_EQ(error_message([] {
              validate(make_grid(2, 2, 2, Vec3<double>(0, 3, 0), Vec3<double>(1, 3, 1)));
            }),
            "RegularGrid: min.y = max.y = 3: the box has zero extent along y");
  // 2000^3 points do not fit in a 32-bit index.
  EXPECT_THROW(validate(unit_grid(2000, 2000, 2000)), Error);
  // A reversed axis is a mirrored grid, which SOFA accepts.
  EXPECT_NO_THROW(validate(make_grid(2, 2, 2, Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 1))));
}

}  // namespace
}  // namespace fastcorot

namespace fastcorot {
namespace {

// TetrahedronFEMForceField's own tessellation of a grid (its init): the cells mirrored as
// Hexa2TetraTopologicalMapping's swapping mirrors them, but always SOFA's plain split, so the
// tetrahedra of cells mirrored an odd number of times are those of the mapping with their last two
// vertices exchanged (negatively oriented).
TEST(RegularGrid, TetrahedronFemTessellationIsTheSwappedSplitWithoutItsReorientation) {
  RegularGrid grid;
  grid.n = {4, 3, 3};
  const auto mapped = grid_tetrahedra(grid, true);
  const auto fem = tetrahedron_fem_grid_tetrahedra(grid);
  ASSERT_EQ(fem.size(), mapped.size());
  const auto points = grid_points<double>(grid);
  for (std::size_t t = 0; t < fem.size(); ++t) {
    const std::size_t cell = t / 6;
    const Index i = static_cast<Index>(cell % 3), j = static_cast<Index>((cell / 3) % 2), k = static_cast<Index>(cell / 6);
    const bool odd = ((i % 2 == 0) + (j % 2 == 1) + (k % 2 == 1)) % 2 == 1;
    const Tetrahedron expected = odd ? Tetrahedron{mapped[t][0], mapped[t][1], mapped[t][3], mapped[t][2]} : mapped[t];
    EXPECT_EQ(fem[t], expected) << "tetrahedron " << t;
    EXPECT_EQ(signed_volume(points, fem[t]) > 0, !odd == (signed_volume(points, mapped[t]) > 0))
        << "tetrahedron " << t;
  }
}

}  // namespace
}  // namespace fastcorot
