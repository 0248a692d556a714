// SOFA's point, quad and hexahedron set containers, SphereGridTopology, GenerateGrid,
// StringMeshCreator, Mesh2PointTopologicalMapping and QuadPressureForceField through the real
// parser and builder. Expected values are worked out by hand from SOFA's sources (commit
// 2a278d891f; each test says which), never taken from the code under test.
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/topology/regular_grid.h"

#include "support/scene_text.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fastcorot {
namespace {

using V = Vec3<double>;

bool says(const std::string& error, const std::string& part) { return error.find(part) != std::string::npos; }

// The points of a 3 x 2 x 2 grid over [0, 4] x [0, 1] x [0, 0.5] (x fastest) and its two cells.
const std::string kTwoCellPoints = "0 0 0 2 0 0 4 0 0 0 1 0 2 1 0 4 1 0 0 0 0.5 2 0 0.5 4 0 0.5 0 1 0.5 2 1 0.5 4 1 0.5";
const std::string kTwoCells = "0 1 4 3 6 7 10 9 1 2 5 4 7 8 11 10";

std::string solver() { return "<EulerImplicitSolver/><EigenSimplicialLDLT/>"; }

const HexahedronFEMForceField<double>& hexahedron_field(const LoadedScene& scene) {
  const auto* field = dynamic_cast<const HexahedronFEMForceField<double>*>(scene.simulation.objects[0].system.force_fields.at(0).get());
  if (!field) throw std::runtime_error("no HexahedronFEMForceField");
  return *field;
}

TEST(SofaTopologyContainers, HexahedronSetInlineIsTheGridsCells) {
  // The same cells given inline and by a RegularGridTopology: same hexahedra, same element stiffness.
  const std::string fem = "<UniformMass totalMass=\"1\"/><HexahedronFEMForceField youngModulus=\"300\" poissonRatio=\"0.3\"/>";
  const LoadedScene set = testing::build_scene_text("<Node name=\"b\">" + solver() +
      "<HexahedronSetTopologyContainer points=\"" + kTwoCellPoints + "\" hexas=\"" + kTwoCells + "\"/>"
      "<HexahedronSetTopologyModifier/><HexahedronSetGeometryAlgorithms/><MechanicalObject/>" + fem + "</Node>");
  const LoadedScene grid = testing::build_scene_text("<Node name=\"b\">" + solver() +
      "<RegularGridTopology n=\"3 2 2\" min=\"0 0 0\" max=\"4 1 0.5\"/><MechanicalObject/>" + fem + "</Node>");
  ASSERT_EQ(set.simulation.objects[0].system.state.position.size(), 12u);
  EXPECT_EQ(set.simulation.objects[0].system.state.position[10], V(2, 1, 0.5));
  ASSERT_EQ(hexahedron_field(set).hexahedra().size(), 2u);
  EXPECT_EQ(hexahedron_field(set).hexahedra()[1], hexahedron_field(grid).hexahedra()[1]);
  EXPECT_LT((hexahedron_field(set).element_stiffness(1) - hexahedron_field(grid).element_stiffness(1)).norm(),
            1e-12 * hexahedron_field(grid).element_stiffness(1).norm());
}

TEST(SofaTopologyContainers, HexahedronSetFromGenerateGridWithLumpedMass) {
  // SOFA's GenerateGrid.scn wiring: the container links the engine's outputs. One cell of 1 x 2 x 3:
  // lumped MeshMatrixMass puts rho V / 20 x 2.5 = rho V / 8 on each corner.
  const LoadedScene scene = testing::build_scene_text(
      "<GenerateGrid name=\"g\" min=\"0 0 0\" max=\"1 2 3\" resolution=\"1 1 1\"/><Node name=\"h\">" + solver() +
      "<HexahedronSetTopologyContainer hexahedra=\"@../g.hexahedra\" position=\"@../g.output_position\" createQuadArray=\"1\"/>"
      "<MechanicalObject translation=\"5 0 0\"/><MeshMatrixMass massDensity=\"2\" lumping=\"1\"/>"
      "<HexahedronFEMForceField youngModulus=\"1\" poissonRatio=\"0.45\" method=\"polar\"/></Node>");
  const auto& object = scene.simulation.objects[0];
  ASSERT_EQ(object.system.state.position.size(), 8u);
  EXPECT_EQ(object.system.state.position[7], V(6, 2, 3));  // point (1, 1, 1) moved by the state's translation
  const auto masses = object.system.mass.vertex_masses();
  for (double m : masses) EXPECT_NEAR(m, 2 * 6 / 8.0, 1e-14);
  EXPECT_EQ(hexahedron_field(scene).hexahedra()[0], (Hexahedron{0, 1, 3, 2, 4, 5, 7, 6}));
}

TEST(SofaTopologyContainers, HexahedronSetQuadsAndQuadPressure) {
  // src="@g" takes the engine's same-named data; the quads are SOFA's quad array of the hexahedra:
  // for one cube (0 2 3 1)... faces (0 2 3 1) (4 5 7 6) (0 1 5 4) (1 3 7 5) (3 2 6 7) (0 4 6 2).
  // Quad 1 (the top, z = 1, area 1 x 2) under pressure (0 0 -4): -8 / 4 = -2 on each of its corners.
  const LoadedScene scene = testing::build_scene_text(
      "<GenerateGrid name=\"g\" max=\"1 2 1\" resolution=\"1 1 1\"/><Node name=\"h\">" + solver() +
      "<HexahedronSetTopologyContainer name=\"c\" src=\"@../g\"/><MechanicalObject/><UniformMass totalMass=\"1\"/>"
      "<BoxROI name=\"top\" box=\"-1 -1 0.9 2 3 1.1\"/>"
      "<QuadPressureForceField quadList=\"@top.quadIndices\" pressure=\"0 0 -4\"/></Node>");
  const auto& forces = scene.simulation.objects[0].system.constant_forces.at(0);
  ASSERT_EQ(forces.indices.size(), 4u);
  EXPECT_EQ(forces.indices, (std::vector<Index>{4, 5, 7, 6}));
  for (const auto& f : forces.forces) EXPECT_LT((f - V(0, 0, -2)).norm(), 1e-14);
  EXPECT_TRUE(says(testing::scene_error("<GenerateGrid name=\"g\" max=\"1 2 1\" resolution=\"1 1 1\"/><Node name=\"h\">" + solver() +
                                        "<HexahedronSetTopologyContainer src=\"@../g\"/><MechanicalObject/><UniformMass totalMass=\"1\"/>"
                                        "<QuadPressureForceField quadList=\"6\" pressure=\"0 0 -4\"/></Node>"),
                   "quadList: quad 6 out of range"));
}

TEST(SofaTopologyContainers, Hexa2TetraFromAHexahedronSet) {
  // SOFA's Hexa2TetraTopologicalMapping on a container that is not a grid: cells taken 2 x 1 per
  // layer. Without swapping the first tetrahedron is corners (0 5 1 6); with it, hexahedron 0 (even
  // x) is mirrored along x (corners 1 0 3 2 5 4 7 6) and split with the mirrored table: (0 5 6 1) -> (1 4 7 0).
  const auto first = [](const std::string& swapping) {
    const LoadedScene scene = testing::build_scene_text("<Node name=\"b\">" + solver() +
        "<HexahedronSetTopologyContainer name=\"hexa\" position=\"0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\" "
        "hexahedra=\"0 1 2 3 4 5 6 7\"/><Node name=\"t\"><TetrahedronSetTopologyContainer name=\"tet\"/>"
        "<Hexa2TetraTopologicalMapping input=\"@../hexa\" output=\"@tet\" swapping=\"" + swapping + "\"/>"
        "<MechanicalObject/><UniformMass totalMass=\"1\"/>"
        "<TetrahedronFEMForceField youngModulus=\"10\" poissonRatio=\"0.3\"/></Node></Node>");
    const auto& mesh = *scene.simulation.objects[0].mesh;
    EXPECT_EQ(mesh.num_tetrahedra(), 6);
    return mesh.tetrahedron(0);
  };
  EXPECT_EQ(first("false"), (Tetrahedron{0, 5, 1, 6}));
  EXPECT_EQ(first("true"), (Tetrahedron{1, 4, 7, 0}));
}

TEST(SofaTopologyContainers, TetrahedronFEMSplitsAHexahedronSet) {
  // SOFA's TetrahedronFEMForceField::init on hexahedra alone: mirrored as with swapping, plain table:
  // hexahedron 0 mirrored along x (SOFA's xEdges swapped) gives (c0 c5 c1 c6) of the mirrored corners.
  const LoadedScene scene = testing::build_scene_text("<Node name=\"b\">" + solver() +
      "<HexahedronSetTopologyContainer points=\"" + kTwoCellPoints + "\" hexahedra=\"" + kTwoCells + "\"/>"
      "<MechanicalObject/><UniformMass totalMass=\"1\"/><TetrahedronFEMForceField youngModulus=\"10\" poissonRatio=\"0.3\"/></Node>");
  const auto& mesh = *scene.simulation.objects[0].mesh;
  ASSERT_EQ(mesh.num_tetrahedra(), 12);
  EXPECT_EQ(mesh.tetrahedron(0), (Tetrahedron{1, 6, 0, 9}));  // cell 0 = (0 1 4 3 6 7 10 9) mirrored: (1 0 3 4 7 6 9 10)
  EXPECT_EQ(mesh.tetrahedron(6), (Tetrahedron{1, 8, 2, 11}));  // cell 1 (odd): not mirrored, (0 5 1 6)
}

TEST(SofaTopologyContainers, BadHexahedraAreRefused) {
  const auto body = [](const std::string& hexahedra) {
    return "<Node name=\"b\">" + solver() + "<HexahedronSetTopologyContainer position=\"" + kTwoCellPoints +
           "\" hexahedra=\"" + hexahedra + "\"/><MechanicalObject/><UniformMass totalMass=\"1\"/>"
           "<HexahedronFEMForceField youngModulus=\"1\" poissonRatio=\"0.3\"/></Node>";
  };
  const std::string arity = testing::scene_error(body("0 1 4 3 6 7 10"));
  EXPECT_TRUE(says(arity, "HexahedronSetTopologyContainer") && says(arity, "hexahedra needs 8 indices")) << arity;
  const std::string beyond = testing::scene_error(body("0 1 4 3 6 7 10 12"));
  EXPECT_TRUE(says(beyond, "HexahedronSetTopologyContainer") && says(beyond, "names point 12")) << beyond;
}

TEST(SofaTopologyContainers, SphereGridTopologyGivesTheStateAndHexahedra) {
  // SOFA's SphereGridTopology.scn objects, smaller: 3 x 3 x 3 points of radius 2 along y: the
  // centre (point 13) stays at the origin, point 14 (cube (2, 0, 0)) is on the sphere at (2, 0, 0).
  const LoadedScene scene = testing::build_scene_text("<Node name=\"s\">" + solver() +
      "<MechanicalObject dx=\"10\"/><UniformMass totalMass=\"100\"/>"
      "<SphereGridTopology nx=\"3\" ny=\"3\" nz=\"3\" radius=\"2\" axis=\"0 1 0\"/>"
      "<HexahedronFEMForceField youngModulus=\"1116\" poissonRatio=\"0.3\" method=\"large\"/></Node>");
  const auto& x = scene.simulation.objects[0].system.state.position;
  ASSERT_EQ(x.size(), 27u);
  EXPECT_LT((x[13] - V(10, 0, 0)).norm(), 1e-15);
  EXPECT_LT((x[14] - V(12, 0, 0)).norm(), 1e-15);
  EXPECT_LT((x[10] - V(10, 0, 2)).norm(), 1e-15);  // cube (0, -2, 0): Y = (0, 0, -1)
  RegularGrid grid;
  grid.n = {3, 3, 3};
  ASSERT_EQ(hexahedron_field(scene).hexahedra().size(), 8u);
  EXPECT_EQ(hexahedron_field(scene).hexahedra()[7], grid_cell_corners(grid, 1, 1, 1));
  EXPECT_TRUE(says(testing::scene_error("<Node name=\"s\">" + solver() + "<MechanicalObject/><UniformMass totalMass=\"1\"/>"
                                        "<SphereGridTopology n=\"3 1 3\"/></Node>"),
                   "SphereGridTopology"));
}

TEST(SofaTopologyContainers, PointSetInlineAndFromStringMeshCreator) {
  const LoadedScene inline_points = testing::build_scene_text("<Node name=\"p\">" + solver() +
      "<PointSetTopologyContainer points=\"0 0 0 1 2 3\"/><MechanicalObject/><UniformMass totalMass=\"1\"/></Node>");
  EXPECT_EQ(inline_points.simulation.objects[0].system.state.position[1], V(1, 2, 3));
  // StringMeshCreator: point x at (x / 4, 0, 0), then the loader's scale and translation.
  const LoadedScene string = testing::build_scene_text("<Node name=\"p\">" + solver() +
      "<StringMeshCreator name=\"s\" resolution=\"5\" scale3d=\"2 1 1\" translation=\"0 1 0\"/>"
      "<PointSetTopologyContainer src=\"@s\"/><MechanicalObject/><UniformMass totalMass=\"1\"/></Node>");
  const auto& x = string.simulation.objects[0].system.state.position;
  ASSERT_EQ(x.size(), 5u);
  EXPECT_EQ(x[3], V(1.5, 1, 0));
  const std::string bad = testing::scene_error("<Node name=\"p\">" + solver() +
      "<StringMeshCreator name=\"s\" resolution=\"1\"/><PointSetTopologyContainer src=\"@s\"/><MechanicalObject/>"
      "<UniformMass totalMass=\"1\"/></Node>");
  EXPECT_TRUE(says(bad, "StringMeshCreator 's'") && says(bad, "resolution")) << bad;
}

TEST(SofaTopologyContainers, GenerateGridBadResolutionNamesIt) {
  const std::string error = testing::scene_error("<GenerateGrid name=\"g\" max=\"1 1 1\" resolution=\"0 1 1\"/>"
      "<Node name=\"t\">" + solver() + "<TetrahedronSetTopologyContainer tetrahedra=\"@../g.tetrahedra\" "
      "position=\"@../g.output_position\"/><MechanicalObject/><UniformMass totalMass=\"1\"/></Node>");
  EXPECT_TRUE(says(error, "GenerateGrid 'g'") && says(error, "resolution")) << error;
}

TEST(SofaTopologyContainers, Mesh2PointPlacesPointsOnTheInputsEdges) {
  // SOFA's Mesh2PointTopologicalMapping.scn on one tetrahedron: pointBaryCoords (0 0 0) copies the
  // 4 points, edgeBaryCoords (0.5 0 0) adds the midpoints of the container's 6 edges, created in
  // SOFA's order (0 1) (0 2) (0 3) (1 2) (1 3) (2 3). The state there has no mass and no force: it
  // stays put and is not simulated.
  const LoadedScene scene = testing::build_scene_text("<Node name=\"m\">" + solver() +
      "<TetrahedronSetTopologyContainer name=\"c1\" position=\"0 0 0 2 0 0 0 2 0 0 0 2\" tetrahedra=\"0 1 2 3\"/>"
      "<MechanicalObject/><DiagonalMass massDensity=\"1\"/>"
      "<TetrahedronFEMForceField youngModulus=\"10\" poissonRatio=\"0.3\"/>"
      "<Node name=\"points\"><PointSetTopologyContainer name=\"c2\"/>"
      "<Mesh2PointTopologicalMapping input=\"@c1\" output=\"@c2\" pointBaryCoords=\"0 0 0\" edgeBaryCoords=\"0.5 0 0\"/>"
      "<MechanicalObject name=\"marks\"/><SphereCollisionModel radius=\"0.25\"/></Node></Node>");
  ASSERT_EQ(scene.simulation.objects.size(), 1u);
  EXPECT_EQ(scene.simulation.objects[0].system.size(), 4);
  bool reported = false;
  for (const auto& line : scene.info) reported = reported || says(line, "stay put");
  EXPECT_TRUE(reported);
  // The points themselves, read through a mapped state's position: what the container holds.
  const LoadedScene mapped = testing::build_scene_text("<Node name=\"m\">" + solver() +
      "<TetrahedronSetTopologyContainer name=\"c1\" position=\"0 0 0 2 0 0 0 2 0 0 0 2\" tetrahedra=\"0 1 2 3\"/>"
      "<MechanicalObject/><DiagonalMass massDensity=\"1\"/></Node>"
      "<Node name=\"points\"><EulerImplicitSolver/><EigenSimplicialLDLT/><PointSetTopologyContainer name=\"c2\"/>"
      "<Mesh2PointTopologicalMapping input=\"@/m/c1\" output=\"@c2\" pointBaryCoords=\"0 0 0\" edgeBaryCoords=\"0.5 0 0\"/>"
      "<MechanicalObject/><UniformMass totalMass=\"1\"/></Node>");
  const auto& x = mapped.simulation.objects.at(1).system.state.position;
  ASSERT_EQ(x.size(), 10u);
  EXPECT_EQ(x[3], V(0, 0, 2));
  EXPECT_EQ(x[4], V(1, 0, 0));  // edge (0 1)
  EXPECT_EQ(x[7], V(1, 1, 0));  // edge (1 2)
  EXPECT_EQ(x[9], V(0, 1, 1));  // edge (2 3)
  const std::string bad = testing::scene_error("<Node name=\"m\">" + solver() +
      "<TetrahedronSetTopologyContainer name=\"c1\" position=\"0 0 0 2 0 0\" edges=\"0 5\"/>"
      "<PointSetTopologyContainer name=\"c2\"/><Mesh2PointTopologicalMapping input=\"@c1\" output=\"@c2\" edgeBaryCoords=\"0.5 0 0\"/>"
      "<MechanicalObject topology=\"@c2\"/><UniformMass totalMass=\"1\"/></Node>");
  EXPECT_TRUE(says(bad, "Mesh2PointTopologicalMapping") && says(bad, "names point 5")) << bad;
}

}  // namespace
}  // namespace fastcorot
