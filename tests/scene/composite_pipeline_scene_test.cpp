// SOFA's CompositeCollisionPipeline in scenes: each SubCollisionPipeline detects and responds with
// its own models, intersection method and contact manager, so two balls over two floors rest at the
// closed-form heights of their own sub-pipelines' contact distances; what SOFA warns of (a model in no
// sub-pipeline, a sub-pipeline missing a link) is warned; a second pipeline beside it is refused.
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;

// Ball i: a point of mass 0.5 at x = 4 i, 0.4 above floor i (a still triangle in y = 0 around it).
std::string ball_and_floor(int i) {
  const std::string n = std::to_string(i), x = std::to_string(4 * i);
  return "<Node name=\"ball" + n + "\"><EulerImplicitSolver rayleighMass=\"2\" rayleighStiffness=\"0\"/><CGLinearSolver iterations=\"100\" "
         "tolerance=\"1e-30\" threshold=\"1e-30\"/><MechanicalObject position=\"" + x + " 0.4 0\"/><UniformMass totalMass=\"0.5\"/>"
         "<PointCollisionModel name=\"point\" contactStiffness=\"20\"/></Node>"
         "<Node name=\"floor" + n + "\"><MeshTopology position=\"" + std::to_string(4 * i - 1) + " 0 -1  " + std::to_string(4 * i + 1) +
         " 0 -1  " + x + " 0 2\" triangles=\"0 2 1\"/><MechanicalObject/>"
         "<TriangleCollisionModel name=\"triangle\" simulated=\"0\" moving=\"0\" contactStiffness=\"20\"/></Node>";
}

// Sub-pipeline i for ball i and floor i, keeping contact distance d.
std::string sub_pipeline(int i, const std::string& d, const std::string& omit = "") {
  const std::string n = std::to_string(i);
  std::string text = "<BruteForceBroadPhase name=\"broad" + n + "\"/><BVHNarrowPhase name=\"narrow" + n + "\"/>"
                     "<MinProximityIntersection name=\"method" + n + "\" alarmDistance=\"0.6\" contactDistance=\"" + d + "\"/>"
                     "<CollisionResponse name=\"response" + n + "\" response=\"PenalityContactForceField\"/><SubCollisionPipeline name=\"sub" + n + "\"";
  for (const auto& [attribute, value] :
       {std::pair<std::string, std::string>{"collisionModels", "@ball" + n + "/point @/floor" + n + "/triangle"}, {"broadPhaseDetection", "@broad" + n},
        {"narrowPhaseDetection", "@narrow" + n}, {"intersectionMethod", "@method" + n}, {"contactManager", "@response" + n}}) {
    if (attribute != omit) text += " " + attribute + "=\"" + value + "\"";
  }
  return text + "/>";
}

const std::string kRoot = "dt=\"0.01\" gravity=\"0 -9.81 0\"";

bool warned(const LoadedScene& scene, const std::string& text) {
  for (const auto& line : scene.warnings) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(CompositePipelineScene, EachSubPipelineKeepsItsOwnContactDistance) {
  LoadedScene scene = build_scene_text(ball_and_floor(0) + ball_and_floor(1) + sub_pipeline(0, "0.2") + sub_pipeline(1, "0.3") +
                                           "<CompositeCollisionPipeline subCollisionPipelines=\"@sub0 @sub1\"/>",
                                       kRoot);
  ASSERT_TRUE(scene.simulation.collisions);
  for (int step = 0; step < 3000; ++step) scene.simulation.step();
  ASSERT_EQ(scene.simulation.objects.size(), 2u);
  // At rest: k pen = m g with k = ks² / d, pen = d − y.
  for (const auto& [object, d] : {std::pair{std::size_t{0}, 0.2}, std::pair{std::size_t{1}, 0.3}}) {
    const double k = 20.0 * 20.0 / d;
    EXPECT_NEAR(scene.simulation.objects[object].system.state.position[0].y(), d - 0.5 * 9.81 / k, 1e-9) << "ball " << object;
  }
  EXPECT_EQ(scene.simulation.collision_report().contacts, 2);
}

TEST(CompositePipelineScene, WhatSofaWarnsOfIsWarned) {
  // Ball 1's sub-pipeline has no contact manager: it does nothing, so ball 1 falls through its floor;
  // a model listed by no sub-pipeline is said.
  LoadedScene scene = build_scene_text(ball_and_floor(0) + ball_and_floor(1) +
                                           "<Node name=\"loose\"><MechanicalObject position=\"9 9 9\"/><PointCollisionModel simulated=\"0\"/></Node>" +
                                           sub_pipeline(0, "0.2") + sub_pipeline(1, "0.3", "contactManager") +
                                           "<CompositeCollisionPipeline subCollisionPipelines=\"@sub0 @sub1\"/>",
                                       kRoot);
  EXPECT_TRUE(warned(scene, "no contactManager: this sub-pipeline does nothing"));
  EXPECT_TRUE(warned(scene, "is in no SubCollisionPipeline"));
  ASSERT_TRUE(scene.simulation.collisions);
  for (int step = 0; step < 300; ++step) scene.simulation.step();
  EXPECT_GT(scene.simulation.objects[0].system.state.position[0].y(), 0);
  EXPECT_LT(scene.simulation.objects[1].system.state.position[0].y(), -1);
  // Nothing linked: warned, no contacts.
  LoadedScene empty = build_scene_text(ball_and_floor(0) + "<CompositeCollisionPipeline/>", kRoot);
  EXPECT_FALSE(empty.simulation.collisions);
  EXPECT_TRUE(warned(empty, "no SubCollisionPipeline"));
  // Beside a CollisionPipeline: not simulated, each collision component says why.
  LoadedScene two = build_scene_text(ball_and_floor(0) + sub_pipeline(0, "0.2") + "<CollisionPipeline/>" +
                                         "<CompositeCollisionPipeline subCollisionPipelines=\"@sub0\"/>",
                                     kRoot);
  EXPECT_FALSE(two.simulation.collisions);
  EXPECT_TRUE(warned(two, "one pipeline, please"));
}

TEST(CompositePipelineScene, ALinkToSomethingElseIsAnError) {
  EXPECT_NE(testing::scene_error(ball_and_floor(0) + sub_pipeline(0, "0.2") + "<CompositeCollisionPipeline subCollisionPipelines=\"@broad0\"/>")
                .find("not a SubCollisionPipeline"),
            std::string::npos);
}

}  // namespace
}  // namespace fastcorot
