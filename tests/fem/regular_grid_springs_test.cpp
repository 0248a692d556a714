// RegularGridSpringForceField's springs against counts and lengths worked out by hand from SOFA's
// RegularGridSpringForceField::addForce (Sofa/Component/SolidMechanics/Spring, commit 2a278d891f):
// lines along x, y, z; two diagonals per cell face in the xy, xz, yz planes; four per cell; each
// kind's stiffness and damping over the rest length from the grid's spacing.
#include "fastcorot/fem/regular_grid_springs.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fastcorot {
namespace {

RegularGrid grid_3x2x2() {
  RegularGrid grid;
  grid.n = {3, 2, 2};
  grid.min = {0, 0, 0};
  grid.max = {4, 1, 0.5};  // spacing 2, 1, 0.5
  return grid;
}

TEST(RegularGridSprings, CountsOrderAndLengthsOfEachKind) {
  const RegularGrid grid = grid_3x2x2();
  RegularGridSpringParameters<double> p;
  p.lines_stiffness = 6, p.lines_damping = 2;
  p.quads_stiffness = 0, p.quads_damping = 0;
  p.cubes_stiffness = 0, p.cubes_damping = 0;
  const auto lines = regular_grid_springs<double>(grid, p);
  // (nx-1) ny nz + nx (ny-1) nz + nx ny (nz-1) = 8 + 6 + 6.
  ASSERT_EQ(lines.size(), 20u);
  EXPECT_EQ(lines[0].a, 0);  // along x first: (0,0,0)-(1,0,0)
  EXPECT_EQ(lines[0].b, 1);
  EXPECT_EQ(lines[1].a, 1);
  EXPECT_EQ(lines[1].b, 2);
  EXPECT_DOUBLE_EQ(lines[0].rest_length, 2);
  EXPECT_DOUBLE_EQ(lines[0].stiffness, 3);  // 6 / 2
  EXPECT_DOUBLE_EQ(lines[0].damping, 1);
  EXPECT_EQ(lines[8].a, 0);  // then along y: (0,0,0)-(0,1,0) = point 3
  EXPECT_EQ(lines[8].b, 3);
  EXPECT_DOUBLE_EQ(lines[8].rest_length, 1);
  EXPECT_EQ(lines[14].a, 0);  // then along z: point 6
  EXPECT_EQ(lines[14].b, 6);
  EXPECT_DOUBLE_EQ(lines[14].stiffness, 12);  // 6 / 0.5

  p.lines_stiffness = 0, p.lines_damping = 0;
  p.quads_stiffness = 5;
  const auto quads = regular_grid_springs<double>(grid, p);
  // 2 per face: xy (nx-1)(ny-1)nz = 4, xz (nx-1)ny(nz-1) = 4, yz nx(ny-1)(nz-1) = 3 faces.
  ASSERT_EQ(quads.size(), 2u * (4 + 4 + 3));
  EXPECT_EQ(quads[0].a, 0);  // (0,0,0)-(1,1,0)
  EXPECT_EQ(quads[0].b, 4);
  EXPECT_EQ(quads[1].a, 1);  // (1,0,0)-(0,1,0)
  EXPECT_EQ(quads[1].b, 3);
  EXPECT_DOUBLE_EQ(quads[0].rest_length, std::sqrt(5.0));
  EXPECT_DOUBLE_EQ(quads[0].stiffness, 5 / std::sqrt(5.0));
  EXPECT_EQ(quads[0].damping, 0);
  EXPECT_EQ(quads[8].a, 0);  // xz plane: (0,0,0)-(1,0,1)
  EXPECT_EQ(quads[8].b, 7);
  EXPECT_DOUBLE_EQ(quads[8].rest_length, std::sqrt(4.25));
  EXPECT_EQ(quads[17].a, 3);  // yz plane, second diagonal of the first face: (0,1,0)-(0,0,1)
  EXPECT_EQ(quads[17].b, 6);
  EXPECT_DOUBLE_EQ(quads[17].rest_length, std::sqrt(1.25));

  p.quads_stiffness = 0, p.quads_damping = 0;
  p.cubes_stiffness = 1, p.cubes_damping = 0;
  const auto cubes = regular_grid_springs<double>(grid, p);
  ASSERT_EQ(cubes.size(), 8u);  // 4 per cell, 2 cells
  const std::pair<Index, Index> first_cell[4] = {{0, 10}, {1, 9}, {3, 7}, {6, 4}};
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(cubes[static_cast<std::size_t>(k)].a, first_cell[k].first);
    EXPECT_EQ(cubes[static_cast<std::size_t>(k)].b, first_cell[k].second);
    EXPECT_DOUBLE_EQ(cubes[static_cast<std::size_t>(k)].rest_length, std::sqrt(5.25));
  }
  EXPECT_EQ(cubes[4].a, 1);  // second cell
}

TEST(RegularGridSprings, DefaultsMakeEveryKindAndAllAreAtRestOnTheGrid) {
  const RegularGrid grid = grid_3x2x2();
  const auto springs = regular_grid_springs<double>(grid, RegularGridSpringParameters<double>{});
  EXPECT_EQ(springs.size(), 20u + 22u + 8u);
  const auto x = grid_points<double>(grid);
  for (const auto& s : springs) {
    EXPECT_NEAR((x[static_cast<std::size_t>(s.b)] - x[static_cast<std::size_t>(s.a)]).norm(), s.rest_length, 1e-14);
    EXPECT_NEAR(s.stiffness * s.rest_length, 100, 1e-12);
    EXPECT_NEAR(s.damping * s.rest_length, 5, 1e-12);
  }
}

TEST(RegularGridSprings, BadValuesAreRefused) {
  RegularGridSpringParameters<double> p;
  p.quads_stiffness = -1;
  EXPECT_THROW(regular_grid_springs<double>(grid_3x2x2(), p), Error);
  RegularGrid empty = grid_3x2x2();
  empty.n = {3, 0, 2};
  EXPECT_THROW(regular_grid_springs<double>(empty, RegularGridSpringParameters<double>{}), Error);
}

TEST(RegularGridSprings, AFlatGridIsACloth) {
  // One point along y (SOFA's 2D grid): lines along x and z and the xz faces' diagonals, nothing
  // along y; every rest length is the distance between the points it joins.
  RegularGrid flat = grid_3x2x2();
  flat.n = {3, 1, 2};
  RegularGridSpringParameters<double> p;
  p.lines_stiffness = 10;
  p.quads_stiffness = 10;
  p.cubes_stiffness = 10;
  const auto springs = regular_grid_springs<double>(flat, p);
  EXPECT_EQ(springs.size(), 4u + 3u + 2u * 2u);  // x lines, z lines, two diagonals per xz face
  const auto x = grid_points<double>(flat);
  for (const auto& s : springs) {
    EXPECT_NEAR((x[static_cast<std::size_t>(s.b)] - x[static_cast<std::size_t>(s.a)]).norm(), s.rest_length, 1e-14);
  }
}

}  // namespace
}  // namespace fastcorot
