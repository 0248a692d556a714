// The contact manager's response per model pair: RuleBasedContactManager's ordered rules (a model's
// name, a group number or *, matched either way round; $variables$), a model's own contactResponse
// before them, the manager's response otherwise. Each case is checked against the same scene written
// with a plain CollisionResponse giving that response, bit for bit, and against the other response,
// which must differ.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/constraint/unilateral_lagrangian_constraint.h"
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fastcorot {
namespace {

using testing::build_scene_text;

// Points of mass 0.5 falling from `height` onto a still triangle in the plane y = 0 (named "floor",
// group 2), one node per point ("ball0", "ball1", ...), each in group 10 + its index; `manager`
// is the contact manager's element, `extra` goes into each ball's point model.
std::string balls_over_floor(const std::string& manager, int balls = 1, const std::string& extra = "", double spacing = 0.3) {
  std::string text =
      "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
      "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/>" + manager;
  for (int b = 0; b < balls; ++b) {
    const std::string i = std::to_string(b);
    text += "<Node name=\"ball" + i + "\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><CGLinearSolver iterations=\"100\" "
            "tolerance=\"1e-30\" threshold=\"1e-30\"/><MechanicalObject position=\"" + std::to_string(spacing * b - 0.2) +
            " 0.3 0.2\"/><UniformMass totalMass=\"0.5\"/><PointCollisionModel name=\"ball" + i + "\" group=\"" +
            std::to_string(10 + b) + "\" contactStiffness=\"20\" " + extra + "/></Node>";
  }
  return text +
         "<Node name=\"floor\"><MeshTopology position=\"-1 0 -1  1 0 -1  0 0 2\" triangles=\"0 2 1\"/><MechanicalObject/>"
         "<TriangleCollisionModel name=\"floor\" group=\"2\" simulated=\"0\" moving=\"0\" contactStiffness=\"20\"/></Node>";
}

const std::string kRoot = "dt=\"0.01\" gravity=\"0 -9.81 0\"";

// Every ball's height at each of 60 steps (contact from about step 20).
std::vector<double> heights(LoadedScene scene) {
  std::vector<double> y;
  for (int step = 0; step < 60; ++step) {
    scene.simulation.step();
    for (const auto& object : scene.simulation.objects) {
      for (const auto& x : object.system.state.position) y.push_back(x.y());
    }
  }
  return y;
}

std::vector<double> heights_with(const std::string& response, int balls = 1) {
  return heights(build_scene_text(balls_over_floor("<CollisionResponse response=\"" + response + "\"/>", balls), kRoot));
}

bool warned(const LoadedScene& scene, const std::string& text) {
  for (const auto& line : scene.warnings) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(ContactManagerScene, TheTwoResponsesUsedHereDiffer) {
  // Without this the equalities below could not fail.
  EXPECT_NE(heights_with("PenalityContactForceField"), heights_with("StickContactForceField"));
}

TEST(ContactManagerScene, WithoutAWholeRuleEveryPairTakesTheManagersResponse) {
  // SOFA's own RuleBasedContactManager.scn writes rules="default": a word, not a rule.
  LoadedScene scene = build_scene_text(
      balls_over_floor("<RuleBasedContactManager response=\"PenalityContactForceField\" rules=\"default\"/>"), kRoot);
  EXPECT_TRUE(warned(scene, "rules: 'default' is not a whole rule"));
  ASSERT_TRUE(scene.simulation.collisions);
  EXPECT_EQ(heights(std::move(scene)), heights_with("PenalityContactForceField"));
}

TEST(ContactManagerScene, ARuleMatchesNamesGroupsAndStarsEitherWayRound) {
  for (const std::string rules : {"ball0 floor StickContactForceField", "floor ball0 StickContactForceField", "2 * StickContactForceField",
                                  "* 10 StickContactForceField", "7 * PenalityContactForceField  floor * StickContactForceField"}) {
    LoadedScene scene = build_scene_text(
        balls_over_floor("<RuleBasedContactManager response=\"PenalityContactForceField\" rules=\"" + rules + "\"/>"), kRoot);
    ASSERT_TRUE(scene.simulation.collisions) << rules;
    EXPECT_EQ(heights(std::move(scene)), heights_with("StickContactForceField")) << rules;
  }
  // A rule that matches no pair leaves the manager's response.
  LoadedScene unmatched = build_scene_text(
      balls_over_floor("<RuleBasedContactManager response=\"PenalityContactForceField\" rules=\"3 * StickContactForceField\"/>"), kRoot);
  EXPECT_EQ(heights(std::move(unmatched)), heights_with("PenalityContactForceField"));
}

TEST(ContactManagerScene, VariablesAreAttributesOfTheManager) {
  LoadedScene scene = build_scene_text(
      balls_over_floor("<RuleBasedContactManager response=\"PenalityContactForceField\" variables=\"kind\" kind=\"StickContactForceField\" "
                       "rules=\"* * $kind$\"/>"),
      kRoot);
  EXPECT_FALSE(warned(scene, "unknown attribute")) << "a declared variable is an attribute";
  EXPECT_EQ(heights(std::move(scene)), heights_with("StickContactForceField"));
  // Undeclared: warned, replaced by nothing (as SOFA), so no response is simulated.
  LoadedScene undeclared = build_scene_text(
      balls_over_floor("<RuleBasedContactManager response=\"PenalityContactForceField\" rules=\"* * $kind$\"/>"), kRoot);
  EXPECT_TRUE(warned(undeclared, "$kind$, which `variables` does not declare"));
  EXPECT_FALSE(undeclared.simulation.collisions);
}

TEST(ContactManagerScene, AModelsOwnResponseComesFirst) {
  LoadedScene scene = build_scene_text(
      balls_over_floor("<CollisionResponse response=\"PenalityContactForceField\"/>", 1, "contactResponse=\"StickContactForceField\""), kRoot);
  ASSERT_TRUE(scene.simulation.collisions);
  EXPECT_EQ(heights(std::move(scene)), heights_with("StickContactForceField"));
}

TEST(ContactManagerScene, CollisionResponseTakesTheModelsOwnResponseOnlyWhenTheyAgree) {
  // SOFA's CollisionResponse::getContactResponse: one model's own response, or both when equal;
  // two different ones give the manager's (RuleBasedContactManager would take the first model's).
  const std::string floor_stick = "<TriangleCollisionModel name=\"floor\" group=\"2\" simulated=\"0\" moving=\"0\" contactStiffness=\"20\"";
  const auto with_floor_response = [&](const std::string& manager, const std::string& ball, const std::string& floor) {
    std::string text = balls_over_floor(manager, 1, ball);
    text.replace(text.find(floor_stick), floor_stick.size(), floor_stick + " " + floor);
    return build_scene_text(text, kRoot);
  };
  const std::string plain = "<CollisionResponse response=\"PenalityContactForceField\"/>";
  EXPECT_EQ(heights(with_floor_response(plain, "", "contactResponse=\"StickContactForceField\"")), heights_with("StickContactForceField"));
  EXPECT_EQ(heights(with_floor_response(plain, "contactResponse=\"StickContactForceField\"", "contactResponse=\"StickContactForceField\"")),
            heights_with("StickContactForceField"));
  LoadedScene disagree = with_floor_response(plain, "contactResponse=\"StickContactForceField\"", "contactResponse=\"PenalityContactForceField?x=1\"");
  EXPECT_EQ(heights(std::move(disagree)), heights_with("PenalityContactForceField"));
}

TEST(ContactManagerScene, AResponseCarriesItsParametersAfterAQuestionMark) {
  // SOFA's contact factory reads "Name?a=1&b=2": the manager's response carries its responseParams
  // so, and a model's own response or a rule's may carry its own.
  const std::string loop = "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"50\" tolerance=\"1e-12\"/>";
  const auto friction_mu = [&](const std::string& manager, const std::string& ball) {
    std::string text = balls_over_floor(loop + manager, 1, ball);
    text.replace(text.find("<UniformMass"), 0, "<UncoupledConstraintCorrection/>");
    LoadedScene scene = build_scene_text(text, kRoot);
    const auto* free_motion = dynamic_cast<const FreeMotionAnimationLoop<double>*>(scene.simulation.constraints.get());
    EXPECT_NE(free_motion, nullptr);
    if (!free_motion) return -1.0;
    const auto* contact = dynamic_cast<const UnilateralLagrangianConstraint<double>*>(free_motion->constraints.back().get());
    EXPECT_NE(contact, nullptr);
    return contact ? contact->parameters().mu : -1.0;
  };
  EXPECT_EQ(friction_mu("<CollisionResponse response=\"FrictionContactConstraint\" responseParams=\"mu=0.25\"/>", ""), 0.25);
  EXPECT_EQ(friction_mu("<CollisionResponse response=\"PenalityContactForceField\"/>", "contactResponse=\"FrictionContactConstraint?mu=0.125\""),
            0.125);
  EXPECT_EQ(friction_mu("<RuleBasedContactManager response=\"PenalityContactForceField\" rules=\"* * FrictionContactConstraint?mu=0.5&amp;tol=1e-9\"/>", ""),
            0.5);
}

// Ball o's heights over 60 steps.
std::vector<double> heights_of(LoadedScene scene, std::size_t o) {
  std::vector<double> y;
  for (int step = 0; step < 60; ++step) {
    scene.simulation.step();
    y.push_back(scene.simulation.objects.at(o).system.state.position[0].y());
  }
  return y;
}

TEST(ContactManagerScene, PairsMayTakeDifferentResponses) {
  // Two balls 1.2 apart (out of each other's reach): a rule gives ball1's pair with the floor stick
  // springs, ball0's keeps the manager's penalty; each ball moves as in the scene where every pair
  // has its response.
  const auto two = [](const std::string& manager) { return build_scene_text(balls_over_floor(manager, 2, "", 1.2), kRoot); };
  const std::string rules = "<RuleBasedContactManager response=\"PenalityContactForceField\" rules=\"ball1 floor StickContactForceField\"/>";
  LoadedScene mixed = two(rules);
  ASSERT_TRUE(mixed.simulation.collisions);
  EXPECT_EQ(heights_of(two(rules), 0), heights_of(two("<CollisionResponse response=\"PenalityContactForceField\"/>"), 0));
  EXPECT_EQ(heights_of(two(rules), 1), heights_of(two("<CollisionResponse response=\"StickContactForceField\"/>"), 1));
  EXPECT_NE(heights_of(two(rules), 0), heights_of(two(rules), 1)) << "the two responses differ";
}

}  // namespace
}  // namespace fastcorot
