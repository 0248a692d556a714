// Hexahedral scenes: HexahedronFEMForceField on a RegularGridTopology's cells, and DiagonalMass and
// MeshMatrixMass on them, as SOFA builds them (expectations from SOFA's definitions: a cell's mass
// rho V in eighths on its corners for DiagonalMass; rho V / 20 on each corner and rho V / 40 on each
// of its twelve edges for MeshMatrixMass).
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/topology/regular_grid.h"

#include "support/scene_text.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace fastcorot {
namespace {

// Two cells of 2 x 1 x 0.5 along x (points 3 x 2 x 2), the first face clamped.
std::string grid_scene(const std::string& mass, const std::string& fem = "method=\"large\"") {
  return "<Node name=\"beam\"><EulerImplicitSolver/><EigenSimplicialLDLT/>"
         "<RegularGridTopology name=\"grid\" n=\"3 2 2\" min=\"0 0 0\" max=\"4 1 0.5\"/><MechanicalObject/>" +
         mass + "<HexahedronFEMForceField youngModulus=\"300\" poissonRatio=\"0.3\" " + fem +
         "/><FixedProjectiveConstraint indices=\"0 3 6 9\"/></Node>";
}

TEST(SofaHexahedra, HexahedronFEMTakesTheGridCellsInSofasOrder) {
  LoadedScene scene = testing::build_scene_text(grid_scene("<UniformMass totalMass=\"1\"/>"));
  auto& object = scene.simulation.objects[0];
  ASSERT_EQ(object.system.force_fields.size(), 1u);
  const auto* field = dynamic_cast<const HexahedronFEMForceField<double>*>(object.system.force_fields[0].get());
  ASSERT_NE(field, nullptr);
  RegularGrid grid;
  grid.n = {3, 2, 2};
  grid.max = {4, 1, 0.5};
  ASSERT_EQ(field->hexahedra().size(), 2u);
  EXPECT_EQ(field->hexahedra()[0], grid_cell_corners(grid, 0, 0, 0));
  EXPECT_EQ(field->hexahedra()[1], grid_cell_corners(grid, 1, 0, 0));
  // Its element stiffness is that of the cell with the scene's material (2 x 1 x 0.5 box, large: frame = world).
  const double E = 300, nu = 0.3, scale = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  std::array<Vec3<double>, 8> corners;
  for (std::size_t i = 0; i < 8; ++i) corners[i] = object.system.state.rest_position[static_cast<std::size_t>(field->hexahedra()[0][i])];
  const auto K = hexahedron_element_stiffness<double>(corners, scale, nu / (1 - nu) * scale, (1 - 2 * nu) / (2 * (1 - nu)) * scale);
  EXPECT_LT((field->element_stiffness(0) - K).norm(), 1e-12 * K.norm());
  EXPECT_EQ(object.mesh->num_tetrahedra(), 12);  // drawn and written as six tetrahedra per cell
  for (int s = 0; s < 20; ++s) scene.simulation.step();
  EXPECT_LT(object.system.state.position[11].y(), 1.0);  // the free end sags under gravity
  EXPECT_TRUE(object.system.state.position[11].allFinite());
}

TEST(SofaHexahedra, DiagonalMassPutsEighthsOfEachCellOnItsCorners) {
  const LoadedScene scene = testing::build_scene_text(grid_scene("<DiagonalMass massDensity=\"3\"/>"));
  const auto masses = scene.simulation.objects[0].system.mass.vertex_masses();
  const double cell = 3 * 2 * 1 * 0.5;  // rho V
  EXPECT_NEAR(masses[0], cell / 8, 1e-14);  // a corner of the first cell only
  EXPECT_NEAR(masses[1], cell / 4, 1e-14);  // shared by both cells
  const LoadedScene total = testing::build_scene_text(grid_scene("<DiagonalMass totalMass=\"5\"/>"));
  EXPECT_NEAR(total.simulation.objects[0].system.mass.total_mass(), 5, 1e-13);
}

TEST(SofaHexahedra, MeshMatrixMassOnCornersAndTheTwelveEdges) {
  const LoadedScene scene = testing::build_scene_text(grid_scene("<MeshMatrixMass massDensity=\"2\"/>"));
  const auto& mass = scene.simulation.objects[0].system.mass;
  ASSERT_FALSE(mass.is_lumped());
  const Eigen::MatrixXd M(mass.matrix());
  ASSERT_EQ(M.rows(), 12);
  const double cell = 2 * 2 * 1 * 0.5;
  EXPECT_NEAR(M(0, 0), cell / 20, 1e-14);
  EXPECT_NEAR(M(1, 1), 2 * cell / 20, 1e-14);
  EXPECT_NEAR(M(0, 1), cell / 40, 1e-14);  // an edge of the first cell
  EXPECT_NEAR(M(1, 4), 2 * cell / 40, 1e-14);  // the edge shared by both cells (1 to 4 along y)
  EXPECT_EQ(M(0, 4), 0.0);                  // a face diagonal: no mass
  EXPECT_NEAR(M.sum(), 2 * cell, 1e-13);
  const LoadedScene total = testing::build_scene_text(grid_scene("<MeshMatrixMass totalMass=\"7\"/>"));
  EXPECT_NEAR(Eigen::MatrixXd(total.simulation.objects[0].system.mass.matrix()).sum(), 7, 1e-12);
  // Lumped (SOFA's MeshMatrixMass::massInitialization: the corner share rho V / 20 times 2.5): rho V / 8.
  const LoadedScene lumped = testing::build_scene_text(grid_scene("<MeshMatrixMass massDensity=\"2\" lumping=\"true\"/>"));
  const auto masses = lumped.simulation.objects[0].system.mass.vertex_masses();
  EXPECT_NEAR(masses[0], cell / 8, 1e-14);
  EXPECT_NEAR(masses[1], cell / 4, 1e-14);  // shared by both cells
}

TEST(SofaHexahedra, BadHexahedralScenesAreNamed) {
  EXPECT_NE(testing::scene_error(grid_scene("<UniformMass totalMass=\"1\"/>", "method=\"svd\""))
                .find("HexahedronFEMForceField: method \"svd\": expected large, polar or small"),
            std::string::npos);
  EXPECT_NE(testing::scene_error(grid_scene("<UniformMass totalMass=\"1\"/>", "updateStiffnessMatrix=\"true\""))
                .find("updateStiffnessMatrix=\"true\" is not supported"),
            std::string::npos);
  // A grid mirrored along x (max < min) gives inverted cells.
  const std::string mirrored = "<Node name=\"b\"><EulerImplicitSolver/><CGLinearSolver/><RegularGridTopology n=\"2 2 2\" "
                               "min=\"1 0 0\" max=\"0 1 1\"/><MechanicalObject/><UniformMass totalMass=\"1\"/>"
                               "<HexahedronFEMForceField/></Node>";
  EXPECT_NE(testing::scene_error(mirrored).find("hexahedron 0: a flat or inverted hexahedron"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
