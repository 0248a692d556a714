// TopologicalChangeProcessor scenes: a beam cut in two (the free half falls as a rigid body under
// gravity, the fixed half keeps hanging), removals and additions read from a file of timed changes,
// SOFA's timing rules (timeToRemove fires at the first step starting after it; a file's T= block at
// the first step starting at or after it; interval repeats), a run resumed from a checkpoint after
// a cut equal to the uninterrupted run, and clear errors for what is not supported or wrong.
#include "fastcorot/core/error.h"
#include "fastcorot/io/checkpoint.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <unistd.h>

namespace fastcorot {
namespace {

namespace fs = std::filesystem;

LoadedScene build(const std::string& body) {
  return build_scene(parse_scene_text("<Node name=\"root\" dt=\"0.01\" gravity=\"0 -9.81 0\">\n" + body + "\n</Node>", "test.scn"));
}

std::string load_error(const std::string& body) {
  try {
    build(body);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

// A 10×3×3-point beam along x over [0, 9] × [0, 1] × [0, 1], fixed at x = 0, with `processor`.
std::string beam(const std::string& processor) {
  return R"(
  <Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1"/>
    <CGLinearSolver iterations="200" tolerance="1e-14" threshold="1e-30"/>
    <RegularGridTopology name="grid" n="10 3 3" min="0 0 0" max="9 1 1"/>
    <MechanicalObject name="state"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
    <DiagonalMass massDensity="1"/>
    <FastTetrahedralCorotationalForceField youngModulus="100000" poissonRatio="0.3" method="large"/>
    <BoxROI name="fixed" box="-0.1 -0.1 -0.1 0.1 1.1 1.1"/>
    <FixedProjectiveConstraint indices="@fixed.indices"/>
    <BoxROI name="cut" box="4.1 -0.1 -0.1 4.9 1.1 1.1" strict="false"/>
    )" + processor + R"(
  </Node>)";
}

Vec3<double> mass_weighted_mean(const MechanicalSystem<double>& system, const std::vector<Vec3<double>>& values, double min_x) {
  Vec3<double> sum = Vec3<double>::Zero();
  double mass = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (system.state.rest_position[i].x() < min_x) continue;
    const double m = system.mass.vertex_masses()[i];
    sum += m * values[i];
    mass += m;
  }
  return sum / mass;
}

TEST(TopologicalChangeProcessor, BeamCutInTwoFreeHalfFallsFixedHalfHangs) {
  LoadedScene scene = build(beam(R"(<TopologicalChangeProcessor useDataInputs="true" timeToRemove="0.1" tetrahedraToRemove="@cut.tetrahedronIndices"/>)"));
  Simulation<double>& sim = scene.simulation;
  SimulatedObject<double>& beam_object = sim.objects.at(0);
  const Index all = beam_object.mesh->num_tetrahedra();
  ASSERT_EQ(all, 9 * 2 * 2 * 6);
  // timeToRemove = 0.1: steps start at t = 0, 0.01, ...; the cut comes with the step starting at
  // t = 0.11 (the first after 0.1), i.e. step 12.
  for (int s = 0; s < 11; ++s) sim.step();
  EXPECT_EQ(beam_object.mesh->num_tetrahedra(), all);
  sim.step();
  EXPECT_EQ(beam_object.mesh->num_tetrahedra(), all - 24);  // the layer of 4 cells between x = 4 and 5
  const MechanicalSystem<double>& system = beam_object.system;
  const Vec3<double> v_cut = mass_weighted_mean(system, system.state.velocity, 5.0);
  const double fixed_half_sag = [&] {
    double sag = 0;
    for (std::size_t i = 0; i < system.state.position.size(); ++i) {
      if (system.state.rest_position[i].x() <= 4.0) sag = std::max(sag, (system.state.position[i] - system.state.rest_position[i]).norm());
    }
    return sag;
  }();
  const int after = 50;
  for (int s = 0; s < after; ++s) sim.step();
  // The free half (x >= 5) is a free body: internal forces cancel, so its mass-weighted velocity
  // gains g dt per step (backward Euler integrates a constant force exactly).
  const Vec3<double> v_end = mass_weighted_mean(system, system.state.velocity, 5.0);
  EXPECT_NEAR(v_end.y() - v_cut.y(), -9.81 * 0.01 * after, 1e-6);
  EXPECT_NEAR(v_end.x() - v_cut.x(), 0.0, 1e-6);
  const Vec3<double> drop = mass_weighted_mean(system, system.state.position, 5.0) - mass_weighted_mean(system, system.state.rest_position, 5.0);
  EXPECT_LT(drop.y(), -0.5 * 9.81 * 0.5 * 0.5 * 0.9);  // fell more than 1 m in 0.5 s
  // The fixed half keeps hanging: it moves no more than it sagged before the cut, give or take its
  // rebound (it lost the weight of the other half).
  for (std::size_t i = 0; i < system.state.position.size(); ++i) {
    if (system.state.rest_position[i].x() > 4.0) continue;
    EXPECT_LT((system.state.position[i] - system.state.rest_position[i]).norm(), 2 * fixed_half_sag + 1e-3) << "vertex " << i;
  }
  EXPECT_GT(fixed_half_sag, 0.0);
}

TEST(TopologicalChangeProcessor, ContactsOnTheChangingBodyAreNotSimulatedYetAndSaySo) {
  // The beam's points as a collision model against a still floor: the pipeline is left out, warned.
  const std::string collision = R"(<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/><MinProximityIntersection/><CollisionResponse response="PenalityContactForceField"/>
    <Node name="floor"><MeshTopology position="-5 -2 -5  15 -2 -5  5 -2 15" triangles="0 2 1"/><MechanicalObject/>
    <TriangleCollisionModel simulated="0" moving="0"/></Node>)";
  std::string text = beam(R"(<TopologicalChangeProcessor useDataInputs="true" timeToRemove="0.1" tetrahedraToRemove="@cut.tetrahedronIndices"/>
    <PointCollisionModel/>)");
  LoadedScene scene = build(collision + text);
  EXPECT_FALSE(scene.simulation.collisions);
  bool said = false;
  for (const auto& line : scene.warnings) said = said || line.find("whose topology a TopologicalChangeProcessor changes") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(TopologicalChangeProcessor, FileOfTimedRemovalsAndAdditions) {
  const fs::path dir = fs::temp_directory_path() / ("fastcorot_topology_change_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "changes.txt";
  // Tetrahedra 0 and 1 of the grid go at t = 0.02, tetrahedron 5 at 0.04, and the first two come
  // back at 0.05 (grid cell 0's first two tetrahedra, read from the split in regular_grid.cpp).
  std::ofstream(file) << "T= 0.02\n  REMOVE= 2\n0 1\nT= 0.04\n  REMOVE= 1\n5\n";
  LoadedScene scene = build(beam("<TopologicalChangeProcessor filename=\"" + file.string() + "\"/>"));
  Simulation<double>& sim = scene.simulation;
  const TetMesh& mesh = *sim.objects.at(0).mesh;
  const Index all = mesh.num_tetrahedra();
  const Tetrahedron first = mesh.tetrahedron(0);
  sim.step();  // t = 0
  sim.step();  // t = 0.01
  EXPECT_EQ(mesh.num_tetrahedra(), all);
  sim.step();  // t = 0.02: T= 0.02 is due (at or after)
  EXPECT_EQ(mesh.num_tetrahedra(), all - 2);
  sim.step();
  sim.step();  // t = 0.04
  EXPECT_EQ(mesh.num_tetrahedra(), all - 3);
  for (int s = 0; s < 5; ++s) sim.step();
  EXPECT_EQ(mesh.num_tetrahedra(), all - 3);

  // Additions, with shift: T= 0.05 read at time + 0.03, so due at t = 0.02.
  std::ofstream(file) << "T= 0.04\nREMOVE= 1 0\nT= 0.05\nADD= Tetrahedra 1\n" << first[0] << " " << first[1] << " "
                      << first[2] << " " << first[3] << "\n";
  LoadedScene shifted = build(beam("<TopologicalChangeProcessor filename=\"" + file.string() + "\" shift=\"0.03\"/>"));
  const TetMesh& m2 = *shifted.simulation.objects.at(0).mesh;
  shifted.simulation.step();  // t = 0
  shifted.simulation.step();  // t = 0.01: 0.04 - 0.03 = 0.01 due
  EXPECT_EQ(m2.num_tetrahedra(), all - 1);
  shifted.simulation.step();  // t = 0.02: the tetrahedron comes back, at the end
  EXPECT_EQ(m2.num_tetrahedra(), all);
  EXPECT_EQ(m2.tetrahedron(all - 1), first);
  fs::remove_all(dir);
}

TEST(TopologicalChangeProcessor, IntervalRepeatsTheRemoval) {
  LoadedScene scene = build(beam(R"(<TopologicalChangeProcessor useDataInputs="true" timeToRemove="0" interval="0.03" tetrahedraToRemove="0 1"/>)"));
  Simulation<double>& sim = scene.simulation;
  const TetMesh& mesh = *sim.objects.at(0).mesh;
  const Index all = mesh.num_tetrahedra();
  sim.step();  // t = 0: not after 0
  EXPECT_EQ(mesh.num_tetrahedra(), all);
  sim.step();  // t = 0.01 > 0: removes, next after 0.03
  EXPECT_EQ(mesh.num_tetrahedra(), all - 2);
  sim.step();
  sim.step();  // t = 0.03: not after 0.03
  EXPECT_EQ(mesh.num_tetrahedra(), all - 2);
  sim.step();  // t = 0.04
  EXPECT_EQ(mesh.num_tetrahedra(), all - 4);
}

TEST(TopologicalChangeProcessor, TimesAreComparedWithSofasAccumulatedClock) {
  // SOFA's time is dt added once per step: after 30 steps of 0.01 it is 0.3000000000000001 (after
  // 10, 0.09999999999999999). So timeToRemove = 0.3 fires with step 31, which starts at that
  // time, while timeToRemove = 0.1 waits for step 12 (step 11 starts just below 0.1).
  double clock = 0;
  for (int s = 0; s < 30; ++s) clock += 0.01;
  ASSERT_GT(clock, 0.3);
  for (const auto& [time, step] : {std::pair{"0.3", 31}, std::pair{"0.1", 12}}) {
    LoadedScene scene = build(beam(std::string("<TopologicalChangeProcessor useDataInputs=\"true\" timeToRemove=\"") + time +
                                   "\" tetrahedraToRemove=\"0\"/>"));
    const TetMesh& mesh = *scene.simulation.objects.at(0).mesh;
    const Index all = mesh.num_tetrahedra();
    for (int s = 1; s < step; ++s) scene.simulation.step();
    EXPECT_EQ(mesh.num_tetrahedra(), all) << "timeToRemove " << time;
    scene.simulation.step();
    EXPECT_EQ(mesh.num_tetrahedra(), all - 1) << "timeToRemove " << time;
  }
}

TEST(TopologicalChangeProcessor, ResumingAfterACutEqualsTheUninterruptedRun) {
  const std::string scene_text = beam(R"(<TopologicalChangeProcessor useDataInputs="true" timeToRemove="0.05" tetrahedraToRemove="@cut.tetrahedronIndices"/>)");
  LoadedScene straight = build(scene_text);
  const fs::path dir = fs::temp_directory_path() / ("fastcorot_topology_resume_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path checkpoint = dir / "cut.ckpt";
  for (int s = 0; s < 10; ++s) straight.simulation.step();
  write_checkpoint(checkpoint, straight.simulation, "cut.scn");
  for (int s = 0; s < 10; ++s) straight.simulation.step();

  LoadedScene resumed = build(scene_text);
  restore_checkpoint(checkpoint, resumed.simulation);
  EXPECT_EQ(resumed.simulation.objects[0].mesh->num_tetrahedra(), straight.simulation.objects[0].mesh->num_tetrahedra());
  for (int s = 0; s < 10; ++s) resumed.simulation.step();
  const auto& a = straight.simulation.objects[0].system.state;
  const auto& b = resumed.simulation.objects[0].system.state;
  ASSERT_EQ(a.position.size(), b.position.size());
  for (std::size_t i = 0; i < a.position.size(); ++i) {
    ASSERT_EQ(a.position[i], b.position[i]) << "vertex " << i;
    ASSERT_EQ(a.velocity[i], b.velocity[i]) << "vertex " << i;
  }
  fs::remove_all(dir);
}

TEST(TopologicalChangeProcessor, ErrorsNameWhatIsWrong) {
  const auto expect_load_error = [](const std::string& processor, const std::string& needle) {
    const std::string message = load_error(beam(processor));
    EXPECT_NE(message.find(needle), std::string::npos) << "message: \"" << message << "\" lacks \"" << needle << "\"";
    EXPECT_NE(message.find("TopologicalChangeProcessor"), std::string::npos) << message;
  };
  expect_load_error(R"(<TopologicalChangeProcessor useDataInputs="true" pointsToRemove="3"/>)", "pointsToRemove");
  expect_load_error(R"(<TopologicalChangeProcessor/>)", "filename");
  expect_load_error(R"(<TopologicalChangeProcessor filename="/nonexistent/changes.txt"/>)", "/nonexistent/changes.txt");
  expect_load_error(R"(<TopologicalChangeProcessor useDataInputs="true" interval="-1" tetrahedraToRemove="0"/>)", "interval");
  const fs::path dir = fs::temp_directory_path() / ("fastcorot_topology_error_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "bad.txt";
  std::ofstream(file) << "T= 0.1\nREMOVE= 1\n0\nINCISE= 2\n";
  expect_load_error("<TopologicalChangeProcessor filename=\"" + file.string() + "\"/>", "bad.txt:4");
  std::ofstream(file) << "T= 0.1\nADD= Triangles 1\n0 1 2\n";
  expect_load_error("<TopologicalChangeProcessor filename=\"" + file.string() + "\"/>", "only tetrahedra");
  std::ofstream(file) << "T= 0.1\nREMOVE= 3\n0 1\n";
  expect_load_error("<TopologicalChangeProcessor filename=\"" + file.string() + "\"/>", "ends where");

  // An index beyond the mesh at the time of the change stops the step with the time and the index.
  LoadedScene scene = build(beam(R"(<TopologicalChangeProcessor useDataInputs="true" timeToRemove="0" tetrahedraToRemove="500"/>)"));
  scene.simulation.step();
  try {
    scene.simulation.step();
    ADD_FAILURE() << "an out-of-range removal went through";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("at step 2 (t = 0.01)"), std::string::npos) << message;
    EXPECT_NE(message.find("500"), std::string::npos) << message;
    EXPECT_NE(message.find("TopologicalChangeProcessor"), std::string::npos) << message;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fastcorot
