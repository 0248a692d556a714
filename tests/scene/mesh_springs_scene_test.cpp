// MeshSpringForceField on every topology SOFA's takes (lines, triangles, quads, tetrahedra and
// cubes, springs deduplicated, stiffness over rest length), its `stiffness` setting every kind
// (SOFA declares it an alias of each kind's), Hexa2QuadTopologicalMapping's surface quads, and a
// topology container reading its own mesh file (MeshTopology filename, points / tetras).
// Expected counts are worked out by hand from SOFA's element lists (GridTopology, MeshSpringForceField::init).
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/spring_force_field.h"
#include "fastcorot/io/mesh_readers.h"
#include "fastcorot/topology/hexahedron_faces.h"
#include "fastcorot/topology/regular_grid.h"

#include "support/scene_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace fastcorot {
namespace {

const SpringForceField<double>& springs_of(const LoadedScene& scene) {
  const auto& fields = scene.simulation.objects.at(0).system.force_fields;
  EXPECT_EQ(fields.size(), 1u);
  const auto* springs = dynamic_cast<const SpringForceField<double>*>(fields.at(0).get());
  EXPECT_NE(springs, nullptr);
  return *springs;
}

constexpr const char* kGrid =
    "<Node name=\"N\"><EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-12\" threshold=\"1e-12\"/>"
    "<MechanicalObject/><UniformMass totalMass=\"1\"/><RegularGridTopology n=\"3 2 2\" min=\"0 0 0\" max=\"4 1 0.5\"/>";

TEST(MeshSpringsScene, StiffnessAloneMakesEveryKindOnAGrid) {
  const LoadedScene scene = testing::build_scene_text(std::string(kGrid) + "<MeshSpringForceField stiffness=\"300\" damping=\"3\"/></Node>");
  const auto& springs = springs_of(scene).springs();
  // 20 lines, then the 22 diagonals of the 11 quads, then the 8 diagonals of the 2 cells.
  ASSERT_EQ(springs.size(), 50u);
  std::set<std::pair<Index, Index>> pairs;
  for (const auto& s : springs) {
    pairs.insert({std::min(s.a, s.b), std::max(s.a, s.b)});
    EXPECT_NEAR(s.stiffness * s.rest_length, 300, 1e-12);
    EXPECT_NEAR(s.damping * s.rest_length, 3, 1e-14);
  }
  EXPECT_EQ(pairs.size(), 50u);
  // Every pair of corners of each cell is a spring.
  const RegularGrid grid{{3, 2, 2}, {0, 0, 0}, {4, 1, 0.5}, {}};
  for (Index i = 0; i < 2; ++i) {
    const auto c = grid_cell_corners(grid, i, 0, 0);
    for (int k = 0; k < 8; ++k) {
      for (int j = k + 1; j < 8; ++j) EXPECT_TRUE(pairs.count({std::min(c[k], c[j]), std::max(c[k], c[j])})) << k << " " << j;
    }
  }
  // SOFA's first line is along x from point 0; its first quad diagonal joins corners 0 and 2 of the first quad.
  EXPECT_EQ(springs[0].a, 0);
  EXPECT_EQ(springs[0].b, 1);
  EXPECT_DOUBLE_EQ(springs[0].rest_length, 2);
  EXPECT_EQ(springs[20].a, 0);
  EXPECT_EQ(springs[20].b, 4);
}

TEST(MeshSpringsScene, AFlatGridIsAClothOfLinesAndQuads) {
  // SOFA's cloth: a RegularGridTopology with one point along z (3 × 3 × 1). Its 12 lines and the
  // two diagonals of its 4 quads; no cells. A TetrahedronFEMForceField on it is refused naming the grid.
  const std::string flat =
      "<Node name=\"N\"><EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-12\" threshold=\"1e-12\"/>"
      "<MechanicalObject/><UniformMass totalMass=\"1\"/><RegularGridTopology n=\"3 3 1\" min=\"0 0 0\" max=\"2 2 0\"/>";
  LoadedScene scene = testing::build_scene_text(flat + "<MeshSpringForceField stiffness=\"100\"/></Node>");
  const auto& springs = springs_of(scene).springs();
  EXPECT_EQ(springs.size(), 12u + 8u);
  for (const auto& s : springs) EXPECT_TRUE(s.rest_length == 1 || std::abs(s.rest_length - std::sqrt(2.0)) < 1e-15) << s.rest_length;
  scene.simulation.step();
  for (const auto& x : scene.simulation.objects[0].system.state.position) EXPECT_TRUE(x.allFinite());
  try {
    testing::build_scene_text(flat + "<TetrahedronFEMForceField youngModulus=\"100\" poissonRatio=\"0.3\"/></Node>");
    ADD_FAILURE() << "a TetrahedronFEMForceField on a flat grid was built";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("RegularGridTopology"), std::string::npos) << message;
    EXPECT_NE(message.find("flat and has no cells"), std::string::npos) << message;
  }
}

TEST(MeshSpringsScene, AKindWrittenOverridesStiffness) {
  const LoadedScene scene = testing::build_scene_text(std::string(kGrid) + "<MeshSpringForceField stiffness=\"300\" linesStiffness=\"50\" cubesStiffness=\"0\" quadsStiffness=\"0\"/></Node>");
  const auto& springs = springs_of(scene).springs();
  ASSERT_EQ(springs.size(), 20u);  // the lines only: quads and cubes written 0
  for (const auto& s : springs) EXPECT_NEAR(s.stiffness * s.rest_length, 50, 1e-12);
}

TEST(MeshSpringsScene, TetrahedraGiveTheirEdgesWhateverTheKinds) {
  const LoadedScene scene = testing::build_scene_text(
      "<Node name=\"N\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject/><UniformMass totalMass=\"1\"/>"
      "<TetrahedronSetTopologyContainer points=\"0 0 0  1 0 0  0 1 0  0 0 1  1 1 1\" tetras=\"0 1 2 3  1 2 3 4\"/>"
      "<MeshSpringForceField stiffness=\"10\"/></Node>");
  EXPECT_EQ(scene.simulation.objects[0].system.size(), 5);
  EXPECT_EQ(springs_of(scene).springs().size(), 9u);  // 6 + 3 new edges of the second tetrahedron
}

TEST(MeshSpringsScene, ExplicitEulerOnAGridStaysFiniteAndFallsUnderGravity) {
  LoadedScene scene = testing::build_scene_text(
      "<Node name=\"N\"><EulerExplicitSolver symplectic=\"true\"/><MechanicalObject/><UniformMass totalMass=\"15\"/>"
      "<RegularGridTopology n=\"3 3 4\" min=\"0 0 0\" max=\"1 1 3\"/><MeshSpringForceField stiffness=\"300\"/>"
      "<BoxROI name=\"box\" box=\"-0.1 -0.1 -0.1 1.1 1.1 0.1\"/><FixedProjectiveConstraint indices=\"@box.indices\"/></Node>",
      "dt=\"0.0001\" gravity=\"0 -9.81 0\"");
  for (int s = 0; s < 200; ++s) scene.simulation.step();
  const auto& x = scene.simulation.objects[0].system.state.position;
  // Symplectic Euler's free fall: h^2 g n (n + 1) / 2 after n steps. The free end falls (at most
  // that far); the point beside the fixed face is held back by the springs.
  const double fall = 1e-8 * 9.81 * 200 * 201 / 2;
  EXPECT_LT(x.back().y(), 1.0);
  EXPECT_GT(x.back().y(), 1.0 - fall - 1e-9);
  const Index beside = 1 + 3 * (1 + 3 * 1);  // (1, 1, 1): y = 0.5, z = 1
  // Springs of 300 / 1 on points of 15/36 kg: omega t = 0.53 after 0.02 s, so the point falls about
  // (omega t)^2 / 12 = 2.3% less than freely.
  EXPECT_GT(x[beside].y(), 0.5 - 0.99 * fall);
  EXPECT_LT(x[beside].y(), 0.5 - 0.9 * fall);
}

TEST(HexahedronFaces, BoundaryQuadsOfTwoCellsLeaveTheSharedFace) {
  const RegularGrid grid{{3, 2, 2}, {0, 0, 0}, {2, 1, 1}, {}};
  const std::vector<std::array<Index, 8>> cells = {grid_cell_corners(grid, 0, 0, 0), grid_cell_corners(grid, 1, 0, 0)};
  const auto quads = grid_quads(grid);
  ASSERT_EQ(quads.size(), 11u);
  const auto surface = boundary_quads(quads, cells, false);
  ASSERT_EQ(surface.size(), 10u);
  for (const auto& q : surface) EXPECT_FALSE(q == (std::array<Index, 4>{1, 4, 10, 7})) << "the shared face x = 1";
  const auto flipped = boundary_quads(quads, cells, true);
  EXPECT_EQ(flipped[0], (std::array<Index, 4>{surface[0][3], surface[0][2], surface[0][1], surface[0][0]}));
  EXPECT_EQ(grid_edges(grid).size(), 20u);
  EXPECT_EQ(grid_edges(grid)[8], (Edge{0, 3}));  // the first line along y, after the 8 along x
}

TEST(MeshSpringsScene, AContainerReadsItsOwnMeshFile) {
  const std::string mesh = std::string(FASTCOROT_EXAMPLES_DIR) + "/meshes/cylinder.msh";
  const LoadedScene scene = testing::build_scene_text(
      "<Node name=\"N\"><EulerImplicitSolver/><CGLinearSolver/><MeshTopology name=\"m\" filename=\"" + mesh +
      "\"/><MechanicalObject/><UniformMass totalMass=\"1\"/><TetrahedronFEMForceField youngModulus=\"100\"/></Node>");
  const MeshData data = read_mesh_file(mesh);
  EXPECT_EQ(scene.simulation.objects[0].system.size(), static_cast<Index>(data.points.size()));
  ASSERT_NE(scene.simulation.objects[0].mesh, nullptr);
  EXPECT_EQ(scene.simulation.objects[0].mesh->num_tetrahedra(), static_cast<Index>(data.tetrahedra.size()));
  EXPECT_NE(testing::scene_error("<Node name=\"N\"><EulerImplicitSolver/><CGLinearSolver/><MeshTopology filename=\"nowhere.msh\"/>"
                                 "<MechanicalObject/><UniformMass/></Node>")
                .find("nowhere.msh"),
            std::string::npos);
}

}  // namespace
}  // namespace fastcorot
