// Rigid bodies solved together with other objects under one ODE solver (SOFA's solver integrates
// every state below it as one system), the fields SOFA writes on rigid states, and springs
// between rigid centres:
// - two rigid balls joined by a SpringForceField, each on a PlaneForceField floor, one held by a
//   RestShapeSpringsForceField, move their centres exactly as two 3D points with the same masses and
//   fields do (nothing turns them, so their angular blocks stay at rest);
// - a rigid turned away from its rest orientation by an angular RestShapeSpringsForceField
//   oscillates with ω = sqrt(k_a / I), about the axes activeDirections leaves on;
// - points carried by each of two merged rigids (mapped states and masses) follow their own rigid;
// - PartialFixedProjectiveConstraint holds the chosen of a rigid's six directions;
// - a ConstantForceField on carried points pushes and turns the rigid through Jᵀ;
// - a SpringForceField with a mapped end (a carried point, an IdentityMapping's point) acts
//   through that end's mapping;
// - a state mapped barycentrically onto points two rigids carry (each point mixing both) follows
//   them, also when the rigids' object is merged after another one.
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/mapped_state.h"

#include "../support/oscillation.h"
#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

// A ball at x: a rigid body or a 3D point of mass 1, on the floor y = -3 (a PlaneForceField).
std::string ball(const std::string& name, double x, bool rigid, const std::string& extra = "") {
  const std::string position = std::to_string(x) + " 0 0" + (rigid ? " 0 0 0 1" : "");
  return "<Node name=\"" + name + "\"><MechanicalObject name=\"dofs\" template=\"" + (rigid ? "Rigid3d" : "Vec3d") +
         "\" position=\"" + position + "\"/><UniformMass totalMass=\"1\"/>"
         "<PlaneForceField normal=\"0 1 0\" d=\"-3\" stiffness=\"10000\"/>" + extra + "</Node>";
}

std::string balls(bool first_rigid, bool second_rigid) {
  return "<EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/>"
         "<CGLinearSolver iterations=\"100\" tolerance=\"1e-30\" threshold=\"1e-30\"/>" +
         ball("ball_0", -2, first_rigid, "<RestShapeSpringsForceField stiffness=\"10\" angularStiffness=\"1000\"/>") +
         ball("ball_1", 2, second_rigid) +
         "<SpringForceField object1=\"@ball_0/dofs\" object2=\"@ball_1/dofs\" indices1=\"0\" indices2=\"0\" length=\"4\" stiffness=\"2\"/>";
}

// The centres (or points) of both balls after `steps` steps.
std::vector<Vec3<double>> centres(LoadedScene& scene, int steps) {
  for (int s = 0; s < steps; ++s) scene.simulation.step();
  std::vector<Vec3<double>> out;
  for (const StateSnapshot& state : state_snapshots(scene.simulation.objects.at(0))) out.push_back(state.position.at(0));
  return out;
}

TEST(RigidInteraction, RigidBallsJoinedBySpringsMoveAsPointsWithTheSameFields) {
  LoadedScene points = build_scene_text(balls(false, false), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const auto expected = centres(points, 300);
  ASSERT_EQ(expected.size(), 2u);
  EXPECT_LT(expected[1].y(), -2.9);  // the second ball fell to the floor
  for (const auto [first, second] : {std::pair{true, true}, std::pair{true, false}, std::pair{false, true}}) {
    LoadedScene scene = build_scene_text(balls(first, second), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
    ASSERT_EQ(scene.simulation.objects.size(), 1u);
    const auto got = centres(scene, 300);
    ASSERT_EQ(got.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_LT((got[k] - expected[k]).norm(), 1e-10 * (1 + expected[k].norm())) << first << second << " ball " << k;
    }
    const auto states = state_snapshots(scene.simulation.objects.at(0));
    EXPECT_EQ(states[0].rigid, first);
    EXPECT_EQ(states[1].rigid, second);
    if (second) EXPECT_EQ(states[1].rigid_position.size(), 7u);
  }
}

// Turned by φ0 about z from rest: τ = -k_a φ, I = m i_zz, so φ(t) ≈ φ0 cos(sqrt(k_a / I) t).
TEST(RigidInteraction, AngularRestShapeSpringsTurnARigidBackWithTheirPeriod) {
  const double phi0 = 0.2, ka = 50, izz = 0.5;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(phi0, Vec3<double>::UnitZ()));
  const std::string state = "<MechanicalObject template=\"Rigid3d\" position=\"0 0 0 0 0 " + std::to_string(q.z()) + " " +
                            std::to_string(q.w()) + "\" rest_position=\"0 0 0 0 0 0 1\"/>";
  for (const std::string directions : {"", "1 1 1 1 1 0"}) {
    LoadedScene scene = build_scene_text(
        "<EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-30\" threshold=\"1e-30\"/>" + state +
            "<UniformMass vertexMass=\"1 1 1 0 0 0 1 0 0 0 " + std::to_string(izz) + "\"/>"
            "<RestShapeSpringsForceField stiffness=\"100\" angularStiffness=\"" + std::to_string(ka) + "\"" +
            (directions.empty() ? "" : " activeDirections=\"" + directions + "\"") + "/>",
        "dt=\"0.0005\" gravity=\"0 0 0\"");
    const auto& system = scene.simulation.objects.at(0).system;
    const auto angle = [&] {
      const Eigen::Quaterniond o = system.rigids->coord(system.state.position, 0).orientation;
      return 2 * std::atan2(o.z(), o.w());
    };
    const double start = angle();
    const auto crossings = testing::upward_crossings(scene, 8000, 0.0005, angle);
    if (!directions.empty()) {
      // Rotation about z switched off: the rigid keeps its turn.
      EXPECT_TRUE(crossings.empty());
      EXPECT_NEAR(angle(), start, 1e-12);
      continue;
    }
    ASSERT_GE(crossings.size(), 3u);
    const double period = 2 * std::numbers::pi * std::sqrt(izz / ka);
    EXPECT_NEAR(testing::mean_period(crossings), period, 0.005 * period);
  }
}

// Two rigids, each carrying a point (with a mass) and a mapped state, under one solver: after a
// spin, each carried point is its own rigid's centre plus its turned offset.
TEST(RigidInteraction, PointsCarriedByMergedRigidsFollowTheirOwnRigid) {
  const auto body = [](const std::string& name, const std::string& position, const std::string& velocity) {
    return "<Node name=\"" + name + "\"><MechanicalObject template=\"Rigid3d\" position=\"" + position + "\" velocity=\"" + velocity +
           "\"/><UniformMass totalMass=\"1\"/><Node name=\"carried\"><MechanicalObject position=\"1 0 0\"/>"
           "<UniformMass totalMass=\"0.5\"/><RigidMapping/></Node></Node>";
  };
  LoadedScene scene = build_scene_text("<EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-30\" threshold=\"1e-30\"/>" +
                                           body("a", "0 0 0 0 0 0 1", "0 0 0 0 0 1") + body("b", "5 0 0 0 0 0 1", "0 0 0 1 0 0"),
                                       "dt=\"0.01\" gravity=\"0 0 0\"");
  ASSERT_EQ(scene.simulation.objects.size(), 1u);
  for (int s = 0; s < 50; ++s) scene.simulation.step();
  const auto& system = scene.simulation.objects.at(0).system;
  ASSERT_EQ(system.rigids->size(), 2u);
  ASSERT_TRUE(system.rigid_mapped_mass);
  int carried = 0;
  for (const StateSnapshot& state : state_snapshots(scene.simulation.objects.at(0))) {
    if (!state.mapped) continue;
    ++carried;
    const std::size_t k = state.node.find("/a/") != std::string::npos ? 0 : 1;
    const RigidCoord<double> frame = system.rigids->coord(system.state.position, k);
    EXPECT_LT((state.position.at(0) - frame.project_point(Vec3<double>(1, 0, 0))).norm(), 1e-12) << state.node;
    // Each turned: a about z, b about x (the carried point on b's axis stays put).
    if (k == 0) EXPECT_GT(std::abs(state.position.at(0).y()), 0.1);
  }
  EXPECT_EQ(carried, 2);
}

// PartialFixedProjectiveConstraint on a rigid: fixedDirections "1 0 1 1 1 0" leaves it falling along
// y and turning about z only, whatever the gravity and torque push along the held directions.
TEST(RigidInteraction, PartialFixedRigidsMoveOnlyAlongTheirFreeDirections) {
  LoadedScene scene = build_scene_text(
      "<EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-30\" threshold=\"1e-30\"/>"
      "<MechanicalObject template=\"Rigid3d\" position=\"1 2 3 0 0 0 1\"/><UniformMass totalMass=\"1\"/>"
      "<ConstantForceField forces=\"1 0 1 2 3 4\"/>"
      "<PartialFixedProjectiveConstraint indices=\"0\" fixedDirections=\"1 0 1 1 1 0\" projectVelocity=\"1\"/>",
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  for (int s = 0; s < 50; ++s) scene.simulation.step();
  const auto& system = scene.simulation.objects.at(0).system;
  const RigidCoord<double> c = system.rigids->coord(system.state.position, 0);
  EXPECT_EQ(c.center.x(), 1.0);
  EXPECT_EQ(c.center.z(), 3.0);
  EXPECT_LT(c.center.y(), 1.0);
  EXPECT_EQ(c.orientation.x(), 0.0);
  EXPECT_EQ(c.orientation.y(), 0.0);
  EXPECT_GT(std::abs(c.orientation.z()), 0.01);
  const std::string wrong = scene_error(
      "<EulerImplicitSolver/><CGLinearSolver/><MechanicalObject template=\"Rigid3d\" position=\"0 0 0 0 0 0 1\"/>"
      "<UniformMass totalMass=\"1\"/><PartialFixedProjectiveConstraint fixedDirections=\"1 0 1\"/>");
  EXPECT_NE(wrong.find("needs 6 values (x y z rx ry rz)"), std::string::npos) << wrong;
}

// A ConstantForceField on a carried point pushes the rigid through Jᵀ: the force on the centre and
// the torque r × F, r turning with the body. Point (0, 1, 0) pushed along x: unturned, τ = (0, 0, -1);
// turned 90° about z (r = (-1, 0, 0)), no torque. One explicit step gives v = h F / m, ω = h τ / I.
TEST(RigidInteraction, ConstantForcesOnCarriedPointsPushAndTurnTheRigid) {
  for (const bool turned : {false, true}) {
    const std::string q = turned ? "0 0 0.7071067811865476 0.7071067811865476" : "0 0 0 1";
    LoadedScene scene = build_scene_text(
        "<EulerExplicitSolver symplectic=\"1\"/><MechanicalObject template=\"Rigid3d\" position=\"0 0 0 " + q + "\"/>"
        "<UniformMass vertexMass=\"2 1 0.5 0 0 0 0.5 0 0 0 0.5\"/>"
        "<Node name=\"carried\"><MechanicalObject position=\"0 1 0\"/><ConstantForceField forces=\"1 0 0\"/><RigidMapping/></Node>",
        "dt=\"0.01\" gravity=\"0 0 0\"");
    scene.simulation.step();
    const auto& v = scene.simulation.objects.at(0).system.state.velocity;
    EXPECT_LT((v[0] - Vec3<double>(0.01 * 1 / 2, 0, 0)).norm(), 1e-15) << turned;
    const Vec3<double> expected_omega = turned ? Vec3<double>::Zero() : Vec3<double>(0, 0, -0.01 / (2 * 0.5));
    EXPECT_LT((v[1] - expected_omega).norm(), 1e-15) << turned;
  }
}

// A SpringForceField with a mapped end acts through that end's mapping. (1) A rigid pendulum hung
// from a fixed anchor by a zero-length spring on its carried pivot swings as the same pendulum held
// by a RestShapeSpringsForceField on the pivot (k d and K = k I either way). (2) A spring from a
// point under an IdentityMapping equals the spring from the point itself.
TEST(RigidInteraction, SpringsWithAMappedEndActThroughItsMapping) {
  const std::string solver = "<EulerImplicitSolver/><CGLinearSolver iterations=\"100\" tolerance=\"1e-24\" threshold=\"1e-30\"/>";
  const std::string body = "<MechanicalObject template=\"Rigid3d\" position=\"0.29552020666133955 -0.95533648912560598 0 0 0 "
                           "0.14943813247359922 0.98877107793604228\"/><UniformMass vertexMass=\"1 1 0.1 0 0 0 0.1 0 0 0 0.1\"/>";
  LoadedScene held = build_scene_text(solver + "<Node name=\"body\">" + body +
                                          "<Node name=\"carried\"><MechanicalObject position=\"0 1 0\" rest_position=\"0 0 0\"/>"
                                          "<RestShapeSpringsForceField stiffness=\"1e5\"/><RigidMapping/></Node></Node>",
                                      "dt=\"0.001\" gravity=\"0 -9.81 0\"");
  LoadedScene hung = build_scene_text(solver + "<Node name=\"body\">" + body +
                                          "<Node name=\"carried\"><MechanicalObject name=\"pivot\" position=\"0 1 0\"/><RigidMapping/></Node></Node>"
                                          "<Node name=\"anchor\"><MechanicalObject name=\"a\" position=\"0 0 0\"/><UniformMass totalMass=\"1\"/>"
                                          "<FixedProjectiveConstraint indices=\"0\"/></Node>"
                                          "<SpringForceField object1=\"@body/carried/pivot\" object2=\"@anchor/a\" indices1=\"0\" "
                                          "indices2=\"0\" length=\"0\" stiffness=\"1e5\"/>",
                                      "dt=\"0.001\" gravity=\"0 -9.81 0\"");
  for (int s = 0; s < 1500; ++s) {
    held.simulation.step();
    hung.simulation.step();
  }
  const auto& a = held.simulation.objects.at(0).system;
  const auto& b = hung.simulation.objects.at(0).system;
  const RigidCoord<double> ca = a.rigids->coord(a.state.position, 0), cb = b.rigids->coord(b.state.position, 0);
  // The two systems differ in size (the anchor's block), so CG's round-off differs: 1500 steps
  // leave them ~1e-8 apart, against a swing of 0.3.
  EXPECT_LT((ca.center - cb.center).norm(), 1e-6);
  EXPECT_LT((ca.orientation.coeffs() - cb.orientation.coeffs()).norm(), 1e-6);
  EXPECT_GT((ca.center - Vec3<double>(0.29552020666133955, -0.95533648912560598, 0)).norm(), 0.05);  // it swung

  const std::string points = "<Node name=\"p\"><MechanicalObject name=\"x\" position=\"0 0 0  1 0 0\"/><UniformMass totalMass=\"2\"/>"
                             "<FixedProjectiveConstraint indices=\"0\"/><Node name=\"m\"><MechanicalObject name=\"y\" position=\"0 0 0  1 0 0\"/>"
                             "<IdentityMapping/></Node></Node>"
                             "<Node name=\"q\"><MechanicalObject name=\"z\" position=\"2 1 0\"/><UniformMass totalMass=\"1\"/></Node>";
  const auto run = [&](const std::string& from) {
    LoadedScene scene = build_scene_text(solver + points + "<SpringForceField object1=\"" + from + "\" object2=\"@q/z\" indices1=\"1\" "
                                         "indices2=\"0\" length=\"0.5\" stiffness=\"30\" damping=\"0.5\"/>",
                                         "dt=\"0.01\" gravity=\"0 -9.81 0\"");
    for (int s = 0; s < 100; ++s) scene.simulation.step();
    return scene.simulation.objects.at(0).system.state.position;
  };
  const auto direct = run("@p/x"), mapped = run("@p/m/y");
  ASSERT_EQ(direct.size(), mapped.size());
  for (std::size_t i = 0; i < direct.size(); ++i) EXPECT_LT((direct[i] - mapped[i]).norm(), 1e-12) << i;
}

TEST(RigidInteraction, BadInputIsRefusedInOneLine) {
  const std::string solver = "<EulerImplicitSolver/><CGLinearSolver/>";
  const std::string rigid = "<MechanicalObject name=\"dofs\" template=\"Rigid3d\" position=\"0 0 0 0 0 0 1\"/><UniformMass totalMass=\"1\"/>";
  const std::string directions = scene_error(solver + rigid + "<RestShapeSpringsForceField activeDirections=\"1 1 1\"/>");
  EXPECT_NE(directions.find("6 (x y z rx ry rz) for Rigid3"), std::string::npos) << directions;
  const std::string index = scene_error(solver + "<Node name=\"a\">" + rigid + "</Node><Node name=\"b\">" + rigid +
                                        "</Node><SpringForceField object1=\"@a/dofs\" object2=\"@b/dofs\" "
                                        "indices1=\"1\" indices2=\"0\" length=\"1\" stiffness=\"1\"/>");
  EXPECT_NE(index.find("out of range [0, 1) of object1"), std::string::npos) << index;
  const std::string external = scene_error(solver + rigid + "<RestShapeSpringsForceField external_rest_shape=\"@.\"/>");
  EXPECT_NE(external.find("external_rest_shape is not supported on rigid bodies"), std::string::npos) << external;
}

TEST(RigidInteraction, AStateMappedOntoPointsOfTwoRigidsFollowsThemInAMergedObject) {
  // A free point first (so the rigids' blocks do not start at 0 once merged), then two spinning
  // rigids carrying a tetrahedron's corners (two each) and, below, a state mapped barycentrically
  // onto that tetrahedron: each of its points mixes both rigids (the corners weigh and hold a weak FEM, so the corners
  // node is folded into the rigids and its own mapped nodes follow it).
  const std::string scene =
      "<Node name=\"all\"><EulerImplicitSolver/><CGLinearSolver iterations=\"100\" tolerance=\"1e-20\" threshold=\"1e-20\"/>"
      "<Node name=\"point\"><MechanicalObject name=\"point\" position=\"9 9 9\"/><UniformMass totalMass=\"1\"/></Node>"
      "<Node name=\"bodies\"><MechanicalObject name=\"frames\" template=\"Rigid3d\" position=\"0 0 0 0 0 0 1  1 0 0 0 0 0 1\" "
      "velocity=\"0 0 0 0 0 2  0 1 0 1 0 0\"/><UniformMass totalMass=\"1\"/>"
      "<Node name=\"corners\"><MeshTopology name=\"tet\" position=\"0 0 0  0 1 0  1 0 0  1 0 1\" tetrahedra=\"0 1 2 3\"/>"
      "<MechanicalObject name=\"corners\"/><UniformMass totalMass=\"0.4\"/><TetrahedronFEMForceField youngModulus=\"10\" poissonRatio=\"0.3\"/><RigidMapping globalToLocalCoords=\"1\" rigidIndexPerPoint=\"0 0 1 1\"/>"
      "<Node name=\"inside\"><MechanicalObject name=\"inside\" position=\"0.25 0.25 0.25  0.5 0.2 0.3\"/>"
      "<BarycentricMapping/></Node></Node></Node></Node>";
  LoadedScene loaded = build_scene_text(scene, "dt=\"0.01\" gravity=\"0 0 0\"");
  for (int s = 0; s < 20; ++s) loaded.simulation.step();
  std::vector<Vec3<double>> corners, inside;
  for (const auto& state : state_snapshots(loaded.simulation.objects.at(0))) {
    if (state.name == "corners") corners = state.position;
    if (state.name == "inside") inside = state.position;
  }
  ASSERT_EQ(corners.size(), 4u);
  ASSERT_EQ(inside.size(), 2u);
  EXPECT_GT((corners[2] - Vec3<double>(1, 0, 0)).norm(), 0.1) << "the second rigid moved its corners";
  // The barycentric weights of the rest points, (1 - a - b - c, a, b, c) in the tetrahedron's frame.
  const Vec3<double> rest[2] = {Vec3<double>(0.25, 0.25, 0.25), Vec3<double>(0.5, 0.2, 0.3)};
  const Vec3<double> p0(0, 0, 0), p1(0, 1, 0), p2(1, 0, 0), p3(1, 0, 1);
  Mat3<double> edges;
  edges << p1 - p0, p2 - p0, p3 - p0;
  for (int i = 0; i < 2; ++i) {
    const Vec3<double> f = edges.inverse() * (rest[i] - p0);
    const Vec3<double> expected = (1 - f.sum()) * corners[0] + f[0] * corners[1] + f[1] * corners[2] + f[2] * corners[3];
    EXPECT_LT((inside[static_cast<std::size_t>(i)] - expected).norm(), 1e-12) << i;
  }
}

}  // namespace
}  // namespace fastcorot
