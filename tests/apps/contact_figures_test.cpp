// What `fastcorot run` and `bench` say about contacts, on SOFA's soft cube falling on a floor
// (tests/data/sofa_reference/cube_on_floor.scn): each dumped step's contacts, their count as SOFA
// counts them (cube_on_floor_trajectory.json), their points and normals against the closed form of
// a point over the plane y = -0.3 (the floor's triangles come first, the cube's points second, the
// normal from the floor up), and the --json summaries beside them.
#include "support/command.h"
#include "support/sofa_reference.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace fastcorot {
namespace {

using nlohmann::json;
using testing::json_points;

// The program's standard output alone (its warnings on standard error are left out), and its status.
testing::CommandResult run_stdout(const std::string& arguments) {
  return testing::shell("{ " + std::string(FASTCOROT_EXECUTABLE) + " " + arguments + " 2>/dev/null; }");
}

const std::string kScene = testing::sofa_reference_path("cube_on_floor.scn");
constexpr double kFloor = -0.3, kAlarmDistance = 0.3, kContactDistance = 0.1;  // the scene's

TEST(ContactFigures, DumpHoldsEachStepsContactsAsSofaCountsThemWithTheSummary) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / "contacts_dump";
  std::filesystem::create_directories(dir);
  const auto file = dir / "state.json";
  const auto result = run_stdout("run " + kScene + " --steps 50 --quiet --json --dump-state " + file.string() +
                                 " --dump-steps 0,9,10,29,30,49,50");
  ASSERT_EQ(result.status, 0) << result.output;
  const json summary = json::parse(result.output);
  std::ifstream in(file);
  const json dump = json::parse(in);
  ASSERT_TRUE(dump.contains("contacts"));
  const json& contacts = dump["contacts"];
  // No detection before the first step.
  EXPECT_EQ(contacts["0"]["count"], 0);
  const json sofa = testing::load_sofa_trajectory("cube_on_floor_trajectory.json");
  for (const long step : {10L, 30L, 50L}) {
    const std::string key = std::to_string(step);
    const json& entry = contacts[key];
    const int count = entry["count"].get<int>();
    EXPECT_EQ(count, sofa["steps"][key]["contacts"].get<int>()) << "step " << step;
    ASSERT_EQ(entry["points"].size(), static_cast<std::size_t>(count));
    ASSERT_EQ(entry["normals"].size(), static_cast<std::size_t>(count));
    // Detection runs at the step's start: the cube's points as the previous step left them.
    const auto before = json_points(dump["steps"][std::to_string(step - 1)]["root/cube"]);
    for (int k = 0; k < count; ++k) {
      const auto points = json_points(entry["points"][static_cast<std::size_t>(k)]);
      ASSERT_EQ(points.size(), 2u);
      const auto normal = json_points(json::array({entry["normals"][static_cast<std::size_t>(k)]}))[0];
      const std::string where = "step " + key + " contact " + std::to_string(k);
      EXPECT_NEAR(normal.norm(), 1.0, 1e-12) << where;
      EXPECT_TRUE(std::find(before.begin(), before.end(), points[1]) != before.end()) << where << ": not a cube point";
      // The closest point of the plane and the normal up from it (every point is over the floor).
      EXPECT_NEAR(points[0].y(), kFloor, 1e-12) << where;
      EXPECT_NEAR(points[0].x(), points[1].x(), 1e-12) << where;
      EXPECT_NEAR(points[0].z(), points[1].z(), 1e-12) << where;
      EXPECT_NEAR(normal.y(), 1.0, 1e-12) << where;
      const double height = points[1].y() - kFloor;
      EXPECT_GT(height, 0) << where;
      EXPECT_LT(height, kAlarmDistance) << where;
      // Resting by step 50: each point sits just inside the contact distance (d − its load / k).
      if (step == 50) EXPECT_LT(height, kContactDistance) << where;
    }
  }
  // The summary's figures beside the dump's counts.
  ASSERT_TRUE(summary.contains("contacts")) << result.output;
  const json& figures = summary["contacts"];
  EXPECT_EQ(figures["last_step"], contacts["50"]["count"]);
  EXPECT_EQ(figures["max_per_step"], 16);  // the cube's 16 bottom points
  EXPECT_GT(figures["mean_per_step"].get<double>(), 0.0);
  EXPECT_LT(figures["mean_per_step"].get<double>(), 16.0);  // none over the first steps
  EXPECT_EQ(figures["model_pairs_per_step"].get<double>(), 1.0);  // the cube's points, the floor's triangles
  EXPECT_GT(figures["element_pairs_per_step"].get<double>(), 0.0);
  EXPECT_EQ(figures["degenerate_elements"], 0);
  EXPECT_EQ(figures["crossed"], 0) << "the cube rests on the floor, never through it";
  EXPECT_GE(figures["detection_share"].get<double>(), 0.0);
  EXPECT_LE(figures["detection_share"].get<double>(), 1.0);
  EXPECT_EQ(summary["steps"], 50);
  EXPECT_FALSE(summary.contains("constraints"));  // no FreeMotionAnimationLoop
}

// A point found over the floor moving down too fast for its contact to stop it within the step: one
// warning, at the first step it happens, naming the models; the summary counts them.
TEST(ContactFigures, AContactThatEndsAStepCrossedIsWarnedOnce) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / "contacts_crossed";
  std::filesystem::create_directories(dir);
  const auto scene = dir / "fast_point.scn";
  std::ofstream(scene) << R"(<Node name="root" dt="0.01" gravity="0 -9.81 0">
  <CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>
  <MinProximityIntersection alarmDistance="0.5" contactDistance="0.2"/><CollisionResponse response="PenalityContactForceField"/>
  <Node name="ball"><EulerImplicitSolver/><CGLinearSolver iterations="100" tolerance="1e-30" threshold="1e-30"/>
    <MechanicalObject position="0.1 0.4 0.2" velocity="0 -100 0"/><UniformMass totalMass="0.5"/><PointCollisionModel/></Node>
  <Node name="floor"><MeshTopology position="-1 0 -1  1 0 -1  0 0 2" triangles="0 2 1"/><MechanicalObject/>
    <TriangleCollisionModel simulated="0" moving="0"/></Node>
</Node>)";
  const auto result = testing::shell(std::string(FASTCOROT_EXECUTABLE) + " run " + scene.string() + " --steps 3 --json 2>&1");
  ASSERT_EQ(result.status, 0) << result.output;
  const std::string warning = "warning: step 1: 1 contact(s) ended the step crossed";
  const auto first = result.output.find(warning);
  EXPECT_NE(first, std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("ended the step crossed", first + warning.size()), std::string::npos) << "once per run";
  EXPECT_NE(result.output.find("fast_point.scn:7: TriangleCollisionModel"), std::string::npos) << result.output;
}

// A run resumed from a checkpoint dumps the contacts of the steps it runs as the whole run does; the
// resume step's own detection ran in the first run, so its entry is left out rather than made up.
// The resumed run builds its trees at the resumed positions, and the contacts come in the order of
// the traversal of those trees (SOFA's order): the same contacts, maybe in another order.
TEST(ContactFigures, AResumedRunDumpsTheSameContacts) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / "contacts_resume";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string whole = (dir / "whole.json").string(), resumed = (dir / "resumed.json").string(),
                    checkpoint = (dir / "run.ckpt").string();
  ASSERT_EQ(run_stdout("run " + kScene + " --steps 20 --quiet --dump-steps 20 --dump-state " + whole).status, 0);
  ASSERT_EQ(run_stdout("run " + kScene + " --steps 15 --quiet --checkpoint-every 15 --checkpoint " + checkpoint).status, 0);
  const auto result = run_stdout("run " + kScene + " --steps 20 --quiet --resume " + checkpoint +
                                 " --dump-steps 15,20 --dump-state " + resumed);
  ASSERT_EQ(result.status, 0) << result.output;
  std::ifstream a(whole), b(resumed);
  const json first = json::parse(a), second = json::parse(b);
  EXPECT_TRUE(second["steps"].contains("15"));
  EXPECT_FALSE(second["contacts"].contains("15"));
  ASSERT_GT(first["contacts"]["20"]["count"].get<int>(), 0);
  const auto as_set = [](const json& contacts) {
    std::vector<std::string> items;
    for (std::size_t c = 0; c < contacts["points"].size(); ++c) items.push_back(contacts["points"][c].dump() + contacts["normals"][c].dump());
    std::sort(items.begin(), items.end());
    return items;
  };
  EXPECT_EQ(as_set(second["contacts"]["20"]), as_set(first["contacts"]["20"]));
  EXPECT_EQ(second["steps"]["20"], first["steps"]["20"]) << "the same positions";
}

TEST(ContactFigures, SceneWithoutCollisionHasNoContactsEntry) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / "contacts_none";
  std::filesystem::create_directories(dir);
  const auto file = dir / "state.json";
  const auto result = run_stdout("run --steps 1 --quiet --json --dump-state " + file.string() + " --dump-steps 1");
  ASSERT_EQ(result.status, 0) << result.output;
  const json summary = json::parse(result.output);
  EXPECT_FALSE(summary.contains("contacts"));
  EXPECT_EQ(summary["steps"], 1);
  EXPECT_EQ(summary["objects"], 1);
  std::ifstream in(file);
  EXPECT_FALSE(json::parse(in).contains("contacts"));
}

TEST(ContactFigures, BenchJsonCarriesTheContactFigures) {
  // Contacts start by step 10 (SOFA: 12 at step 10): ten untimed steps, then five timed.
  const auto result = run_stdout("bench " + kScene + " --steps 5 --warmup 10 --threads 1 --json");
  ASSERT_EQ(result.status, 0) << result.output;
  const json figures = json::parse(result.output);
  ASSERT_TRUE(figures.contains("contacts")) << result.output;
  const json& contacts = figures["contacts"];
  for (const char* key : {"last_step", "max_per_step", "mean_per_step", "model_pairs_per_step", "element_pairs_per_step",
                          "degenerate_elements", "detection_seconds", "detection_share"}) {
    EXPECT_TRUE(contacts.contains(key)) << key;
  }
  EXPECT_GT(contacts["last_step"].get<int>(), 0);
  EXPECT_LE(contacts["last_step"].get<int>(), contacts["max_per_step"].get<int>());
  EXPECT_LE(contacts["mean_per_step"].get<double>(), contacts["max_per_step"].get<double>());
  EXPECT_GE(figures["ms_per_step"]["collision_detection"].get<double>(), 0.0);
  EXPECT_NEAR(figures["ms_per_step"]["collision_detection"].get<double>(),
              1e3 * contacts["detection_seconds"].get<double>() / 5, 1e-9);
}

}  // namespace
}  // namespace fastcorot
