// HexahedronFEMForceFieldAndMass's mass against SOFA's definitions (HexahedronFEMForceFieldAndMass.inl,
// commit 2a278d891f), evaluated by hand here: integrateMass of signs ±1 is
// 1/72 + 1/72 + 1/216 + 1/24 + 1/8 + 1/72 + 1/24 + 1/24 = 8/27, so each hexahedron's matrix is
// V rho 8/27 between every pair of its corners along each axis, its row sums 8 times that, and the
// weight rho V / 8 per corner with V = |n1-n0| |n3-n0| |n4-n0|.
#include "fastcorot/sim/hexahedron_fem_mass.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace fastcorot {
namespace {

struct TwoCells {
  RegularGrid grid;
  std::vector<Vec3<double>> rest;
  std::unique_ptr<HexahedronFEMForceField<double>> field;
  TwoCells() {
    grid.n = {3, 2, 2};
    grid.max = {4, 1, 0.5};  // cells 2 x 1 x 0.5: V = 1
    rest = grid_points<double>(grid);
    std::vector<Hexahedron> cells = {grid_cell_corners(grid, 0, 0, 0), grid_cell_corners(grid, 1, 0, 0)};
    field = std::make_unique<HexahedronFEMForceField<double>>(grid.num_points(), cells, rest,
                                                              HexahedronFEMForceField<double>::Parameters{});
  }
};

TEST(HexahedronFemMass, SofasIntegralIsEightTwentySevenths) {
  for (int sx : {-1, 1}) {
    for (int sy : {-1, 1}) {
      for (int sz : {-1, 1}) EXPECT_NEAR(hexahedron_mass_integral<double>(sx, sy, sz), 8.0 / 27, 1e-16);
    }
  }
  EXPECT_NEAR(hexahedron_mass_integral<double>(0, 0, 0), 1.0 / 8, 1e-16);
}

TEST(HexahedronFemMass, EveryPairOfCornersOfACellCarriesVRhoEightTwentySevenths) {
  TwoCells cells;
  const double rho = 3;
  const Mass<double> mass = hexahedron_fem_mass<double>(*cells.field, cells.rest, rho, false);
  ASSERT_FALSE(mass.is_lumped());
  const Eigen::MatrixXd m(mass.matrix());
  const double entry = 1 * rho * 8.0 / 27;
  const auto first = grid_cell_corners(cells.grid, 0, 0, 0), second = grid_cell_corners(cells.grid, 1, 0, 0);
  EXPECT_NEAR(m(first[0], first[6]), entry, 1e-14);      // corners of the first cell only
  EXPECT_NEAR(m(first[0], first[0]), entry, 1e-14);
  EXPECT_NEAR(m(first[1], first[1]), 2 * entry, 1e-14);  // point 1 is in both cells
  EXPECT_NEAR(m(first[1], second[1]), entry, 1e-14);     // points 1 and 2 share the second cell only
  EXPECT_EQ(m(first[0], second[1]), 0);                   // points 0 and 2 share no cell
  EXPECT_LT((m - m.transpose()).norm(), 1e-15);
  EXPECT_NEAR(mass.total_mass(), 2 * 64 * entry, 1e-12);
  // Gravity: rho V / 8 on each corner of each cell.
  const auto weights = mass.gravity_masses();
  EXPECT_NEAR(weights[static_cast<std::size_t>(first[0])], rho / 8, 1e-15);
  EXPECT_NEAR(weights[static_cast<std::size_t>(first[1])], rho / 4, 1e-15);
  std::vector<Vec3<double>> f(cells.rest.size(), Vec3<double>::Zero());
  mass.add_gravity({0, -10, 0}, f);
  EXPECT_NEAR(f[static_cast<std::size_t>(first[0])].y(), -10 * rho / 8, 1e-13);
}

TEST(HexahedronFemMass, LumpedIsTheRowSums) {
  TwoCells cells;
  const Mass<double> consistent = hexahedron_fem_mass<double>(*cells.field, cells.rest, 2.0, false);
  const Mass<double> lumped = hexahedron_fem_mass<double>(*cells.field, cells.rest, 2.0, true);
  ASSERT_TRUE(lumped.is_lumped());
  for (std::size_t i = 0; i < cells.rest.size(); ++i) {
    EXPECT_NEAR(lumped.vertex_masses()[i], consistent.vertex_masses()[i], 1e-13);
    EXPECT_EQ(lumped.gravity_masses()[i], consistent.gravity_masses()[i]);
  }
  EXPECT_NEAR(lumped.vertex_masses()[0], 8 * 2.0 * 8.0 / 27, 1e-13);
}

TEST(HexahedronFemMass, BadDensityIsRefused) {
  TwoCells cells;
  EXPECT_THROW(hexahedron_fem_mass<double>(*cells.field, cells.rest, 0.0, false), Error);
  EXPECT_THROW(hexahedron_fem_mass<double>(*cells.field, cells.rest, std::nan(""), false), Error);
}

}  // namespace
}  // namespace fastcorot
