// Collision and penalty contact through the scene builder: a soft cube falling on a still floor
// against SOFA's own trajectory (tests/data/sofa_reference/cube_on_floor*), contacts counted as
// SOFA counts them; a point mass resting on a triangle at the closed-form height d − m g / k for
// 10,000 steps; what is not simulated yet warned in one line per component; bad input refused.
#include "fastcorot/collision/contact_pipeline.h"
#include "fastcorot/core/parallel.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"
#include "fastcorot/state/rigid3.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tetrahedron_faces.h"

#include "../support/scene_text.h"
#include "support/contact_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

TEST(CollisionScene, SoftCubeFallsOnAFloorAsInSofa) {
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("cube_on_floor.scn"));
  const auto reference = testing::load_sofa_trajectory("cube_on_floor_trajectory.json");
  auto& simulation = scene.simulation;
  ASSERT_TRUE(simulation.collisions);
  ASSERT_EQ(simulation.objects.size(), 1u);
  const auto& x = simulation.objects[0].system.state.position;
  const auto rest = testing::json_points(reference["steps"]["0"]["points"]);
  for (const long step : testing::dumped_steps(reference)) {
    while (simulation.steps_done() < step) simulation.step();
    const auto& frame = reference["steps"][std::to_string(step)];
    const auto d = testing::compare_points(x, testing::json_points(frame["points"]), rest);
    EXPECT_LE(d.difference, 1e-9 * d.displacement + 1e-15) << "step " << step;
    // SOFA counts its detection outputs; the penalty keeps one per point here, so the two agree.
    if (step > 0) {
      EXPECT_EQ(simulation.collision_report().contacts, frame["contacts"].get<int>()) << "step " << step;
    }
  }
  const double lowest = std::min_element(x.begin(), x.end(), [](const auto& a, const auto& b) { return a.y() < b.y(); })->y();
  EXPECT_GT(lowest, -0.3) << "resting on the floor, not through it";
}

TEST(CollisionScene, SpheresOnSpheresFollowSofa) {
  // DiscreteIntersection: overlapping spheres only. SOFA counts its detection outputs; its penalty
  // keeps one contact per id (the floor sphere's index here), as fastcorot's count does.
  testing::expect_contact_trajectory("spheres_on_spheres.scn", "spheres_on_spheres_trajectory.json", 1e-9,
                                     {.contacts = false, .rows = false});
}

TEST(CollisionScene, StickSpringsFollowSofaAndStayAliveWhileNothingIsFound) {
  // StickContactForceField: springs at rest where detection finds the pair, kept while it finds
  // nothing (steps 3 to 33 in SOFA), pulling the cube back.
  testing::expect_contact_trajectory("stick_on_spheres.scn", "stick_on_spheres_trajectory.json", 1e-9, {.contacts = false, .rows = false});
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("stick_on_spheres.scn"));
  const auto reference = testing::load_sofa_trajectory("stick_on_spheres_trajectory.json");
  for (int step = 1; step <= 10; ++step) scene.simulation.step();
  ASSERT_EQ(reference["steps"]["10"]["contacts"].get<int>(), 0) << "SOFA finds nothing at step 10";
  EXPECT_GT(scene.simulation.collision_report().contacts, 0) << "the springs of step 2, kept alive";
}

TEST(CollisionScene, SelfCollisionFollowsSofasPruning) {
  // Triangle, Line and Point models of one node with selfCollision: the cubes' own adjacent elements
  // are pruned (without that, a cube's own vertices sit at distance 0 from its triangles and push it
  // apart), the falling cube rests on the fixed one as in SOFA.
  testing::expect_contact_trajectory("self_collision_cubes.scn", "self_collision_cubes_trajectory.json", 1e-9,
                                     {.contacts = false, .rows = false});
}

TEST(CollisionScene, RigidSpheresFollowSofaWithTheRadiusCountedTwice) {
  // SOFA's RigidSphereModel: the contact point is the sphere's surface point, carried by the rigid,
  // and the radius is added to the contact distance too. A ball meets the cube's Vec3 spheres
  // (explicit, two bodies), a bead a still sphere (implicit); both are thrown back up, as in SOFA.
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("rigid_spheres_on_spheres.scn"));
  const auto reference = testing::load_sofa_trajectory("rigid_spheres_on_spheres_trajectory.json");
  auto& simulation = scene.simulation;
  ASSERT_TRUE(simulation.collisions);
  ASSERT_EQ(simulation.objects.size(), 3u);  // cube, ball, bead: one object per solver
  const auto rest = testing::json_points(reference["steps"]["0"]["points"]);
  int contacts = 0;
  double highest = 0;
  for (const long step : testing::dumped_steps(reference)) {
    while (simulation.steps_done() < step) simulation.step();
    highest = std::max(highest, simulation.objects[1].system.state.position[0].y());
    const auto& frame = reference["steps"][std::to_string(step)];
    const auto d = testing::compare_points(simulation.objects[0].system.state.position, testing::json_points(frame["points"]), rest);
    EXPECT_LE(d.difference, 1e-9 * d.displacement + 1e-15) << "cube, step " << step;
    for (const auto& [object, name] : {std::pair{std::size_t{1}, "ball"}, std::pair{std::size_t{2}, "bead"}}) {
      const auto& system = simulation.objects[object].system;
      ASSERT_TRUE(system.rigids);
      const RigidCoord<double> coord = system.rigids->coord(system.state.position, 0);
      const auto& sofa = frame[name];
      const Vec3<double> centre(sofa[0].get<double>(), sofa[1].get<double>(), sofa[2].get<double>());
      const Eigen::Quaterniond q(sofa[6].get<double>(), sofa[3].get<double>(), sofa[4].get<double>(), sofa[5].get<double>());
      EXPECT_LE((coord.center - centre).norm(), 1e-9 * std::max(1.0, centre.norm())) << name << ", step " << step;
      EXPECT_LE(std::abs(std::abs(coord.orientation.dot(q)) - 1), 1e-12) << name << ", step " << step;
    }
    if (step > 0) {
      EXPECT_EQ(simulation.collision_report().contacts, frame["contacts"].get<int>()) << "step " << step;
    }
    contacts += simulation.collision_report().contacts;
  }
  EXPECT_EQ(contacts, 2);  // each body's one contact
  EXPECT_GT(highest, 1.6) << "the ball was thrown above where it started";
}

// A point of mass m above a still triangle in the plane y = 0; contact distance d, stiffnesses
// ks₁ = ks₂ = s, so k = s² / d.
std::string point_over_floor(double height, const std::string& extra = "") {
  return "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
         "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/><CollisionResponse response=\"PenalityContactForceField\"/>"
         "<Node name=\"ball\"><EulerImplicitSolver rayleighMass=\"2\" rayleighStiffness=\"0\"/><CGLinearSolver iterations=\"100\" "
         "tolerance=\"1e-30\" threshold=\"1e-30\"/><MechanicalObject name=\"point\" position=\"0.1 " + std::to_string(height) +
         " 0.2\"/><UniformMass totalMass=\"0.5\"/><PointCollisionModel contactStiffness=\"20\"/>" + extra + "</Node>"
         "<Node name=\"floor\"><MeshTopology position=\"-1 0 -1  1 0 -1  0 0 2\" triangles=\"0 2 1\"/><MechanicalObject/>"
         "<TriangleCollisionModel simulated=\"0\" moving=\"0\" contactStiffness=\"20\"/></Node>";
}

TEST(CollisionScene, APointMassRestsAtTheClosedFormHeightAndNeverSinks) {
  LoadedScene scene = build_scene_text(point_over_floor(0.4), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  ASSERT_TRUE(scene.simulation.collisions);
  const auto& x = scene.simulation.objects[0].system.state.position;
  const double d = 0.2, k = 20.0 * 20.0 / d, expected = d - 0.5 * 9.81 / k;
  double lowest = 1;
  for (int step = 0; step < 10000; ++step) {
    scene.simulation.step();
    lowest = std::min(lowest, x[0].y());
  }
  EXPECT_NEAR(x[0].y(), expected, 1e-9);
  EXPECT_NEAR(x[0].x(), 0.1, 1e-12);
  EXPECT_GT(lowest, 0.0) << "never through the floor";
  EXPECT_EQ(scene.simulation.collision_report().contacts, 1);
}

TEST(CollisionScene, SofasParallelPhasesAreThePhases) {
  // The MultiThreading plugin's ParallelBruteForceBroadPhase and ParallelBVHNarrowPhase give the
  // same outputs as the sequential phases (FreeMotionAnimationLoop.scn suggests the swap).
  std::string text = point_over_floor(0.4);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"<BruteForceBroadPhase/>", "<ParallelBruteForceBroadPhase/>"},
                                 {"<BVHNarrowPhase/>", "<ParallelBVHNarrowPhase/>"}}) {
    text.replace(text.find(from), from.size(), to);
  }
  LoadedScene parallel = build_scene_text(text, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  LoadedScene plain = build_scene_text(point_over_floor(0.4), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  ASSERT_TRUE(parallel.simulation.collisions);
  for (int step = 0; step < 100; ++step) {
    parallel.simulation.step();
    plain.simulation.step();
    ASSERT_EQ(parallel.simulation.objects[0].system.state.position[0], plain.simulation.objects[0].system.state.position[0]) << step;
  }
  EXPECT_EQ(parallel.simulation.collision_report().contacts, 1);
}

TEST(CollisionScene, PointsAMesh2PointMappingPlacedAreAStillObstacle) {
  // SOFA's Mesh2PointTopologicalMapping.scn: spheres on the points the mapping placed (no mass, no
  // force: SOFA integrates them with nothing acting, so they stay put) meet a falling point.
  LoadedScene scene = build_scene_text(
      "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
      "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/><CollisionResponse response=\"PenalityContactForceField\"/>"
      "<Node name=\"m\"><EulerImplicitSolver/><CGLinearSolver iterations=\"100\" tolerance=\"1e-20\" threshold=\"1e-20\"/>"
      "<TetrahedronSetTopologyContainer name=\"c1\" position=\"0 0 0 2 0 0 0 2 0 0 0 2\" tetrahedra=\"0 1 2 3\"/>"
      "<MechanicalObject/><DiagonalMass massDensity=\"1\"/><FixedProjectiveConstraint indices=\"0 1 2 3\"/>"
      "<Node name=\"points\"><PointSetTopologyContainer name=\"c2\"/>"
      "<Mesh2PointTopologicalMapping input=\"@c1\" output=\"@c2\" pointBaryCoords=\"0 0 0\"/>"
      "<MechanicalObject name=\"marks\"/><SphereCollisionModel radius=\"0.25\" contactStiffness=\"20\"/></Node></Node>"
      "<Node name=\"ball\"><EulerImplicitSolver/><CGLinearSolver iterations=\"100\" tolerance=\"1e-20\" threshold=\"1e-20\"/>"
      "<MechanicalObject position=\"0 0 2.8\"/><UniformMass totalMass=\"0.1\"/><PointCollisionModel contactStiffness=\"20\"/></Node>",
      "dt=\"0.01\" gravity=\"0 0 -9.81\"");
  ASSERT_TRUE(scene.simulation.collisions);
  for (const auto& line : scene.warnings) EXPECT_EQ(line.find("not simulated"), std::string::npos) << line;
  int contacts = 0;
  for (int step = 0; step < 300; ++step) {
    scene.simulation.step();
    contacts += scene.simulation.collision_report().contacts;
  }
  EXPECT_GT(contacts, 0);
  EXPECT_GT(scene.simulation.objects.at(1).system.state.position[0].z(), 2.25) << "held above the sphere at (0, 0, 2)";
}

TEST(CollisionScene, APointThatCrossesTheFloorInOneStepIsReported) {
  // Found 0.4 above the floor moving down at 100 m/s: the penalty cannot stop it within the step.
  LoadedScene fast = build_scene_text(point_over_floor(0.4), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  fast.simulation.objects[0].system.state.velocity[0] = Vec3<double>(0, -100, 0);
  fast.simulation.step();
  const CollisionReport& report = fast.simulation.collision_report();
  EXPECT_EQ(report.contacts, 1);
  EXPECT_EQ(report.crossed, 1);
  const double y = fast.simulation.objects[0].system.state.position[0].y();
  ASSERT_LT(y, 0);
  EXPECT_NEAR(report.deepest_crossing, -y, 1e-12) << "the floor is the plane y = 0";
  EXPECT_NE(report.crossed_models.find("TriangleCollisionModel"), std::string::npos) << report.crossed_models;
  // At rest on the floor: nothing crosses.
  LoadedScene resting = build_scene_text(point_over_floor(0.4), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  for (int step = 0; step < 200; ++step) {
    resting.simulation.step();
    EXPECT_EQ(resting.simulation.collision_report().crossed, 0) << step;
  }
}

TEST(CollisionScene, WhatIsNotSimulatedYetIsWarnedPerComponent) {
  // A model kind not simulated: the scene loads, its collisions ignored, each component saying why.
  std::string text = point_over_floor(0.4);
  text.replace(text.find("<PointCollisionModel"), std::string("<PointCollisionModel").size(), "<TetrahedronCollisionModel/><PointCollisionModel");
  LoadedScene scene = build_scene_text(text, "dt=\"0.01\"");
  EXPECT_FALSE(scene.simulation.collisions);
  int said = 0;
  for (const auto& line : scene.warnings) said += line.find("TetrahedronCollisionModel is not simulated yet") != std::string::npos;
  EXPECT_GE(said, 5) << "the pipeline's components and both models";
  // A collision model without a pipeline: no contacts, as in SOFA (an info line).
  LoadedScene alone = build_scene_text("<Node name=\"b\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject position=\"0 0 0\"/>"
                                       "<UniformMass totalMass=\"1\"/><PointCollisionModel/></Node>");
  EXPECT_FALSE(alone.simulation.collisions);
}

TEST(CollisionScene, ModelsOnATetrahedronContainerTakeEveryFaceAndEdgeWithAWarning) {
  // A soft cube whose Triangle, Line and Point models sit on its TetrahedronSetTopologyContainer (filled
  // by a Hexa2TetraTopologicalMapping): SOFA's triangle and edge arrays of the tetrahedra, inner ones
  // included, warned (SOFA's contact mappers do not follow such models); it lands and rests on a floor.
  const std::string text =
      "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
      "<MinProximityIntersection alarmDistance=\"0.3\" contactDistance=\"0.1\"/><CollisionResponse response=\"PenalityContactForceField\"/>"
      "<Node name=\"cube\"><EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/><SparseLDLSolver/>"
      "<RegularGridTopology name=\"grid\" n=\"3 3 3\" min=\"-0.5 0 -0.5\" max=\"0.5 1 0.5\"/><MechanicalObject name=\"points\"/>"
      "<UniformMass totalMass=\"2\"/><TetrahedronFEMForceField youngModulus=\"2000\" poissonRatio=\"0.3\"/>"
      "<Node name=\"volume\"><TetrahedronSetTopologyContainer name=\"tetrahedra\"/>"
      "<Hexa2TetraTopologicalMapping input=\"@../grid\" output=\"@tetrahedra\"/>"
      "<TriangleCollisionModel contactStiffness=\"30\"/><LineCollisionModel contactStiffness=\"30\"/>"
      "<PointCollisionModel contactStiffness=\"30\"/></Node></Node>"
      "<Node name=\"floor\"><MeshTopology position=\"-3 -0.3 -3  3 -0.3 -3  3 -0.3 3  -3 -0.3 3\" triangles=\"0 2 1  0 3 2\"/>"
      "<MechanicalObject/><TriangleCollisionModel simulated=\"0\" moving=\"0\" contactStiffness=\"30\"/></Node>";
  LoadedScene scene = build_scene_text(text, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const auto* pipeline = dynamic_cast<const ContactPipeline<double>*>(scene.simulation.collisions.get());
  ASSERT_TRUE(pipeline);
  // The mapping's tetrahedra: the grid's cells split as Hexa2TetraTopologicalMapping splits them.
  RegularGrid grid;
  grid.n = {3, 3, 3};
  grid.min = Vec3<double>(-0.5, 0, -0.5);
  grid.max = Vec3<double>(0.5, 1, 0.5);
  const std::vector<Tetrahedron> tetrahedra = grid_tetrahedra(grid, false);
  ASSERT_EQ(tetrahedra.size(), 48u);
  ASSERT_EQ(pipeline->models().size(), 4u);
  EXPECT_EQ(pipeline->models()[0].triangles, tetrahedron_set_triangles(tetrahedra));
  EXPECT_EQ(pipeline->models()[1].edges, tetrahedron_set_edges(tetrahedra));
  int warned = 0;
  for (const auto& line : scene.warnings) warned += line.find("inner ones included") != std::string::npos;
  EXPECT_EQ(warned, 2) << "the Triangle and Line models";
  const auto& x = scene.simulation.objects[0].system.state.position;
  int touching = 0;
  for (int step = 0; step < 200; ++step) {
    scene.simulation.step();
    touching += scene.simulation.collision_report().contacts > 0;
    for (const auto& p : x) ASSERT_GT(p.y(), -0.3) << "step " << step;
  }
  EXPECT_GT(touching, 100);
  // A surface container whose src links the volume (SOFA's TrianglePressureForceField.scn) is a
  // surface, not a volume: its tetrahedra are not its own.
  const std::string surface = std::string(text).replace(
      text.find("<TriangleCollisionModel contactStiffness"),
      0, "<Node name=\"surface\"><TriangleSetTopologyContainer name=\"triangles\" src=\"@../tetrahedra\"/>"
         "<Tetra2TriangleTopologicalMapping input=\"@../tetrahedra\" output=\"@triangles\"/>"
         "<TriangleCollisionModel contactStiffness=\"30\"/></Node>");
  LoadedScene with_surface = build_scene_text(surface, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const auto* surface_pipeline = dynamic_cast<const ContactPipeline<double>*>(with_surface.simulation.collisions.get());
  ASSERT_TRUE(surface_pipeline);
  EXPECT_FALSE(surface_pipeline->models()[0].triangles.empty());
  for (const auto& line : with_surface.warnings) EXPECT_EQ(line.find("is a grid or a volume"), std::string::npos) << line;
}

// Two point masses closing head-on, each under its own solver, no gravity: SOFA's explicit penalty
// (its response in the root, outside both solvers), evaluated once per step at the step's start.
std::string two_points(const std::string& root_solver = "") {
  return root_solver +
         "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
         "<MinProximityIntersection alarmDistance=\"0.2\" contactDistance=\"0.1\"/><CollisionResponse response=\"PenalityContactForceField\"/>"
         "<Node name=\"a\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
         "<MechanicalObject position=\"0 0 0\" velocity=\"1 0 0\"/><UniformMass totalMass=\"2\"/><PointCollisionModel contactStiffness=\"5\"/></Node>"
         "<Node name=\"b\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
         "<MechanicalObject position=\"0.3 0 0\" velocity=\"-0.5 0 0\"/><UniformMass totalMass=\"1\"/><PointCollisionModel contactStiffness=\"4\"/></Node>";
}

TEST(CollisionScene, ExplicitPenaltyBetweenTwoBodiesKeepsMomentumAndActsOncePerStep) {
  LoadedScene scene = build_scene_text(two_points(), "dt=\"0.01\" gravity=\"0 0 0\"");
  auto& simulation = scene.simulation;
  ASSERT_TRUE(simulation.collisions);
  ASSERT_EQ(simulation.objects.size(), 2u);
  auto& a = simulation.objects[0].system.state;
  auto& b = simulation.objects[1].system.state;
  const double p0 = 2 * a.velocity[0].x() + b.velocity[0].x();
  const double d = 0.1, k = 5.0 * 4.0 / d, h = 0.01;
  bool touched = false;
  for (int step = 0; step < 60; ++step) {
    const double gap = b.position[0].x() - a.position[0].x();
    const double va = a.velocity[0].x(), vb = b.velocity[0].x();
    simulation.step();
    // The force k (d − gap) n, from the positions the step began at, over the step: Δv = h f / m.
    const double f = gap < d ? k * (d - gap) : 0.0;
    touched = touched || f > 0;
    EXPECT_NEAR(a.velocity[0].x(), va - h * f / 2, 1e-12) << "step " << step;
    EXPECT_NEAR(b.velocity[0].x(), vb + h * f / 1, 1e-12) << "step " << step;
    EXPECT_NEAR(2 * a.velocity[0].x() + b.velocity[0].x(), p0, 1e-12) << "step " << step;
  }
  EXPECT_TRUE(touched);
  EXPECT_GT(b.velocity[0].x(), a.velocity[0].x()) << "pushed apart";
}

// A rigid ball of radius 0.3 overlapping a still Vec3 sphere of radius 0.5 (centres 0.7 apart) under
// `method`, or a `model` on the rigid state.
std::string rigid_ball(const std::string& method, const std::string& model = "<SphereCollisionModel radius=\"0.3\"/>") {
  return "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>" + method +
         "<CollisionResponse response=\"PenalityContactForceField\"/>"
         "<Node name=\"ball\"><EulerImplicitSolver/><CGLinearSolver iterations=\"100\" tolerance=\"1e-30\" threshold=\"1e-30\"/>"
         "<MechanicalObject template=\"Rigid3d\" position=\"0 0.7 0  0 0 0 1\"/><UniformMass totalMass=\"1\"/>" + model + "</Node>"
         "<Node name=\"post\"><MechanicalObject position=\"0 0 0\"/><SphereCollisionModel radius=\"0.5\" simulated=\"0\"/></Node>";
}

TEST(CollisionScene, RigidSpheresMeetWhereSofaHasARuleForThem) {
  // DiscreteIntersection: the post's point is its centre, the ball's its surface point (SOFA's
  // getContactPointByNormal), pushed by k (d − gap), d = r₁ + r₂ as the mappers add them.
  LoadedScene discrete = build_scene_text(rigid_ball("<DiscreteIntersection/>"), "dt=\"0.01\" gravity=\"0 0 0\"");
  ASSERT_TRUE(discrete.simulation.collisions);
  discrete.simulation.step();
  EXPECT_EQ(discrete.simulation.collision_report().contacts, 1);
  const auto& x = discrete.simulation.objects[0].system.state.position;
  // Implicit Euler from rest, m = 1: v = h k pen / (m + h² k), k = 10·10 / 0.8, pen = 0.8 − (0.7 − 0.3).
  const double h = 0.01, k = 100 / 0.8, pen = 0.8 - 0.4;
  EXPECT_NEAR(x[0].y(), 0.7 + h * h * k * pen / (1 + h * h * k), 1e-12) << "pushed from its surface point";
  // LocalMinDistance registers its sphere rules for Vec3 spheres only: no pair, no contact.
  LoadedScene lmd = build_scene_text(rigid_ball("<LocalMinDistance alarmDistance=\"1\" contactDistance=\"0.1\"/>"), "dt=\"0.01\" gravity=\"0 0 0\"");
  lmd.simulation.step();
  EXPECT_EQ(lmd.simulation.collision_report().contacts, 0);
  EXPECT_EQ(lmd.simulation.objects[0].system.state.position[0].y(), 0.7);
  // Other models on a Rigid3 state need its points under a RigidMapping: said, not simulated.
  LoadedScene point = build_scene_text(rigid_ball("<DiscreteIntersection/>", "<PointCollisionModel/>"), "dt=\"0.01\"");
  EXPECT_FALSE(point.simulation.collisions);
  bool said = false;
  for (const auto& line : point.warnings) said = said || line.find("a PointCollisionModel on a Rigid3 state") != std::string::npos;
  EXPECT_TRUE(said);
}

// 1,600 points over a floor of 2 × 39 × 39 triangles: enough element pairs for several chunks of
// the narrow phase.
std::string rain_over_floor() {
  std::string floor_points, triangles, drops;
  const int n = 40;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) floor_points += std::to_string(0.1 * i) + " 0 " + std::to_string(0.1 * j) + "  ";
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      triangles += std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(b) + "  " + std::to_string(b) + " " +
                   std::to_string(c) + " " + std::to_string(d) + "  ";
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      drops += std::to_string(0.1 * i + 0.037) + " " + std::to_string(0.05 + 0.002 * ((i * 7 + j * 3) % 11)) + " " +
               std::to_string(0.1 * j + 0.041) + "  ";
    }
  }
  return "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
         "<MinProximityIntersection alarmDistance=\"0.1\" contactDistance=\"0.03\"/><CollisionResponse response=\"PenalityContactForceField\"/>"
         "<Node name=\"rain\"><EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-12\" threshold=\"1e-20\"/>"
         "<MechanicalObject position=\"" + drops + "\"/><UniformMass totalMass=\"1\"/><PointCollisionModel contactStiffness=\"30\"/></Node>"
         "<Node name=\"floor\"><MeshTopology position=\"" + floor_points + "\" triangles=\"" + triangles + "\"/><MechanicalObject/>"
         "<TriangleCollisionModel simulated=\"0\" moving=\"0\" contactStiffness=\"30\"/></Node>";
}

TEST(CollisionScene, OneAndTwoThreadsFindTheSameContactsBitwise) {
  set_yield_cores_to_other_processes(false);  // two threads even on a busy machine
  LoadedScene one = build_scene_text(rain_over_floor(), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  LoadedScene two = build_scene_text(rain_over_floor(), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  one.simulation.threads = 1;
  two.simulation.threads = 2;
  long pairs = 0;
  for (int step = 0; step < 20; ++step) {
    one.simulation.step();
    two.simulation.step();
    EXPECT_EQ(one.simulation.collision_report().contacts, two.simulation.collision_report().contacts) << step;
    pairs = std::max(pairs, one.simulation.collision_report().element_pairs);
  }
  EXPECT_GT(pairs, 2 * 1024) << "several chunks";
  EXPECT_GT(one.simulation.collision_report().contacts, 1000);
  EXPECT_EQ(one.simulation.objects[0].system.state.position, two.simulation.objects[0].system.state.position);
  const auto a = one.simulation.collisions->contacts(), b = two.simulation.collisions->contacts();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t c = 0; c < a.size(); ++c) {
    EXPECT_EQ(a[c].point[0], b[c].point[0]);
    EXPECT_EQ(a[c].normal, b[c].normal);
  }
  set_yield_cores_to_other_processes(true);
}

TEST(CollisionScene, BadInputIsRefusedNamingTheComponent) {
  std::string negative = point_over_floor(0.4);
  negative.replace(negative.find("<PointCollisionModel contactStiffness=\"20\"/>"), std::string("<PointCollisionModel contactStiffness=\"20\"/>").size(),
                   "<PointCollisionModel contactDistance=\"-1\"/>");
  EXPECT_NE(scene_error(negative).find("contactDistance, contactStiffness and contactFriction must be ≥ 0"), std::string::npos) << scene_error(negative);
  std::string outside = point_over_floor(0.4);
  outside.replace(outside.find("triangles=\"0 2 1\""), std::string("triangles=\"0 2 1\"").size(), "triangles=\"0 2 7\"");
  EXPECT_NE(scene_error(outside).find("names point 7, outside the 3 points"), std::string::npos) << scene_error(outside);
}

}  // namespace
}  // namespace fastcorot
