// FrictionContactConstraint under FreeMotionAnimationLoop through the scene builder: a soft cube
// landing and sliding on a floor against SOFA's own trajectories (position and velocity violations,
// Gauss–Seidel and LCP: tests/data/sofa_reference/cube_on_floor_friction*); a point mass on a floor
// with gravity tilted by θ against Coulomb's closed forms (it sticks iff tan θ ≤ μ, else gains
// h g (sin θ − μ cos θ) of speed per step; its normal impulse per step is m g cos θ h); two masses
// meeting head-on keep their momentum; bad input and unsupported settings said clearly.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/constraint/unilateral_lagrangian_constraint.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"

#include "../support/scene_text.h"
#include "support/contact_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

// SOFA's solvers stop at 1e-12 (scaled by the rows): the two agree to about that, not bitwise.
TEST(FrictionContactScene, SoftCubeSlidesOnAFloorAsInSofa) {
  testing::expect_contact_trajectory("cube_on_floor_friction.scn", "cube_on_floor_friction_trajectory.json", 1e-9);
}

TEST(FrictionContactScene, VelocityViolationsFollowSofa) {
  testing::expect_contact_trajectory("cube_on_floor_friction_velocity.scn", "cube_on_floor_friction_velocity_trajectory.json", 1e-9);
}

TEST(FrictionContactScene, LcpSolverFollowsSofa) {
  testing::expect_contact_trajectory("cube_on_floor_friction_lcp.scn", "cube_on_floor_friction_lcp_trajectory.json", 1e-9);
}

TEST(FrictionContactScene, NewProximityContactsFollowSofa) {
  // Clamped to the floor's edges and corners: more contacts than MinProximity's (19 against 16).
  testing::expect_contact_trajectory("cube_on_floor_friction_newproximity.scn", "cube_on_floor_friction_newproximity_trajectory.json",
                                     1e-9);
}

TEST(FrictionContactScene, LocalMinDistanceContactsFollowSofa) {
  testing::expect_contact_trajectory("cube_on_floor_friction_localmindistance.scn",
                                     "cube_on_floor_friction_localmindistance_trajectory.json", 1e-9);
}

TEST(FrictionContactScene, SpheresSlideOnAFloorAsInSofa) {
  // Triangle–Sphere contacts keep the contact distance plus the radius.
  testing::expect_contact_trajectory("spheres_on_floor_friction.scn", "spheres_on_floor_friction_trajectory.json", 1e-9);
}

constexpr double kMass = 0.5, kG = 9.81, kH = 0.01;

// A number as the scene text writes it, every digit kept.
std::string number(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

// A point of mass m resting at the contact distance (0.2) above a large still triangle in y = 0,
// gravity g (sin θ, −cos θ, 0), contacts with friction coefficient `mu`.
std::string point_on_incline(double mu, const std::string& solver = "<BlockGaussSeidelConstraintSolver maxIterations=\"100\" tolerance=\"1e-15\"/>") {
  return "<FreeMotionAnimationLoop/>" + solver +
         "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
         "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/>"
         "<CollisionResponse response=\"FrictionContactConstraint\" responseParams=\"mu=" + number(mu) + "\"/>"
         "<Node name=\"ball\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
         "<MechanicalObject name=\"point\" position=\"0.1 0.2 0.2\"/><UniformMass totalMass=\"0.5\"/><PointCollisionModel/>"
         "<LinearSolverConstraintCorrection/></Node>"
         "<Node name=\"floor\"><MeshTopology position=\"-10 0 -10  10 0 -10  0 0 20\" triangles=\"0 2 1\"/><MechanicalObject/>"
         "<TriangleCollisionModel simulated=\"0\" moving=\"0\"/></Node>";
}

std::string tilted_gravity(double theta) {
  return "dt=\"0.01\" gravity=\"" + number(kG * std::sin(theta)) + " " + number(-kG * std::cos(theta)) + " 0\"";
}

TEST(FrictionContactScene, APointOnAnInclineSticksIffTanThetaIsBelowMu) {
  const double theta = std::atan(0.4);
  const double gx = kG * std::sin(theta), gy = -kG * std::cos(theta);
  for (const double mu : {0.5, 0.4000001}) {
    LoadedScene scene = build_scene_text(point_on_incline(mu), tilted_gravity(theta));
    auto& simulation = scene.simulation;
    const auto& x = simulation.objects[0].system.state.position;
    const auto& v = simulation.objects[0].system.state.velocity;
    for (int step = 0; step < 200; ++step) {
      simulation.step();
      ASSERT_EQ(simulation.collision_report().contacts, 1) << "step " << step;
      // The normal impulse holds the weight's normal part over the step.
      const auto lambda = simulation.constraints->constraint_forces();
      ASSERT_EQ(lambda.size(), 3u);
      EXPECT_NEAR(lambda[0], -kMass * gy * kH, 1e-12) << "step " << step;
      // The friction impulse holds the tangential part, inside the disk.
      EXPECT_NEAR(std::hypot(lambda[1], lambda[2]), kMass * gx * kH, 1e-12) << "step " << step;
    }
    EXPECT_NEAR(x[0].x(), 0.1, 1e-11) << "mu " << mu;
    EXPECT_NEAR(x[0].y(), 0.2, 1e-11) << "at the contact distance";
    EXPECT_NEAR(v[0].norm(), 0.0, 1e-11);
  }
}

TEST(FrictionContactScene, AnObstacleOnAStillRigidIsPlacedByItsFrame) {
  // STLIB's Floor: a rigid no solver moves, its triangle under a RigidMapping in the rigid's frame
  // (here moved by (1, -2, 3) and turned a quarter about y: local (x, 0, z) lands at (1 + z, -2, 3 - x)).
  // The point rests on it as on the same triangle written in the world.
  const std::string header = "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"100\" tolerance=\"1e-15\"/>"
                             "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
                             "<MinProximityIntersection alarmDistance=\"0.5\" contactDistance=\"0.2\"/>"
                             "<CollisionResponse response=\"FrictionContactConstraint\" responseParams=\"mu=0.5\"/>";
  const std::string ball = "<Node name=\"ball\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
                           "<MechanicalObject name=\"point\" position=\"1.1 -1.7 3.2\"/><UniformMass totalMass=\"0.5\"/>"
                           "<PointCollisionModel/>%s</Node>";
  const std::string corrected = "<LinearSolverConstraintCorrection/>";
  const auto with = [&](const std::string& correction) {
    std::string text = ball;
    text.replace(text.find("%s"), 2, correction);
    return text;
  };
  const std::string s = number(std::sqrt(0.5));
  const std::string carried = "<Node name=\"floor\"><MechanicalObject template=\"Rigid3\" position=\"1 -2 3 0 " + s + " 0 " + s +
                              "\"/><Node name=\"collision\"><MeshTopology position=\"10 0 -10  10 0 10  -20 0 0\" triangles=\"0 2 1\"/>"
                              "<MechanicalObject/><TriangleCollisionModel simulated=\"0\" moving=\"0\"/><RigidMapping/></Node></Node>";
  const std::string world = "<Node name=\"floor\"><MeshTopology position=\"-9 -2 -7  11 -2 -7  1 -2 23\" triangles=\"0 2 1\"/>"
                            "<MechanicalObject/><TriangleCollisionModel simulated=\"0\" moving=\"0\"/></Node>";
  LoadedScene on_rigid = build_scene_text(header + with(corrected) + carried, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  LoadedScene in_world = build_scene_text(header + with(corrected) + world, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const auto& a = on_rigid.simulation.objects[0].system.state.position;
  const auto& b = in_world.simulation.objects[0].system.state.position;
  for (int step = 0; step < 100; ++step) {
    on_rigid.simulation.step();
    in_world.simulation.step();
    ASSERT_NEAR((a[0] - b[0]).norm(), 0.0, 1e-12) << "step " << step;
  }
  EXPECT_EQ(on_rigid.simulation.collision_report().contacts, 1);
  EXPECT_NEAR(a[0].y(), -1.8, 1e-9) << "resting at the contact distance above y = -2";
  // Without a correction on the ball, neither side's compliance reaches W: warned, no contact
  // response, the ball falls through as in SOFA.
  LoadedScene uncorrected = build_scene_text(header + with("") + carried, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  bool warned = false;
  for (const auto& line : uncorrected.warnings) warned = warned || line.find("no constraint correction on either side") != std::string::npos;
  EXPECT_TRUE(warned);
  for (int step = 0; step < 100; ++step) uncorrected.simulation.step();
  EXPECT_LT(uncorrected.simulation.objects[0].system.state.position[0].y(), -2.0);
}

TEST(FrictionContactScene, ABodyWithoutCorrectionPushesTheOtherOnly) {
  // The floor simulated (its own solver, its points held) but with no constraint correction: warned;
  // the corrected point rests on it as on the still floor (only its own compliance in W).
  const std::string still = point_on_incline(0.5);
  std::string simulated = still;
  const std::string floor = "<Node name=\"floor\"><MeshTopology";
  simulated.replace(simulated.find(floor), floor.size(),
                    "<Node name=\"floor\"><EulerImplicitSolver/><SparseLDLSolver/><MeshTopology");
  const std::string model = "<TriangleCollisionModel simulated=\"0\" moving=\"0\"/>";
  simulated.replace(simulated.find(model), model.size(),
                    "<UniformMass totalMass=\"1\"/><FixedProjectiveConstraint indices=\"0 1 2\"/><TriangleCollisionModel/>");
  LoadedScene a = build_scene_text(still, tilted_gravity(0));
  LoadedScene b = build_scene_text(simulated, tilted_gravity(0));
  ASSERT_EQ(b.simulation.objects.size(), 2u);
  bool warned = false;
  for (const auto& line : b.warnings) warned = warned || line.find("has no constraint correction: its FrictionContactConstraint contacts push the other side only") != std::string::npos;
  EXPECT_TRUE(warned);
  for (int step = 0; step < 100; ++step) {
    a.simulation.step();
    b.simulation.step();
    ASSERT_NEAR((a.simulation.objects[0].system.state.position[0] - b.simulation.objects[0].system.state.position[0]).norm(), 0, 1e-12)
        << "step " << step;
  }
  EXPECT_NEAR(b.simulation.objects[0].system.state.position[0].y(), 0.2, 1e-11);
}

TEST(FrictionContactScene, APointOnASteeperInclineGainsCoulombsSpeedEachStep) {
  const double theta = std::atan(0.4);
  const double gx = kG * std::sin(theta), gy = -kG * std::cos(theta);
  for (const double mu : {0.2, 0.0}) {
    LoadedScene scene = build_scene_text(point_on_incline(mu), tilted_gravity(theta));
    auto& simulation = scene.simulation;
    const auto& x = simulation.objects[0].system.state.position;
    const auto& v = simulation.objects[0].system.state.velocity;
    const int steps = 100;
    for (int step = 0; step < steps; ++step) {
      simulation.step();
      const auto lambda = simulation.constraints->constraint_forces();
      ASSERT_EQ(lambda.size(), mu > 0 ? 3u : 1u);
      EXPECT_NEAR(lambda[0], -kMass * gy * kH, 1e-12);
      if (mu > 0) {
        EXPECT_NEAR(std::hypot(lambda[1], lambda[2]), mu * lambda[0], 1e-12) << "on the disk's rim";
      }
    }
    const double a = gx + mu * gy;  // g (sin θ − μ cos θ)
    EXPECT_NEAR(v[0].x(), steps * kH * a, 1e-10) << "mu " << mu;
    EXPECT_NEAR(v[0].y(), 0.0, 1e-11);
    EXPECT_NEAR(v[0].z(), 0.0, 1e-11);
    // Semi-implicit Euler: x_n = x_0 + h² a n (n + 1) / 2.
    EXPECT_NEAR(x[0].x(), 0.1 + kH * kH * a * steps * (steps + 1) / 2, 1e-10);
    EXPECT_NEAR(x[0].y(), 0.2, 1e-11);
  }
}

TEST(FrictionContactScene, TwoMassesMeetingHeadOnKeepTheirMomentumWithoutRebound) {
  // Two points, each under its own solver, closing at 1 + 0.5; no gravity; Point–Point contacts.
  const std::string text =
      "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"100\" tolerance=\"1e-15\"/>"
      "<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
      "<MinProximityIntersection alarmDistance=\"0.2\" contactDistance=\"0.05\"/>"
      "<CollisionResponse response=\"FrictionContactConstraint\" responseParams=\"mu=0\"/>"
      "<Node name=\"a\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
      "<MechanicalObject position=\"0 0 0\" velocity=\"1 0 0\"/><UniformMass totalMass=\"2\"/><PointCollisionModel/>"
      "<LinearSolverConstraintCorrection/></Node>"
      "<Node name=\"b\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
      "<MechanicalObject position=\"0.5 0 0\" velocity=\"-0.5 0 0\"/><UniformMass totalMass=\"1\"/><PointCollisionModel/>"
      "<LinearSolverConstraintCorrection/></Node>";
  LoadedScene scene = build_scene_text(text, "dt=\"0.01\" gravity=\"0 0 0\"");
  auto& simulation = scene.simulation;
  ASSERT_EQ(simulation.objects.size(), 2u);
  const auto momentum = [&] { return 2 * simulation.objects[0].system.state.velocity[0] + simulation.objects[1].system.state.velocity[0]; };
  const Vec3<double> before = momentum();
  bool touched = false;
  for (int step = 0; step < 100; ++step) {
    simulation.step();
    touched = touched || simulation.collision_report().contacts > 0;
    EXPECT_NEAR((momentum() - before).norm(), 0.0, 1e-12) << "step " << step;
    const double gap = simulation.objects[1].system.state.position[0].x() - simulation.objects[0].system.state.position[0].x();
    EXPECT_GE(gap, 0.05 - 1e-12) << "never closer than the contact distance, step " << step;
  }
  EXPECT_TRUE(touched);
  // No rebound: they end moving together at the common speed.
  const double common = before.x() / 3;
  EXPECT_NEAR(simulation.objects[0].system.state.velocity[0].x(), common, 1e-10);
  EXPECT_NEAR(simulation.objects[1].system.state.velocity[0].x(), common, 1e-10);
}

TEST(FrictionContactScene, TheTangentFrameIsSofas) {
  // SOFA's frame for n = (0, 1, 0): t = (n_z, n_x, n_y) = (0, 0, 1); s = n × t / |n × t| = (1, 0, 0);
  // t ← −n × s = (0, 0, 1).
  Vec3<double> t, s;
  UnilateralLagrangianConstraint<double>::tangents(Vec3<double>(0, 1, 0), t, s);
  EXPECT_LT((s - Vec3<double>(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((t - Vec3<double>(0, 0, 1)).norm(), 1e-15);
  // Any normal: an orthonormal frame.
  const Vec3<double> n = Vec3<double>(0.3, -0.5, 0.81).normalized();
  UnilateralLagrangianConstraint<double>::tangents(n, t, s);
  EXPECT_NEAR(t.dot(n), 0, 1e-15);
  EXPECT_NEAR(s.dot(n), 0, 1e-15);
  EXPECT_NEAR(t.dot(s), 0, 1e-15);
  EXPECT_NEAR(t.norm(), 1, 1e-15);
}

TEST(FrictionContactScene, FrictionResolutionMatchesCoulombsDiskByHand) {
  // W diagonal 2, coupling W_nt = 0.5; d = (−1, 3, 0): λ_n = 0.5, then d_t = 3 + 0.5·0.5 = 3.25,
  // λ_t = −3.25, clipped to μ λ_n = 0.25 in size.
  DenseMatrix<double> w = DenseMatrix<double>::Identity(3, 3) * 2;
  w(0, 1) = w(1, 0) = 0.5;
  UnilateralFrictionResolution<double> resolution(0.5, 0);
  double f[3] = {0, 0, 0};
  resolution.init(0, w, f);
  const double d[3] = {-1, 3, 0};
  resolution.resolve(0, w, d, f, d);
  EXPECT_DOUBLE_EQ(f[0], 0.5);
  EXPECT_DOUBLE_EQ(f[1], -0.25);
  EXPECT_DOUBLE_EQ(f[2], 0.0);
  // A pulling normal impulse releases all three.
  const double apart[3] = {1, 3, 0};
  double g[3] = {0, 1, 1};
  resolution.resolve(0, w, apart, g, apart);
  EXPECT_EQ(g[0], 0.0);
  EXPECT_EQ(g[1], 0.0);
  EXPECT_EQ(g[2], 0.0);
}

TEST(FrictionContactScene, AugmentedLagrangianResolutionByHand) {
  // SOFA's AugmentedLagrangianResolutionWithFriction, ε = 0.5, μ = 0.5, W unused.
  AugmentedLagrangianFrictionResolution<double> resolution(0.5, 0.5, 0);
  const DenseMatrix<double> w = DenseMatrix<double>::Identity(3, 3) * 7;
  // λ_n = 1 − 0.5·(−2) = 2; tangents (0.2, 0) − 0.5·(0.4, 0.2) = (0, −0.1): inside μ λ_n = 1, kept.
  double f[3] = {1, 0.2, 0};
  const double d[3] = {-2, 0.4, 0.2};
  resolution.resolve(0, w, d, f, d);
  EXPECT_DOUBLE_EQ(f[0], 2);
  EXPECT_DOUBLE_EQ(f[1], 0);
  EXPECT_DOUBLE_EQ(f[2], -0.1);
  // λ_n = 0 − 0.5·(−1) = 0.5; tangents (0, 0) − 0.5·(3, 4) = (−1.5, −2): outside μ λ_n = 0.25, so
  // instead λ_t −= μ ε d_n d_t / |d_t| = −0.25·(−1)·(0.6, 0.8) → (0.15, 0.2).
  double g[3] = {0, 0, 0};
  const double e[3] = {-1, 3, 4};
  resolution.resolve(0, w, e, g, e);
  EXPECT_DOUBLE_EQ(g[0], 0.5);
  EXPECT_DOUBLE_EQ(g[1], 0.15);
  EXPECT_DOUBLE_EQ(g[2], 0.2);
  // Pulling: all three released.
  double h[3] = {0.1, 1, 1};
  const double apart[3] = {1, 0, 0};
  resolution.resolve(0, w, apart, h, apart);
  EXPECT_EQ(h[0], 0.0);
  EXPECT_EQ(h[1], 0.0);
  EXPECT_EQ(h[2], 0.0);
}

TEST(FrictionContactScene, AugmentedLagrangianResponseWithoutFrictionIsTheUnilateralOne) {
  // Its own default mu is 0: one row per contact, resolved as UnilateralResolution, so the point
  // on the incline follows FrictionContactConstraint with mu=0 bit for bit; with mu > 0 it has
  // three rows and slides otherwise.
  const auto augmented = [](const std::string& params) {
    std::string text = point_on_incline(0);
    text.replace(text.find("response=\"FrictionContactConstraint\" responseParams=\"mu=0\""),
                 std::string("response=\"FrictionContactConstraint\" responseParams=\"mu=0\"").size(),
                 "response=\"AugmentedLagrangianResponseConstraint\" responseParams=\"" + params + "\"");
    return build_scene_text(text, tilted_gravity(0.4));
  };
  LoadedScene plain = build_scene_text(point_on_incline(0), tilted_gravity(0.4));
  LoadedScene frictionless = augmented("epsilon=10");
  LoadedScene rough = augmented("mu=0.8&epsilon=10");
  ASSERT_TRUE(frictionless.simulation.collisions);
  ASSERT_TRUE(rough.simulation.collisions);
  bool differs = false;
  for (int step = 0; step < 50; ++step) {
    plain.simulation.step();
    frictionless.simulation.step();
    rough.simulation.step();
    ASSERT_EQ(plain.simulation.objects[0].system.state.position[0], frictionless.simulation.objects[0].system.state.position[0]) << step;
    differs = differs || rough.simulation.objects[0].system.state.position[0] != plain.simulation.objects[0].system.state.position[0];
  }
  EXPECT_TRUE(differs) << "friction holds the point back";
  const auto* loop = dynamic_cast<const FreeMotionAnimationLoop<double>*>(rough.simulation.constraints.get());
  ASSERT_NE(loop, nullptr);
  const auto* contact = dynamic_cast<const UnilateralLagrangianConstraint<double>*>(loop->constraints.back().get());
  ASSERT_NE(contact, nullptr);
  EXPECT_EQ(contact->rows_per_contact(), 3);
  EXPECT_TRUE(contact->parameters().augmented);
  EXPECT_EQ(contact->parameters().epsilon, 10);
}

TEST(FrictionContactScene, BadInputAndUnsupportedSettingsAreSaid) {
  std::string garbage = point_on_incline(0.3);
  garbage.replace(garbage.find("responseParams=\"mu=0.29999999999999999\""), std::string("responseParams=\"mu=0.29999999999999999\"").size(), "responseParams=\"mu=abc\"");
  EXPECT_NE(scene_error(garbage).find("responseParams: 'mu=abc' is not name=number"), std::string::npos) << scene_error(garbage);
  std::string negative = point_on_incline(0.3);
  negative.replace(negative.find("mu=0.29999999999999999"), std::string("mu=0.29999999999999999").size(), "mu=-1");
  EXPECT_NE(scene_error(negative).find("mu, tol and epsilon must be ≥ 0"), std::string::npos) << scene_error(negative);

  // Under the default loop: the scene loads, its collisions said to need FreeMotionAnimationLoop.
  std::string default_loop = point_on_incline(0.3);
  default_loop.replace(default_loop.find("<FreeMotionAnimationLoop/>"), std::string("<FreeMotionAnimationLoop/>").size(), "");
  default_loop.replace(default_loop.find("<LinearSolverConstraintCorrection/>"), std::string("<LinearSolverConstraintCorrection/>").size(), "");
  LoadedScene plain = build_scene_text(default_loop, "dt=\"0.01\"");
  EXPECT_FALSE(plain.simulation.collisions);
  bool said = false;
  for (const auto& line : plain.warnings) said = said || line.find("only a FreeMotionAnimationLoop solves") != std::string::npos;
  EXPECT_TRUE(said);
  // A contactStiffness of 0 disables the response, as in SOFA: no contact, the point falls through.
  std::string soft = point_on_incline(0.3);
  soft.replace(soft.find("<PointCollisionModel/>"), std::string("<PointCollisionModel/>").size(), "<PointCollisionModel contactStiffness=\"0\"/>");
  LoadedScene disabled = build_scene_text(soft, "dt=\"0.01\"");
  for (int step = 0; step < 5; ++step) disabled.simulation.step();
  EXPECT_EQ(disabled.simulation.constraint_report().rows, 0);
  EXPECT_LT(disabled.simulation.objects[0].system.state.position[0].y(), 0.2);
}

}  // namespace
}  // namespace fastcorot
