// SOFA components that scenes bring beyond our own (RegularGridTopology's nx/xmin forms and p0,
// SubsetMapping, the partial projective constraints, MeshSpringForceField, the explicit and
// Newmark integrators, AttachProjectiveConstraint), fed as inline XML through the parser and builder; each expectation is
// worked out by hand from SOFA's definition of the component.
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/spring_force_field.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"
#include "fastcorot/sim/explicit_solvers.h"
#include "fastcorot/sim/newmark_solver.h"

#include "support/scene_text.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace fastcorot {
namespace {

LoadedScene build(const std::string& body, const std::string& root_attributes = "") {
  return testing::build_scene_text(body, root_attributes);
}
std::string error_of(const std::string& body) { return testing::scene_error(body); }

// A 3×2×2 grid split into tetrahedra, under `solver`, with `extra` components in the node.
std::string beam(const std::string& extra, const std::string& solver = "<EulerImplicitSolver/><CGLinearSolver iterations=\"25\"/>",
                 const std::string& grid = "n=\"3 2 2\" min=\"0 0 0\" max=\"2 1 1\"") {
  return "<Node name=\"beam\">" + solver + "<RegularGridTopology name=\"grid\" " + grid +
         "/><MechanicalObject name=\"state\"/><TetrahedronSetTopologyContainer name=\"tets\"/>"
         "<Hexa2TetraTopologicalMapping input=\"@grid\" output=\"@tets\"/><UniformMass totalMass=\"1\"/>"
         "<TetrahedronFEMForceField youngModulus=\"100\" poissonRatio=\"0.3\"/>" + extra + "</Node>";
}

TEST(SofaGrid, NxNyNzAndTheSixBoundsReplaceNMinMaxAsSofaParsesThem) {
  const LoadedScene scene = build(beam("", "<EulerImplicitSolver/><CGLinearSolver/>",
                                       "n=\"2 2 2\" nx=\"4\" ny=\"2\" nz=\"2\" xmin=\"0\" xmax=\"0.3\" ymin=\"0\" ymax=\"1\" "
                                       "zmin=\"0\" zmax=\"1\" scale=\"2\""));
  const auto& x = scene.simulation.objects[0].system.state.position;
  ASSERT_EQ(x.size(), 16u);
  // xmax read as a float, times the scale: 0.3f * 2, in steps of a third.
  EXPECT_EQ(x[3].x(), static_cast<double>(0.3f) * 2);
  EXPECT_EQ(x[1].x(), static_cast<double>(0.3f) * 2 / 3);
  EXPECT_EQ(x[15], Vec3<double>(static_cast<double>(0.3f) * 2, 2, 2));
  // nx alone (not all three) is ignored, as in SOFA.
  EXPECT_EQ(build(beam("", "<EulerImplicitSolver/><CGLinearSolver/>", "nx=\"5\" n=\"3 2 2\"")).simulation.objects[0].system.size(), 12);
}

TEST(SofaGrid, P0MovesPointZeroAndKeepsTheSize) {
  const LoadedScene scene = build(beam("", "<EulerImplicitSolver/><CGLinearSolver/>", "n=\"3 2 2\" min=\"0 0 0\" max=\"2 1 1\" p0=\"5 0 -1\""));
  const auto& x = scene.simulation.objects[0].system.state.position;
  EXPECT_EQ(x[0], Vec3<double>(5, 0, -1));
  EXPECT_EQ(x[11], Vec3<double>(7, 1, 0));
  EXPECT_NE(error_of(beam("", "<EulerImplicitSolver/><CGLinearSolver/>", "n=\"3 2 2\" p0=\"1 nan 0\"")), "");
}

// A visual model with the grid's points 1, 2 and 5 (written into an OBJ file here), mapped by `mapping`.
std::string subset_scene(const std::string& mapping) {
  const auto folder = std::filesystem::temp_directory_path() / ("fastcorot_subset_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "three.obj") << "v 1 0 0\nv 2 0 0\nv 2 1 0\nf 1 2 3\n";
  return beam("<Node name=\"visual\"><OglModel name=\"model\" filename=\"" + (folder / "three.obj").string() + "\"/>" + mapping +
              "</Node>");
}

TEST(SofaSubsetMapping, IndicesRangesAndSearchByRadius) {
  for (const std::string& mapping : {std::string("<SubsetMapping indices=\"1 2 5\"/>"), std::string("<SubsetMapping/>")}) {
    const LoadedScene scene = build(subset_scene(mapping));
    const auto& surface = scene.simulation.objects[0].visual_surfaces.at(0);
    EXPECT_EQ(surface.mapping, "SubsetMapping");
    Points<double> x(12, Vec3<double>::Zero());
    x[1] = {7, 0, 0};
    x[2] = {8, 0, 0};
    x[5] = {9, 0, 0};
    const auto mapped = surface.points(x);
    EXPECT_EQ(mapped[0], Vec3<double>(7, 0, 0));
    EXPECT_EQ(mapped[2], Vec3<double>(9, 0, 0));
  }
  const LoadedScene ranged = build(subset_scene("<SubsetMapping first=\"3\" last=\"5\"/>"));
  Points<double> x(12, Vec3<double>::Zero());
  x[4] = {1, 1, 1};
  EXPECT_EQ(ranged.simulation.objects[0].visual_surfaces.at(0).points(x)[1], Vec3<double>(1, 1, 1));
  EXPECT_NE(error_of(subset_scene("<SubsetMapping indices=\"1 2 40\"/>")).find("index 40 out of range"), std::string::npos);
  EXPECT_NE(error_of(subset_scene("<SubsetMapping indices=\"1 2\"/>")).find("2 indices for a visual model of 3 points"),
            std::string::npos);
  EXPECT_NE(error_of(subset_scene("<SubsetMapping radius=\"0\"/>")), "");
}

TEST(SofaProjectiveConstraints, PartialFixedHoldsTheChosenAxes) {
  const LoadedScene scene = build(beam("<PartialFixedProjectiveConstraint indices=\"2 3\" fixedDirections=\"0 1 1\" projectVelocity=\"1\"/>"));
  const auto& system = scene.simulation.objects[0].system;
  ASSERT_EQ(system.projections.size(), 2u);
  EXPECT_EQ(system.projections[0].projector, Mat3<double>(Vec3<double>(1, 0, 0).asDiagonal()));
  ASSERT_EQ(system.placements.size(), 2u);
  EXPECT_EQ(system.placements[1].velocity_projector, Mat3<double>(Vec3<double>(1, 0, 0).asDiagonal()));
  EXPECT_NE(error_of(beam("<PartialFixedProjectiveConstraint indices=\"12\"/>")).find("index 12 out of range [0, 12)"),
            std::string::npos);
}

TEST(SofaProjectiveConstraints, FixedPlaneSelectsBetweenDminAndDmaxStrictly) {
  // x . (1, 0, 0) strictly inside (0.5, 2): the points at x = 1 (1, 4, 7, 10), not those at 2.
  const LoadedScene scene = build(beam("<FixedPlaneProjectiveConstraint direction=\"1 0 0\" dmin=\"0.5\" dmax=\"2\"/>"));
  const auto& system = scene.simulation.objects[0].system;
  ASSERT_EQ(system.projections.size(), 4u);
  EXPECT_EQ(system.projections[0].point, 1);
  EXPECT_EQ(system.projections[3].point, 10);
  EXPECT_EQ(system.projections[0].projector, Mat3<double>(Vec3<double>(0, 1, 1).asDiagonal()));
  EXPECT_TRUE(system.placements.empty());
}

TEST(SofaProjectiveConstraints, PlaneConstraintFixesThePointsInItsSlab) {
  // SOFA's Objects/PlaneConstraint.xml (built in): a PlaneROI and a FixedProjectiveConstraint. The
  // slab over the rectangle x in [-0.5, 0.5], y in [-0.5, 1.5] at z = 0, 0.2 thick, holds the points
  // (0, 0, 0) and (0, 1, 0): indices 0 and 3 of the 3×2×2 grid.
  const LoadedScene scene = build(beam("<PlaneConstraint plane=\"-0.5 -0.5 0 0.5 -0.5 0 0.5 1.5 0 0.2\"/>"));
  EXPECT_EQ(scene.simulation.objects[0].system.fixed, (std::vector<Index>{0, 3}));
}

TEST(SofaProjectiveConstraints, PlaneAndLineProjectIncrementsAndPlacePoints) {
  const LoadedScene scene = build(beam("<PlaneProjectiveConstraint indices=\"1\" normal=\"0 0 2\" origin=\"0 0 0.25\"/>"
                                       "<LineProjectiveConstraint indices=\"2\" direction=\"0 3 0\" origin=\"2 0 0\"/>"));
  const auto& system = scene.simulation.objects[0].system;
  ASSERT_EQ(system.placements.size(), 2u);
  EXPECT_EQ(system.placements[0].projector, Mat3<double>(Vec3<double>(1, 1, 0).asDiagonal()));
  EXPECT_EQ(system.placements[0].origin, Vec3<double>(0, 0, 0.25));
  EXPECT_EQ(system.placements[1].projector, Mat3<double>(Vec3<double>(0, 1, 0).asDiagonal()));
  // A step keeps point 1 on z = 0.25 and point 2 on the line x = 2, z = 0, under gravity along z.
  LoadedScene moving = build(beam("<PlaneProjectiveConstraint indices=\"1\" normal=\"0 0 2\" origin=\"0 0 0.25\"/>"
                                  "<LineProjectiveConstraint indices=\"2\" direction=\"0 3 0\" origin=\"2 0 0\"/>"),
                             "gravity=\"1 2 -9\"");
  for (int s = 0; s < 3; ++s) moving.simulation.step();
  const auto& x = moving.simulation.objects[0].system.state.position;
  EXPECT_NEAR(x[1].z(), 0.25, 1e-15);
  EXPECT_NEAR(x[2].x(), 2, 1e-15);
  EXPECT_NEAR(x[2].z(), 0, 1e-15);
}

TEST(SofaMeshSpringForceField, SpringsFromTheTetrahedraAndTheirFaces) {
  const LoadedScene scene = build(beam("<MeshSpringForceField tetrasStiffness=\"30\" tetrasDamping=\"1\"/>"));
  const auto& fields = scene.simulation.objects[0].system.force_fields;
  ASSERT_EQ(fields.size(), 2u);
  const auto* springs = dynamic_cast<const SpringForceField<double>*>(fields[1].get());
  ASSERT_NE(springs, nullptr);
  EXPECT_EQ(springs->component(), "MeshSpringForceField");
  // One spring per distinct edge of the tetrahedra.
  EXPECT_EQ(static_cast<Index>(springs->springs().size()), fields[1]->mesh().num_edges());
  // The triangles' springs are the tetrahedra's edges again (SOFA's triangle array of the tetrahedra).
  const LoadedScene faces = build(beam("<MeshSpringForceField trianglesStiffness=\"3\"/>"));
  const auto& face_fields = faces.simulation.objects[0].system.force_fields;
  ASSERT_EQ(face_fields.size(), 2u);
  const auto* face_springs = dynamic_cast<const SpringForceField<double>*>(face_fields[1].get());
  ASSERT_NE(face_springs, nullptr);
  EXPECT_EQ(static_cast<Index>(face_springs->springs().size()), face_fields[1]->mesh().num_edges());
}

TEST(SofaIntegrators, ExplicitAndNewmarkSolversAreBuilt) {
  const LoadedScene euler = build(beam("", "<EulerExplicitSolver symplectic=\"0\"/>"));
  EXPECT_NE(dynamic_cast<ExplicitEulerSolver<double>*>(euler.simulation.objects[0].ode_solver.get()), nullptr);
  const LoadedScene rk4 = build(beam("", "<RungeKutta4Solver/>"));
  EXPECT_NE(dynamic_cast<RungeKutta4Solver<double>*>(rk4.simulation.objects[0].ode_solver.get()), nullptr);
  LoadedScene newmark = build(beam("", "<NewmarkImplicitSolver rayleighStiffness=\"0.1\"/><SparseLDLSolver/>"));
  EXPECT_NE(dynamic_cast<NewmarkSolver<double>*>(newmark.simulation.objects[0].ode_solver.get()), nullptr);
  newmark.simulation.step();
  EXPECT_EQ(newmark.simulation.objects[0].ode_solver->carried_state().size(), 1u + 3 * 12);
  // A consistent mass with an explicit solver and no linear solver: refused at the first step.
  std::string consistent = beam("", "<EulerExplicitSolver/>");
  consistent.replace(consistent.find("<UniformMass totalMass=\"1\"/>"), 28, "<MeshMatrixMass totalMass=\"1\"/>");
  LoadedScene scene = build(consistent);
  try {
    scene.simulation.step();
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("needs a linear solver"), std::string::npos);
  }
  EXPECT_NE(error_of(beam("", "<NewmarkImplicitSolver beta=\"-1\"/><SparseLDLSolver/>")).find("beta"), std::string::npos);
}

TEST(SofaTrianglePressure, RestAreaTimesPressureOnTheBoundaryTrianglesInTheBox) {
  // The grid's x = 2 face (4 points, 2 boundary triangles of area 1/2 each) under pressure (1, 2, 3).
  const LoadedScene scene = build(beam(
      "<Node name=\"surface\"><TriangleSetTopologyContainer name=\"triangles\"/>"
      "<Tetra2TriangleTopologicalMapping input=\"@../tets\" output=\"@triangles\"/>"
      "<BoxROI name=\"roi\" box=\"1.9 -1 -1 2.1 2 2\" triangles=\"@triangles.triangles\"/>"
      "<TrianglePressureForceField pressure=\"1 2 3\" triangleList=\"@roi.triangleIndices\"/></Node>"));
  const auto& loads = scene.simulation.objects[0].system.constant_forces;
  ASSERT_EQ(loads.size(), 1u);
  ASSERT_EQ(loads[0].indices.size(), 6u);
  Vec3<double> total = Vec3<double>::Zero();
  for (std::size_t i = 0; i < loads[0].indices.size(); ++i) {
    EXPECT_EQ(static_cast<int>(loads[0].indices[i]) % 3, 2);  // points at x = 2
    total += loads[0].forces[i];
  }
  EXPECT_NEAR((total - Vec3<double>(1, 2, 3)).norm(), 0, 1e-14);  // face area 1
  EXPECT_NE(error_of(beam("<TrianglePressureForceField pressure=\"1 0 0\" triangleList=\"1000\"/>")).find("triangle 1000 out of range"),
            std::string::npos);
  EXPECT_NE(error_of(beam("<TrianglePressureForceField useConstantForce=\"0\"/>")).find("useConstantForce"), std::string::npos);
}

TEST(SofaLinks, RelativeIndexNamesAnEarlierComponentOfTheNode) {
  const LoadedScene scene = build(beam("<BoxROI box=\"-0.1 -1 -1 0.1 2 2\"/><FixedProjectiveConstraint indices=\"@[-1].indices\"/>"));
  EXPECT_EQ(scene.simulation.objects[0].system.fixed, (std::vector<Index>{0, 3, 6, 9}));
  EXPECT_NE(error_of(beam("<FixedProjectiveConstraint indices=\"@[-40].indices\"/>")).find("no component 40 places before"),
            std::string::npos);
}

TEST(SofaNodes, EveryNodeHasTheRootsGravity) {
  // SOFA copies each node's context from its parent's (Node::updateContext): a child node's own
  // gravity is overwritten, as SOFA's regression reference of Benchmark/Analysis/Pendulum.scn shows
  // (its pendulums, in nodes with gravity along -y, fall along the root's -z). Warned once per node.
  const LoadedScene scene = build("<Node name=\"outer\" gravity=\"0 0 -3\">" + beam("") + "</Node>", "gravity=\"0 -10 0\"");
  EXPECT_EQ(scene.simulation.objects[0].system.gravity, Vec3<double>(0, -10, 0));
  int said = 0;
  for (const auto& line : scene.warnings) said += line.find("gravity 0 0 -3 is not used") != std::string::npos;
  EXPECT_EQ(said, 1);
  // The root's own value written again on a child: nothing to say.
  const LoadedScene same = build("<Node name=\"outer\" gravity=\"0 -10 0\">" + beam("") + "</Node>", "gravity=\"0 -10 0\"");
  for (const auto& line : same.warnings) EXPECT_EQ(line.find("gravity"), std::string::npos) << line;
}

TEST(SofaPenaltyForceFields, PlaneAndConeAreBuilt) {
  const LoadedScene scene = build(beam("<PlaneForceField normal=\"0 0 1\" d=\"-1\" stiffness=\"10\"/>"
                                       "<ConicalForceField coneCenter=\"0 0 -5\" coneHeight=\"0 0 20\" coneAngle=\"30\"/>"));
  const auto& fields = scene.simulation.objects[0].system.force_fields;
  ASSERT_EQ(fields.size(), 3u);
  EXPECT_EQ(fields[1]->component(), "PlaneForceField");
  EXPECT_EQ(fields[2]->component(), "ConicalForceField");
  EXPECT_NE(error_of(beam("<ConicalForceField/>")).find("coneHeight is zero"), std::string::npos);
  EXPECT_NE(error_of(beam("<PlaneForceField stiffness=\"-1\"/>")).find("stiffness = -1"), std::string::npos);
}

TEST(SofaTetrahedralCorotational, TheSameElementAsTetrahedronFEMForceField) {
  for (const std::string method : {"small", "large", "polar"}) {
    std::string older = beam("", "<EulerImplicitSolver/><CGLinearSolver/>");
    older.replace(older.find("TetrahedronFEMForceField"), 24, "TetrahedralCorotationalFEMForceField method=\"" + method + "\"");
    std::string newer = beam("", "<EulerImplicitSolver/><CGLinearSolver/>");
    newer.replace(newer.find("TetrahedronFEMForceField"), 24, "TetrahedronFEMForceField method=\"" + method + "\"");
    LoadedScene a = build(older, "gravity=\"0 -3 1\""), b = build(newer, "gravity=\"0 -3 1\"");
    EXPECT_EQ(a.simulation.objects[0].system.force_fields[0]->component(), "TetrahedralCorotationalFEMForceField");
    for (int s = 0; s < 3; ++s) {
      a.simulation.step();
      b.simulation.step();
    }
    EXPECT_EQ(a.simulation.objects[0].system.state.position, b.simulation.objects[0].system.state.position) << method;
  }
  // Any other method name is large, as in SOFA (with an info line).
  std::string other = beam("");
  other.replace(other.find("TetrahedronFEMForceField"), 24, "TetrahedralCorotationalFEMForceField method=\"qr\"");
  EXPECT_EQ(build(other).simulation.objects[0].system.force_fields[0]->method_name(), "large");
}

TEST(SofaProjectiveConstraints, AffineMovementOnThePairBoxShell) {
  // The 3x2x2 grid: the shell between [-1, 3]^3 and the box around x = 1 holds the points at x = 0, 2.
  const std::string body = beam(
      "<PairBoxROI name=\"pair\" inclusiveBox=\"3 3 3 -1 -1 -1\" includedBox=\"0.5 -1 -1 1.5 2 2\"/>"
      "<AffineMovementProjectiveConstraint indices=\"@pair.indices\" rotation=\"[0 -1 0, 1 0 0, 0 0 1]\" translation=\"1 0 0\" "
      "endConstraintTime=\"0.02\"/>");
  LoadedScene scene = build(body, "dt=\"0.01\"");
  auto& system = scene.simulation.objects[0].system;
  ASSERT_EQ(system.motions.size(), 8u);
  EXPECT_EQ(system.motions[1].point, 2);
  // Point 2 at (2, 0, 0) goes to R (2, 0, 0) + (1, 0, 0) = (1, 2, 0): half way after the second step
  // (which starts at t = 0.01), there at the third.
  scene.simulation.step();
  EXPECT_EQ(system.state.position[2], Vec3<double>(2, 0, 0));
  scene.simulation.step();
  EXPECT_NEAR((system.state.position[2] - Vec3<double>(1.5, 1, 0)).norm(), 0, 1e-12);
  scene.simulation.step();
  EXPECT_NEAR((system.state.position[2] - Vec3<double>(1, 2, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(system.state.velocity[2], Vec3<double>::Zero());
  EXPECT_NE(error_of(beam("<AffineMovementProjectiveConstraint indices=\"1\" rotation=\"1 0 0\"/>")).find("rotation needs 9 numbers"),
            std::string::npos);
}

TEST(SofaProjectiveConstraints, PatchTestMovementInterpolatesTheCornerMovements) {
  // The beam's 8 box corners (x = 0, 2) in grid order are the constrained points; SOFA's corner
  // search gives corners 0, 1, 3, 4 at (0,0,0), (2,0,0), (0,1,0) and (2,1,1) (worked by hand from
  // its tests), so alpha = x / 2, beta = y, gamma = z, and movement k belongs to the box corner
  // (0,0,0), (2,0,0), (2,1,0), (0,1,0), then the same at z = 1.
  const std::string corners = "0 0 0  2 0 0  0 1 0  2 1 0  0 0 1  2 0 1  0 1 1  2 1 1";
  const std::string movements = "1 0 0  0 1 0  0 0 1  1 1 0  0 1 1  1 0 1  2 0 0  0 2 0";
  LoadedScene scene = build(beam("<PatchTestMovementProjectiveConstraint indices=\"2 7 10\" constrainedPoints=\"" + corners +
                                 "\" cornerMovements=\"" + movements + "\" endConstraintTime=\"0.01\"/>"),
                            "dt=\"0.01\"");
  const auto& motions = scene.simulation.objects[0].system.motions;
  ASSERT_EQ(motions.size(), 3u);
  const Vec3<double> m[8] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}, {2, 0, 0}, {0, 2, 0}};
  // Point 2 = (2, 0, 0): movement 1. Point 7 = (1, 0, 1): half of movements 4 and 5. Point 10 =
  // (1, 1, 1): half of movements 6 and 7.
  EXPECT_LT((motions[0].end - (Vec3<double>(2, 0, 0) + m[1])).norm(), 1e-15);
  EXPECT_LT((motions[1].end - (Vec3<double>(1, 0, 1) + 0.5 * (m[4] + m[5]))).norm(), 1e-15);
  EXPECT_LT((motions[2].end - (Vec3<double>(1, 1, 1) + 0.5 * (m[6] + m[7]))).norm(), 1e-15);
  EXPECT_TRUE(scene.warnings.empty());
  // Planar constrained points: four corners, bilinear; a short list warns and moves by zero.
  LoadedScene planar = build(beam("<PatchTestMovementProjectiveConstraint indices=\"1\" constrainedPoints=\"0 0 0 2 0 0 0 1 0 2 1 0\" "
                                  "cornerMovements=\"0 0 0  4 0 0  0 0 0 .5\"/>"));
  EXPECT_LT((planar.simulation.objects[0].system.motions[0].end - Vec3<double>(3, 0, 0)).norm(), 1e-15);
  ASSERT_EQ(planar.warnings.size(), 2u);
  EXPECT_NE(planar.warnings[0].find("not a multiple of 3"), std::string::npos);
  EXPECT_NE(planar.warnings[1].find("3 movements"), std::string::npos);
}

TEST(SofaProjectiveConstraints, PointHoldsPointsAtItsPoint) {
  LoadedScene scene = build(beam("<PointProjectiveConstraint indices=\"5 7\" point=\"1 2 3\"/><PointProjectiveConstraint/>"));
  auto& system = scene.simulation.objects[0].system;
  scene.simulation.step();
  EXPECT_EQ(system.state.position[5], Vec3<double>(1, 2, 3));
  EXPECT_EQ(system.state.position[7], Vec3<double>(1, 2, 3));
  EXPECT_EQ(system.state.position[0], Vec3<double>::Zero());  // the default: point 0 held at the origin
  EXPECT_EQ(system.state.velocity[5], Vec3<double>::Zero());
  EXPECT_NE(system.state.velocity[4], Vec3<double>::Zero());
  EXPECT_NE(error_of(beam("<PointProjectiveConstraint indices=\"12\"/>")).find("index 12 out of range"), std::string::npos);
}

TEST(SofaTetrahedronFEM, UpdateStiffnessMatrixForPolarAndSvdOnly) {
  std::string polar = beam("");
  polar.replace(polar.find("TetrahedronFEMForceField"), 24, "TetrahedronFEMForceField method=\"polar\" updateStiffnessMatrix=\"1\"");
  const LoadedScene built = build(polar);
  const auto* field = dynamic_cast<const TetrahedronFEMForceField<double>*>(built.simulation.objects[0].system.force_fields[0].get());
  ASSERT_NE(field, nullptr);
  EXPECT_TRUE(field->parameters().update_stiffness_matrix);
  std::string large = beam("");
  large.replace(large.find("TetrahedronFEMForceField"), 24, "TetrahedronFEMForceField updateStiffnessMatrix=\"1\"");
  EXPECT_NE(error_of(large).find("updateStiffnessMatrix with method large is not supported"), std::string::npos) << error_of(large);
}

TEST(SofaGrid, CylinderGridCarriesTetrahedronFEMAndMeshSprings) {
  LoadedScene scene = build(R"(<Node name="cylinder"><EulerImplicitSolver/><CGLinearSolver/>
    <MechanicalObject/><UniformMass totalMass="1"/><FixedProjectiveConstraint indices="0 1 2"/>
    <CylinderGridTopology n="3 3 4" axis="0 1 0" radius="2" length="6"/>
    <MeshSpringForceField stiffness="100" damping="1"/>
    <TetrahedronFEMForceField method="polar" youngModulus="100"/></Node>)");
  auto& object = scene.simulation.objects[0];
  ASSERT_EQ(object.system.size(), 36);
  // `stiffness` sets every kind (SOFA's alias): the grid's 75 lines, the diagonals of its 52 quads
  // and the 4 of each of its 12 cells.
  ASSERT_EQ(object.system.force_fields.size(), 2u);
  const auto* springs = dynamic_cast<const SpringForceField<double>*>(object.system.force_fields[0].get());
  ASSERT_NE(springs, nullptr);
  EXPECT_EQ(springs->springs().size(), 75u + 104u + 48u);
  EXPECT_EQ(object.system.force_fields[1]->mesh().num_tetrahedra(), 6 * 2 * 2 * 3);
  EXPECT_LT((object.system.state.position[35] - Vec3<double>(std::sqrt(2.0), 6, -std::sqrt(2.0))).norm(), 1e-14);
  scene.simulation.step();
  EXPECT_TRUE(object.system.state.position[35].allFinite());
}

// Two beams: under one solver (SOFA's one system), or each with its own.
std::string two_beams(bool one_solver, const std::string& second_gravity = "") {
  const std::string solver = "<EulerImplicitSolver rayleighMass=\"0.1\"/><EigenSimplicialLDLT/>";
  auto object = [&](const std::string& name, const std::string& min, const std::string& extra) {
    return "<Node name=\"" + name + "\"" + extra + ">" + (one_solver ? "" : solver) +
           "<RegularGridTopology name=\"grid\" n=\"3 2 2\" min=\"" + min + "\" max=\"2 1 1\"/><MechanicalObject/>"
           "<TetrahedronSetTopologyContainer name=\"tets\"/><Hexa2TetraTopologicalMapping input=\"@grid\" output=\"@tets\"/>"
           "<UniformMass totalMass=\"1\"/><TetrahedronFEMForceField youngModulus=\"100\" poissonRatio=\"0.3\"/>"
           "<FixedProjectiveConstraint indices=\"0 3\"/></Node>";
  };
  return "<Node name=\"group\">" + (one_solver ? solver : std::string()) + object("a", "0 0 0", "") +
         object("b", "0 0 5", second_gravity) + "</Node>";
}

TEST(SofaSolvers, ObjectsUnderOneSolverAreOneSystem) {
  LoadedScene together = build(two_beams(true), "gravity=\"0 -9.81 1\"");
  LoadedScene apart = build(two_beams(false), "gravity=\"0 -9.81 1\"");
  ASSERT_EQ(together.simulation.objects.size(), 1u);
  ASSERT_EQ(apart.simulation.objects.size(), 2u);
  EXPECT_EQ(together.state_counts, (std::vector<std::size_t>{2}));
  const auto& merged = together.simulation.objects[0].system;
  EXPECT_EQ(merged.size(), 24);
  EXPECT_EQ(merged.fixed, (std::vector<Index>{0, 3, 12, 15}));
  for (int s = 0; s < 5; ++s) {
    together.simulation.step();
    apart.simulation.step();
  }
  // A block-diagonal system: the joint direct solve is each object's, up to rounding.
  for (std::size_t o = 0; o < 2; ++o) {
    for (std::size_t i = 0; i < 12; ++i) {
      EXPECT_LT((merged.state.position[12 * o + i] - apart.simulation.objects[o].system.state.position[i]).norm(), 1e-10);
    }
  }
  // A node's own gravity is the root's in SOFA (SofaNodes.EveryNodeHasTheRootsGravity): one system still.
  EXPECT_EQ(error_of(two_beams(true, " gravity=\"0 0 -1\"")), "");
}

// two_beams(one_solver) with an AttachProjectiveConstraint in the group node.
std::string attached_beams(const std::string& attach, bool one_solver = true) {
  std::string scene = two_beams(one_solver);
  scene.insert(scene.rfind("</Node>"), "<AttachProjectiveConstraint " + attach + "/>");
  return scene;
}

TEST(SofaAttach, PairsOfTwoObjectsBecomeCouplingsOfTheMergedSystem) {
  const LoadedScene scene = build(attached_beams(
      "object1=\"@a\" object2=\"@b\" twoWay=\"1\" indices1=\"1 2\" indices2=\"4 5\" constraintFactor=\"1 0.5\" "
      "positionFactor=\"0.8\" velocityFactor=\"0.6\" responseFactor=\"0.4\""));
  const auto& couplings = scene.simulation.objects[0].system.couplings;
  ASSERT_EQ(couplings.size(), 2u);
  // b's points follow a's 12 in the merged state; each factor is SOFA's 0.5 factor constraintFactor.
  EXPECT_EQ(couplings[1].first, 2);
  EXPECT_EQ(couplings[1].second, 12 + 5);
  EXPECT_TRUE(couplings[1].two_way);
  EXPECT_EQ(couplings[1].response, 0.5 * 0.4 * 0.5);
  EXPECT_EQ(couplings[1].position, 0.5 * 0.8 * 0.5);
  EXPECT_EQ(couplings[1].velocity, 0.5 * 0.6 * 0.5);
  const LoadedScene one_way = build(attached_beams("object1=\"@a\" object2=\"@b\" indices1=\"1\" indices2=\"4\""));
  const auto& c = one_way.simulation.objects[0].system.couplings;
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].two_way);
  EXPECT_EQ(c[0].position, 0.5);
}

TEST(SofaAttach, TheSecondObjectHangsFromTheFirst) {
  // b's corners 0 and 3 are fixed; a (not fixed) hangs by its far end (points 2, 5, 8, 11 at x = 2)
  // from b's near face (0, 3, 6, 9 at x = 0, 5 further along z).
  std::string scene = attached_beams("object1=\"@b\" object2=\"@a\" indices1=\"0 3 6 9\" indices2=\"2 5 8 11\"");
  const std::string fixed = "<FixedProjectiveConstraint indices=\"0 3\"/>";
  scene.replace(scene.find(fixed), fixed.size(), "");  // a's only
  LoadedScene built = build(scene);
  auto& system = built.simulation.objects[0].system;
  for (int s = 0; s < 20; ++s) built.simulation.step();
  // One way: every step a's point moves halfway to b's (5 away at first), so a follows b closely.
  for (Index k = 0; k < 4; ++k) {
    const Vec3<double> gap = system.state.position[static_cast<std::size_t>(3 * k + 2)] - system.state.position[static_cast<std::size_t>(12 + 3 * k)];
    EXPECT_LT(gap.norm(), 0.02) << k;
  }
}

TEST(SofaAttach, BadPairsAreRefused) {
  EXPECT_NE(error_of(attached_beams("object1=\"@a\" object2=\"@b\" indices1=\"1\" indices2=\"12\"")).find("indices2 index 12 out of range"),
            std::string::npos);
  EXPECT_NE(error_of(attached_beams("object1=\"@a\" object2=\"@b\" indices1=\"1 2\" indices2=\"4\"")).find("one per pair"),
            std::string::npos);
  EXPECT_NE(error_of(attached_beams("object1=\"@a\" object2=\"@b\" indices1=\"1\" indices2=\"4\" constraintFactor=\"1 1\"")).find("constraintFactor"),
            std::string::npos);
  EXPECT_NE(error_of(attached_beams("object1=\"@a\" object2=\"@b\" indices1=\"1\" indices2=\"4\" minDistance=\"0.1\"")).find("minDistance"),
            std::string::npos);
  EXPECT_NE(error_of(attached_beams("object1=\"@a/grid\" object2=\"@b\" indices1=\"1\" indices2=\"4\"")).find("not a MechanicalObject"),
            std::string::npos);
  EXPECT_NE(error_of(attached_beams("object1=\"@a\" object2=\"@c\" indices1=\"1\" indices2=\"4\"")).find("broken link"), std::string::npos);
  EXPECT_NE(error_of(attached_beams("object1=\"@a\" object2=\"@b\" indices1=\"1\" indices2=\"4\"", false)).find("no ODE solver"),
            std::string::npos);
}

TEST(SofaPlasticity, TheSceneAttributesReachTheForceField) {
  std::string plastic = beam("");
  plastic.replace(plastic.find("TetrahedronFEMForceField"), 24,
                  "TetrahedronFEMForceField plasticMaxThreshold=\"0.1\" plasticYieldThreshold=\"0.02\" plasticCreep=\"0.5\"");
  const LoadedScene built = build(plastic);
  const auto* field = dynamic_cast<const TetrahedronFEMForceField<double>*>(built.simulation.objects[0].system.force_fields[0].get());
  ASSERT_NE(field, nullptr);
  EXPECT_EQ(field->parameters().plastic_max_threshold, 0.1);
  EXPECT_EQ(field->parameters().plastic_yield_threshold, 0.02);
  EXPECT_EQ(field->parameters().plastic_creep, 0.5);
  std::string assembled = plastic;
  assembled.replace(assembled.find("plasticMaxThreshold"), 0, "computeGlobalMatrix=\"1\" ");
  EXPECT_NE(error_of(assembled).find("plasticity with computeGlobalMatrix"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
