// StickContactConstraint under FreeMotionAnimationLoop through the scene builder, against closed
// forms: a point falling on a still floor is held where it was found (the bilateral rows keep the
// offset found, so it neither rests at the contact distance nor slides along a tilted gravity);
// two masses meeting head-on stick together with their momentum kept and their offset frozen at
// the one found; three rows per contact; kept alive while a step finds nothing (its points
// following the body); what SOFA has no rule for said.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/constraint/stick_contact_constraint.h"
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;

const std::string kHeader =
    "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"200\" tolerance=\"1e-15\"/>"
    "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>";

std::string body(const std::string& name, const std::string& position, const std::string& velocity, const std::string& mass,
                 const std::string& model = "<PointCollisionModel/>") {
  return "<Node name=\"" + name + "\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
         "<MechanicalObject position=\"" + position + "\" velocity=\"" + velocity + "\"/><UniformMass totalMass=\"" + mass + "\"/>" +
         model + "<LinearSolverConstraintCorrection/></Node>";
}

const std::string kFloor =
    "<Node name=\"floor\"><MeshTopology position=\"-10 0 -10  10 0 -10  0 0 20\" triangles=\"0 2 1\"/><MechanicalObject/>"
    "<TriangleCollisionModel simulated=\"0\" moving=\"0\"/></Node>";

const StickContactConstraint<double>* stick_constraint(const LoadedScene& scene) {
  const auto* loop = dynamic_cast<const FreeMotionAnimationLoop<double>*>(scene.simulation.constraints.get());
  if (!loop) return nullptr;
  for (const auto& c : loop->constraints) {
    if (const auto* s = dynamic_cast<const StickContactConstraint<double>*>(c.get())) return s;
  }
  return nullptr;
}

TEST(StickContactConstraintScene, APointIsHeldWhereItWasFound) {
  // Falling from 0.6 under a gravity tilted along x: found within the alarm distance (0.5), then
  // held at that point (a FrictionContactConstraint would let it slide down to the contact
  // distance 0.2 and along x).
  LoadedScene scene = build_scene_text(kHeader + "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/>"
                                                 "<CollisionResponse response=\"StickContactConstraint\"/>" +
                                           body("ball", "0.1 0.6 0.2", "0 0 0", "0.5") + kFloor,
                                       "dt=\"0.01\" gravity=\"3 -9.81 0\"");
  ASSERT_TRUE(scene.simulation.collisions);
  const auto& x = scene.simulation.objects[0].system.state.position;
  Vec3<double> found = Vec3<double>::Zero();
  int found_at = -1;
  for (int step = 0; step < 400; ++step) {
    const Vec3<double> before = x[0];
    scene.simulation.step();
    if (found_at < 0 && scene.simulation.collision_report().contacts > 0) {
      found_at = step;
      found = before;  // where the contact was found: the step's start
    }
    if (found_at >= 0) {
      EXPECT_LT((x[0] - found).norm(), 1e-12) << "step " << step;
      EXPECT_EQ(scene.simulation.collision_report().contacts, 1) << "step " << step;
    }
  }
  ASSERT_GE(found_at, 0);
  EXPECT_GT(found.y(), 0.2) << "held above the contact distance, where it was found";
  EXPECT_LT(found.y(), 0.5);
  const auto* constraint = stick_constraint(scene);
  ASSERT_NE(constraint, nullptr);
  ASSERT_EQ(constraint->contacts().size(), 1u);
  EXPECT_EQ(constraint->rows(), 3);
}

TEST(StickContactConstraintScene, TwoMassesMeetingHeadOnStickWithTheirMomentum) {
  LoadedScene scene = build_scene_text(kHeader + "<MinProximityIntersection alarmDistance=\"0.2\" contactDistance=\"0.05\"/>"
                                                 "<CollisionResponse response=\"StickContactConstraint\"/>" +
                                           body("a", "0 0 0", "1 0 0", "2") + body("b", "0.5 0 0", "-0.5 0 0", "1"),
                                       "dt=\"0.01\" gravity=\"0 0 0\"");
  auto& simulation = scene.simulation;
  ASSERT_EQ(simulation.objects.size(), 2u);
  const auto position = [&](std::size_t o) { return simulation.objects[o].system.state.position[0]; };
  const auto velocity = [&](std::size_t o) { return simulation.objects[o].system.state.velocity[0]; };
  const Vec3<double> momentum = 2 * velocity(0) + velocity(1);
  double offset = -1;
  for (int step = 0; step < 100; ++step) {
    const double gap = position(1).x() - position(0).x();
    simulation.step();
    EXPECT_LT((2 * velocity(0) + velocity(1) - momentum).norm(), 1e-12) << "step " << step;
    if (offset < 0 && simulation.collision_report().contacts > 0) offset = gap;
    if (offset >= 0) EXPECT_NEAR(position(1).x() - position(0).x(), offset, 1e-12) << "step " << step;
  }
  ASSERT_GT(offset, 0.05) << "stuck where found, before the contact distance";
  EXPECT_NEAR(velocity(0).x(), momentum.x() / 3, 1e-10);
  EXPECT_NEAR(velocity(1).x(), momentum.x() / 3, 1e-10);
}

TEST(StickContactConstraintScene, KeptAliveWhileNothingIsFound) {
  // Found 0.3 above the floor (within the alarm distance) with gravity pulling it up: stuck there.
  // Then its state is moved far above, out of the alarm distance: the next step finds nothing, and
  // the rows kept from before pull it back to where it stuck.
  LoadedScene scene = build_scene_text(kHeader + "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/>"
                                                 "<CollisionResponse response=\"StickContactConstraint\"/>" +
                                           body("ball", "0.1 0.3 0.2", "0 0 0", "0.5") + kFloor,
                                       "dt=\"0.01\" gravity=\"0 5 0\"");
  auto& simulation = scene.simulation;
  auto& x = simulation.objects[0].system.state.position;
  for (int step = 0; step < 10; ++step) {
    simulation.step();
    ASSERT_EQ(simulation.collision_report().contacts, 1);
    EXPECT_LT((x[0] - Vec3<double>(0.1, 0.3, 0.2)).norm(), 1e-12) << "step " << step;
  }
  x[0] = Vec3<double>(0.1, 5, 0.2);
  simulation.step();
  EXPECT_EQ(simulation.collision_report().contacts, 1) << "the stuck contact, kept alive";
  EXPECT_LT((x[0] - Vec3<double>(0.1, 0.3, 0.2)).norm(), 1e-12) << "pulled back to where it stuck";
}

TEST(StickContactConstraintScene, MixesWithFrictionlessContactsByRule) {
  // Two points far apart over the floor, gravity tilted along x: a rule sticks b, a keeps the
  // manager's frictionless contact, so b stays where it was found and a slides down along x, resting
  // at the contact distance.
  LoadedScene scene = build_scene_text(
      kHeader + "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/>"
                "<RuleBasedContactManager response=\"FrictionContactConstraint\" responseParams=\"mu=0\" rules=\"b * StickContactConstraint\"/>" +
          body("a", "-0.6 0.3 0.2", "0 0 0", "0.5", "<PointCollisionModel name=\"a\"/>") +
          body("b", "0.6 0.3 0.2", "0 0 0", "0.5", "<PointCollisionModel name=\"b\"/>") + kFloor,
      "dt=\"0.01\" gravity=\"3 -9.81 0\"");
  ASSERT_TRUE(scene.simulation.collisions);
  for (int step = 0; step < 100; ++step) scene.simulation.step();
  const Vec3<double> a = scene.simulation.objects[0].system.state.position[0];
  const Vec3<double> b = scene.simulation.objects[1].system.state.position[0];
  EXPECT_LT((b - Vec3<double>(0.6, 0.3, 0.2)).norm(), 1e-12);
  EXPECT_NEAR(a.y(), 0.2, 1e-9);
  EXPECT_GT(a.x(), -0.3) << "slid along the tilted gravity";
  ASSERT_NE(stick_constraint(scene), nullptr);
}

TEST(StickContactConstraintScene, WhatIsNotSimulatedIsSaid) {
  // Under the default animation loop its rows would never be solved.
  LoadedScene plain = build_scene_text("<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
                                       "<MinProximityIntersection/><CollisionResponse response=\"StickContactConstraint\"/>" +
                                           body("ball", "0.1 0.6 0.2", "0 0 0", "0.5") + kFloor,
                                       "dt=\"0.01\"");
  EXPECT_FALSE(plain.simulation.collisions);
  bool said = false;
  for (const auto& line : plain.warnings) said = said || line.find("StickContactConstraint makes Lagrangian constraints") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace fastcorot
