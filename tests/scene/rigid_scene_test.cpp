// Rigid bodies in scenes (template="Rigid3d"): integrated by the ODE solvers with two Vec3 blocks per
// rigid, against closed forms: free fall, spinning at constant ω (SOFA's convention: no gyroscopic
// term, the inertia not rotated), a constant torque, a pendulum held by a spring on a carried point
// against the small-angle period, with and without a mass on carried points; fixed rigids; points carried by a RigidMapping; bad input
// refused in one line.
#include "fastcorot/io/checkpoint.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/mapped_state.h"

#include "../support/oscillation.h"
#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

// One rigid body under `solvers`, with `own` beside its state and `child` in a child node.
std::string body(const std::string& state_attributes, const std::string& own, const std::string& child = "",
                 const std::string& solvers = "<EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-30\" threshold=\"1e-30\"/>") {
  return "<Node name=\"body\">" + solvers + "<MechanicalObject name=\"dofs\" template=\"Rigid3d\" " + state_attributes + "/>" +
         own + (child.empty() ? "" : "<Node name=\"carried\">" + child + "</Node>") + "</Node>";
}

void step(LoadedScene& scene, int steps) {
  for (int s = 0; s < steps; ++s) scene.simulation.step();
}

RigidCoord<double> rigid(const LoadedScene& scene, std::size_t k = 0) {
  const auto& system = scene.simulation.objects.at(0).system;
  return system.rigids->coord(system.state.position, k);
}

// The rotation of angle |w| about w as a quaternion.
Eigen::Quaterniond turn(const Vec3<double>& w) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(w.norm(), w.normalized()));
}

double quaternion_distance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

TEST(RigidScene, FallsAndSpinsAsImplicitEulerWithoutGyroscopicTerm) {
  // Inertia diag(1, 2, 3) per unit mass: a rigid body spinning about a non-principal... any axis
  // keeps ω in SOFA (no ω × Iω), so ω stays as given and the orientation turns by h ω each step.
  const Vec3<double> w(0.3, -0.5, 1.0), v0(1, 2, 0), g(0, -9.81, 0);
  LoadedScene scene = build_scene_text(
      body("position=\"1 2 3 0 0 0 1\" velocity=\"1 2 0 0.3 -0.5 1\"", "<UniformMass vertexMass=\"2 1 [1 0 0,0 2 0,0 0 3]\"/>"),
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const int n = 200;
  const double h = 0.01;
  step(scene, n);
  const RigidCoord<double> x = rigid(scene);
  // v_k = v0 + k h g, x_n = x0 + h sum_{k=1..n} v_k.
  const Vec3<double> expected = Vec3<double>(1, 2, 3) + n * h * v0 + h * h * g * (n * (n + 1) / 2.0);
  EXPECT_LT((x.center - expected).norm(), 1e-11 * expected.norm());
  EXPECT_LT(quaternion_distance(x.orientation, turn(n * h * w)), 1e-12);
  const auto& v = scene.simulation.objects.at(0).system.state.velocity;
  EXPECT_LT((v[1] - w).norm(), 1e-14);
  EXPECT_LT((v[0] - (v0 + n * h * g)).norm(), 1e-12);
}

TEST(RigidScene, Translation2AndRotation2MoveThePositionsAfterTheRestPositionsWereTaken) {
  // STLIB's Floor and Cube place their rigid this way: rest where written, position moved.
  LoadedScene scene = build_scene_text(
      body("position=\"1 0 0 0 0 0 1\" translation=\"0 1 0\" rotation2=\"0 0 90\" translation2=\"0 0 5\"", "<UniformMass totalMass=\"1\"/>"),
      "dt=\"0.01\" gravity=\"0 0 0\"");
  const auto& system = scene.simulation.objects.at(0).system;
  const RigidCoord<double> x = rigid(scene), rest = system.rigids->rest_coord(system.state.rest_position, 0);
  EXPECT_LT((rest.center - Vec3<double>(1, 1, 0)).norm(), 1e-15);
  EXPECT_LT(quaternion_distance(rest.orientation, Eigen::Quaterniond::Identity()), 1e-15);
  // (1, 1, 0) turned 90 degrees about z is (-1, 1, 0); then up 5; the orientation turns too.
  EXPECT_LT((x.center - Vec3<double>(-1, 1, 5)).norm(), 1e-14);
  EXPECT_LT(quaternion_distance(x.orientation, turn(Vec3<double>(0, 0, M_PI / 2))), 1e-15);
  // The same on points, with SOFA's short forms.
  LoadedScene points = build_scene_text(
      "<Node name=\"points\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject position=\"1 0 0  0 1 0\" dx2=\"2\" rz2=\"180\"/>"
      "<UniformMass totalMass=\"1\"/></Node>", "dt=\"0.01\"");
  const auto& state = points.simulation.objects.at(0).system.state;
  EXPECT_LT((state.position[0] - Vec3<double>(1, 0, 0)).norm(), 1e-15);   // (-1, 0, 0) + (2, 0, 0)
  EXPECT_LT((state.position[1] - Vec3<double>(2, -1, 0)).norm(), 1e-15);
  EXPECT_EQ(state.rest_position[1], Vec3<double>(0, 1, 0));
}

TEST(RigidScene, ExplicitEulerTurnsAndFallsAsSymplecticEuler) {
  const Vec3<double> w(0, 2, 0), g(0, 0, -10);
  LoadedScene scene = build_scene_text(body("velocity=\"0 0 0 0 2 0\"", "<UniformMass totalMass=\"3\"/>", "",
                                            "<EulerExplicitSolver/>"),
                                       "dt=\"0.001\" gravity=\"0 0 -10\"");
  const int n = 500;
  const double h = 0.001;
  step(scene, n);
  const RigidCoord<double> x = rigid(scene);
  EXPECT_LT((x.center - h * h * g * (n * (n + 1) / 2.0)).norm(), 1e-12);
  EXPECT_LT(quaternion_distance(x.orientation, turn(n * h * w)), 1e-12);
}

TEST(RigidScene, ConstantTorqueSpinsUpThroughTheInverseInertia) {
  // τ = (0, 0, 6) on m = 2, inertia diag(1, 1, 3) per unit mass: α = τ / (m · 3) = 1 rad/s².
  for (const std::string solver : {"<CGLinearSolver iterations=\"50\" tolerance=\"1e-30\" threshold=\"1e-30\"/>", "<SparseLDLSolver/>"}) {
    LoadedScene scene = build_scene_text(
        body("", "<UniformMass vertexMass=\"2 1 1 0 0 0 1 0 0 0 3\"/><ConstantForceField forces=\"0 0 0 0 0 6\"/>", "",
             "<EulerImplicitSolver/>" + solver),
        "dt=\"0.01\" gravity=\"0 0 0\"");
    step(scene, 100);
    const auto& v = scene.simulation.objects.at(0).system.state.velocity;
    EXPECT_NEAR(v[1].z(), 1.0, 1e-12) << solver;
    EXPECT_LT(v[0].norm() + v[1].head<2>().norm(), 1e-14) << solver;
    // θ_n = h² sum k α = 0.0001 · 5050.
    EXPECT_LT(quaternion_distance(rigid(scene).orientation, turn(Vec3<double>(0, 0, 0.505))), 1e-12) << solver;
  }
}

TEST(RigidScene, FixedRigidsStayAndOthersFall) {
  LoadedScene scene = build_scene_text(body("position=\"0 0 0 0 0 0 1  5 0 0 0 0 0 1\" velocity=\"0 0 0 1 1 1\"",
                                            "<UniformMass totalMass=\"2\"/><FixedProjectiveConstraint indices=\"0\"/>"),
                                       "dt=\"0.01\"");
  step(scene, 10);
  EXPECT_EQ(rigid(scene, 0).center, Vec3<double>::Zero());
  // As for fixed points, SOFA projects the increments, not the velocity given at init: the fixed
  // rigid keeps turning at its initial ω while gravity does not move it.
  EXPECT_LT(quaternion_distance(rigid(scene, 0).orientation, turn(Vec3<double>(0.1, 0.1, 0.1))), 1e-14);
  EXPECT_EQ(scene.simulation.objects.at(0).system.state.velocity[0], Vec3<double>::Zero());
  EXPECT_LT(rigid(scene, 1).center.y(), -0.005);
}

TEST(RigidScene, RigidMappedPointsAndVisualModelsFollowTheRigid) {
  // globalToLocalCoords: the child's positions are in the world at init, brought into the frame.
  LoadedScene scene = build_scene_text(
      body("position=\"1 0 0 0 0 0.7071067811865476 0.7071067811865476\" velocity=\"0 0 0 0 0 1\"", "<UniformMass totalMass=\"1\"/>",
           "<MechanicalObject name=\"points\" position=\"2 0 0  1 1 0\"/><RigidMapping globalToLocalCoords=\"true\"/>"),
      "dt=\"0.01\" gravity=\"0 0 0\"");
  step(scene, 50);
  const RigidCoord<double> x = rigid(scene);
  const auto states = state_snapshots(scene.simulation.objects.at(0));
  ASSERT_EQ(states.size(), 2u);
  EXPECT_TRUE(states[0].rigid);
  ASSERT_EQ(states[0].rigid_position.size(), 7u);
  EXPECT_EQ(states[0].rigid_position[6], x.orientation.w());
  const auto& points = states[1].position;
  ASSERT_EQ(points.size(), 2u);
  // Point 0 was 1 along the rigid's world x axis at init, point 1 1 along y; the rigid turned by 0.5 rad since.
  const Mat3<double> turned = Eigen::AngleAxisd(0.5, Vec3<double>::UnitZ()).toRotationMatrix();
  EXPECT_LT((points[0] - (x.center + turned * Vec3<double>(1, 0, 0))).norm(), 1e-12);
  EXPECT_LT((points[1] - (x.center + turned * Vec3<double>(0, 1, 0))).norm(), 1e-12);
  // v = v_c + ω × r.
  EXPECT_LT((states[1].velocity[0] - Vec3<double>(0, 0, 1).cross(turned * Vec3<double>(1, 0, 0))).norm(), 1e-12);
}

TEST(RigidScene, IdentityMappedPointsAreTheCentresAndTheirForcesDoNotTurnTheBody) {
  // SOFA's IdentityMapping<Rigid3, Vec3>: one point per body at its centre; a force on it moves the
  // centre only (before, the child took a point per Vec3 block, the angular one included, and a
  // force there turned the body).
  LoadedScene scene = build_scene_text(
      body("position=\"1 2 3 0 0 0.7071067811865476 0.7071067811865476\"", "<UniformMass totalMass=\"2\"/>",
           "<MechanicalObject name=\"centres\"/><ConstantForceField forces=\"4 0 0\"/><IdentityMapping/>"),
      "dt=\"0.01\" gravity=\"0 0 0\"");
  step(scene, 10);
  const RigidCoord<double> x = rigid(scene);
  const auto states = state_snapshots(scene.simulation.objects.at(0));
  ASSERT_EQ(states.size(), 2u);
  ASSERT_EQ(states[1].position.size(), 1u);
  EXPECT_LT((states[1].position[0] - x.center).norm(), 1e-15);
  EXPECT_LT(quaternion_distance(x.orientation, Eigen::Quaterniond(0.7071067811865476, 0, 0, 0.7071067811865476)), 1e-15);
  // Implicit Euler under a constant force a = F/m: x_n = x_0 + a h² n(n+1)/2.
  EXPECT_NEAR(x.center.x(), 1 + 2.0 * 0.01 * 0.01 * 55, 1e-12);
  EXPECT_NEAR(x.center.y(), 2, 1e-15);
}

// A rigid pendulum: the body's point (0, L, 0) (local) is held at the origin by a stiff
// RestShapeSpringsForceField written on the carried point, so the body swings about it under
// gravity. Small angles: θ(t) = θ0 cos(2π t / T), T = 2π sqrt((I + m L²) / (m g L)), I = m i_zz.
// `bob`: a second carried node (its own masses swing with the body).
std::string pendulum(double theta0, const std::string& solver, const std::string& bob = "") {
  const double L = 1;
  const Vec3<double> center = -(Eigen::AngleAxisd(theta0, Vec3<double>::UnitZ()) * Vec3<double>(0, L, 0));
  const Eigen::Quaterniond q(Eigen::AngleAxisd(theta0, Vec3<double>::UnitZ()));
  std::ostringstream position;
  position.precision(17);
  position << center.x() << ' ' << center.y() << " 0 0 0 " << q.z() << ' ' << q.w();
  return body("position=\"" + position.str() + "\"", "<UniformMass vertexMass=\"1 1 0.1 0 0 0 0.1 0 0 0 0.1\"/>",
              "<MechanicalObject name=\"pivot\" position=\"0 1 0\" rest_position=\"0 0 0\"/>"
              "<RestShapeSpringsForceField stiffness=\"1e5\"/><RigidMapping/>" +
                  (bob.empty() ? "" : "</Node><Node name=\"bob\">" + bob),
              "<EulerImplicitSolver/>" + solver);
}

double swing_angle(const LoadedScene& scene) {
  const Eigen::Quaterniond q = rigid(scene).orientation;
  return 2 * std::atan2(q.z(), q.w());
}

TEST(RigidScene, PendulumHeldByASpringOnACarriedPointSwingsWithTheSmallAnglePeriod) {
  const double period = 2 * std::numbers::pi * std::sqrt((0.1 + 1.0) / 9.81);
  for (const std::string solver : {"<CGLinearSolver iterations=\"100\" tolerance=\"1e-20\" threshold=\"1e-20\"/>", "<SparseLDLSolver/>"}) {
    LoadedScene scene = build_scene_text(pendulum(0.05, solver), "dt=\"0.001\" gravity=\"0 -9.81 0\"");
    // Upward zero crossings of θ: a period apart.
    const auto crossings = testing::upward_crossings(scene, 8000, 0.001, [&] { return swing_angle(scene); });
    ASSERT_GE(crossings.size(), 3u) << solver;
    EXPECT_NEAR(testing::mean_period(crossings), period, 0.005 * period) << solver;
    // The pivot stays at the origin (to the spring's give: m g / k plus the swing's pull).
    const auto states = state_snapshots(scene.simulation.objects.at(0));
    EXPECT_LT(states.at(1).position.at(0).norm(), 2e-4) << solver;
  }
}

// A mass written on carried points acts through J: the bob (mass 2 at local (0, -0.5, 0), 1.5 below
// the pivot) adds its inertia m r² about the pivot and its weight's torque, so T = 2π sqrt((I + m0 L²
// + m (1.5 L)²) / (g (m0 L + 1.5 m L))), with the rigid's own m0 = 1, I = 0.1 (its weight at L).
TEST(RigidScene, MassOnCarriedPointsSwingsWithTheBody) {
  const double inertia = 0.1 + 1.0 + 2 * 1.5 * 1.5, moment = 1.0 + 2 * 1.5;
  const double period = 2 * std::numbers::pi * std::sqrt(inertia / (9.81 * moment));
  const std::string bob = "<MechanicalObject position=\"0 -0.5 0\"/><UniformMass totalMass=\"2\"/><RigidMapping/>";
  const std::string cg = "<CGLinearSolver iterations=\"100\" tolerance=\"1e-20\" threshold=\"1e-20\"/>";
  for (const std::string solver : {cg, std::string("<SparseLDLSolver/>")}) {
    LoadedScene scene = build_scene_text(pendulum(0.05, solver, bob), "dt=\"0.001\" gravity=\"0 -9.81 0\"");
    const auto crossings = testing::upward_crossings(scene, 9000, 0.001, [&] { return swing_angle(scene); });
    ASSERT_GE(crossings.size(), 3u) << solver;
    EXPECT_NEAR(testing::mean_period(crossings), period, 0.005 * period) << solver;
  }
}

// EulerExplicitSolver on a rigid carrying a mass: its acceleration solves the coupled 6×6 system,
// M a = f with the mass at the step's start (M = M_own + Jᵀ M_points J).
TEST(RigidScene, ExplicitEulerSolvesTheCoupledBlocksOfACarriedMass) {
  LoadedScene scene = build_scene_text(
      body("position=\"0 0 0 0 0 0 1\" velocity=\"0 0 0 0.2 0 0.1\"", "<UniformMass vertexMass=\"1 1 0.1 0 0 0 0.2 0 0 0 0.3\"/>",
           "<MechanicalObject position=\"0.5 -1 0.2  -0.3 0.4 1\"/><UniformMass vertexMass=\"2\"/><RigidMapping/>",
           "<EulerExplicitSolver symplectic=\"1\"/>"),
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  auto& system = scene.simulation.objects.at(0).system;
  ASSERT_EQ(system.mass.couplings().size(), 1u);
  const std::vector<Vec3<double>> v0 = system.state.velocity;
  std::vector<Vec3<double>> f(2), ma(2), a(2);
  system.compute_force(system.state.position, f);
  const Mass<double> mass = system.mass;
  scene.simulation.step();
  for (std::size_t i = 0; i < 2; ++i) a[i] = (system.state.velocity[i] - v0[i]) / 0.01;
  mass.multiply(a, ma, 1.0, 1);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_LT((ma[i] - f[i]).norm(), 1e-10 * (1 + f[i].norm())) << i;
  // The weight of the carried points turns the body: a torque r × m g about the centre.
  EXPECT_GT(f[1].norm(), 1.0);
}

TEST(RigidScene, OneAndTwoThreadsGiveTheSameBits) {
  std::vector<Vec3<double>> results[2];
  std::vector<Eigen::Vector4d> orientations[2];
  for (int threads : {1, 2}) {
    LoadedScene scene = build_scene_text(pendulum(0.3, "<CGLinearSolver iterations=\"25\" tolerance=\"1e-12\" threshold=\"1e-20\"/>"),
                                         "dt=\"0.001\"");
    scene.simulation.threads = threads;
    step(scene, 200);
    results[threads - 1] = scene.simulation.objects.at(0).system.state.position;
    orientations[threads - 1].push_back(rigid(scene).orientation.coeffs());
  }
  EXPECT_EQ(results[0], results[1]);
  EXPECT_EQ(orientations[0], orientations[1]);
}

TEST(RigidScene, BadInputIsRefusedInOneLine) {
  const std::string mass = "<UniformMass totalMass=\"1\"/>";
  EXPECT_NE(scene_error(body("position=\"0 0 0 0 0 0 0\"", mass)).find("zero"), std::string::npos);
  EXPECT_NE(scene_error(body("position=\"0 0 0 0 0 0\"", mass)).find("7 per rigid"), std::string::npos);
  EXPECT_NE(scene_error(body("velocity=\"0 0 0 0\"", mass)).find("velocity"), std::string::npos);
  const std::string static_solver = scene_error(body("", mass, "", "<StaticSolver/><SparseLDLSolver/>"));
  EXPECT_NE(static_solver.find("does not integrate Rigid3"), std::string::npos) << static_solver;
  const std::string unsupported = scene_error(body("", mass + "<TetrahedronFEMForceField/>"));
  EXPECT_NE(unsupported.find("TetrahedronFEMForceField on the Rigid3 state"), std::string::npos) << unsupported;
  const std::string torque = scene_error(body("", mass + "<ConstantForceField force=\"0 0 1\"/>"));
  EXPECT_NE(torque.find("6 numbers"), std::string::npos) << torque;
  // RigidMapping under a Vec3 object: its parent is of the wrong type.
  const std::string wrong_parent = scene_error(
      "<Node name=\"b\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject position=\"0 0 0\"/><UniformMass totalMass=\"1\"/>"
      "<Node name=\"c\"><MechanicalObject position=\"1 0 0\"/><RigidMapping/></Node></Node>");
  EXPECT_NE(wrong_parent.find("needs a Rigid3 parent"), std::string::npos) << wrong_parent;
  const std::string carried_mass = scene_error(body("", mass, "<MeshTopology position=\"1 0 0  2 0 0  1 1 0  1 0 1\" tetrahedra=\"0 1 2 3\"/><MechanicalObject/>"
                                                    "<MeshMatrixMass massDensity=\"1\"/><RigidMapping/>"));
  EXPECT_NE(carried_mass.find("mass matrix (MeshMatrixMass without lumping) on points carried by rigid bodies"), std::string::npos) << carried_mass;
  const std::string index = scene_error(body("", mass, "<MechanicalObject position=\"1 0 0\"/><RigidMapping index=\"3\"/>"));
  EXPECT_NE(index.find("index 3"), std::string::npos) << index;
  // A .rigid file that does not parse names the file and line.
  const std::string path = ::testing::TempDir() + "bad_body.rigid";
  std::ofstream(path) << "Xsp 3.0\nmass 2\n";
  const std::string file = scene_error(body("", "<UniformMass filename=\"" + path + "\"/>"));
  EXPECT_NE(file.find("bad_body.rigid:2"), std::string::npos) << file;
  std::remove(path.c_str());
}

// A checkpoint holds the orientations: a spinning, falling body resumed from step 30 is bitwise the
// uninterrupted run at step 60; a checkpoint of another number of rigids is refused.
TEST(RigidScene, CheckpointsResumeTurnedBodiesBitwise) {
  const std::string scene = body("position=\"0 0 0 0 0 0 1  2 0 0 0 0 0 1\" velocity=\"1 0 0 0.3 -0.5 1\"",
                                 "<UniformMass vertexMass=\"2 1 [1 0 0,0 2 0,0 0 3]\"/>",
                                 "<MechanicalObject position=\"1 0 0\"/><UniformMass totalMass=\"0.5\"/><RigidMapping/>");
  LoadedScene uninterrupted = build_scene_text(scene, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  step(uninterrupted, 30);
  const std::string path = ::testing::TempDir() + "rigid.ckpt";
  write_checkpoint(path, uninterrupted.simulation, "rigid.scn");
  step(uninterrupted, 30);
  LoadedScene resumed = build_scene_text(scene, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  restore_checkpoint(path, resumed.simulation);
  step(resumed, 30);
  const auto& a = uninterrupted.simulation.objects.at(0).system;
  const auto& b = resumed.simulation.objects.at(0).system;
  EXPECT_EQ(a.state.position, b.state.position);
  EXPECT_EQ(a.state.velocity, b.state.velocity);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(a.rigids->orientation[k].coeffs(), b.rigids->orientation[k].coeffs()) << k;
  EXPECT_GT(quaternion_distance(a.rigids->orientation[0], Eigen::Quaterniond::Identity()), 0.1);
  LoadedScene other = build_scene_text(body("position=\"0 0 0 0 0 0 1\"", "<UniformMass totalMass=\"1\"/>"), "dt=\"0.01\"");
  try {
    restore_checkpoint(path, other.simulation);
    ADD_FAILURE() << "a checkpoint of two rigids resumed one";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("written for scene"), std::string::npos) << error.what();
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace fastcorot
