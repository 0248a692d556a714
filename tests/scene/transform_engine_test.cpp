// TransformEngine (src/scene/transform_engine.cpp) read through the scene's data, against
// transforms worked out here on their own: SOFA's TransformEngine.inl (master 2a278d891f) scales,
// then turns by the Euler angles (createQuaterFromEuler's default order: R = Rz Ry Rx, angles in
// degrees), then by the quaternion, then translates; inverse runs the inverse steps backwards. The
// expected rotations are Eigen AngleAxis products, not the quaternion formulas of the code.
#include "scene/scene_data.h"

#include "fastcorot/core/error.h"

#include "../support/scene_data_text.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <string>

namespace fastcorot::scene_detail {
namespace {

using Data = testing::SceneDataText;
using Eigen::AngleAxisd;
using Eigen::Vector3d;

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

// Rz(c) Ry(b) Rx(a) for SOFA's rotation="a b c" in degrees.
Eigen::Matrix3d euler(double a, double b, double c) {
  return (AngleAxisd(radians(c), Vector3d::UnitZ()) * AngleAxisd(radians(b), Vector3d::UnitY()) *
          AngleAxisd(radians(a), Vector3d::UnitX()))
      .toRotationMatrix();
}

// A number written with all its digits.
std::string text(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  return out.str();
}

Vector3d point(const Numbers& values, std::size_t i) { return {values[3 * i], values[3 * i + 1], values[3 * i + 2]}; }

std::string error_of(const std::string& body, const std::string& component, const std::string& name) {
  try {
    Data data(body);
    data(component, name);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

const std::string kPoints = "1 2 3  -0.5 0.25 4  0 0 0";
const Vector3d kInput[3] = {{1, 2, 3}, {-0.5, 0.25, 4}, {0, 0, 0}};

TEST(TransformEngine, ScalesThenRotatesByEulerAnglesThenTranslates) {
  Data data("<TransformEngine name=\"t\" input_position=\"" + kPoints +
            "\" scale=\"2 3 0.5\" rotation=\"30 45 60\" translation=\"1 -2 3\"/>");
  const Numbers out = data("t", "output_position");
  ASSERT_EQ(out.size(), 9u);
  const Eigen::Matrix3d r = euler(30, 45, 60);
  for (std::size_t i = 0; i < 3; ++i) {
    const Vector3d expected = r * kInput[i].cwiseProduct(Vector3d(2, 3, 0.5)) + Vector3d(1, -2, 3);
    EXPECT_LT((point(out, i) - expected).norm(), 1e-12) << "point " << i;
  }
}

TEST(TransformEngine, InverseUndoesTheStepsInTheOppositeOrder) {
  // The inverse of x -> R (s x) + t is y -> s^-1 R^T (y - t).
  Data data("<TransformEngine name=\"t\" input_position=\"" + kPoints +
            "\" scale=\"2 3 0.5\" rotation=\"30 45 60\" translation=\"1 -2 3\" inverse=\"true\"/>"
            "<TransformEngine name=\"there\" input_position=\"" + kPoints +
            "\" scale=\"2 3 0.5\" rotation=\"30 45 60\" translation=\"1 -2 3\"/>"
            "<TransformEngine name=\"back\" input_position=\"@there.output_position\""
            " scale=\"2 3 0.5\" rotation=\"30 45 60\" translation=\"1 -2 3\" inverse=\"1\"/>");
  const Numbers out = data("t", "output_position");
  const Numbers back = data("back", "output_position");
  const Eigen::Matrix3d r = euler(30, 45, 60);
  for (std::size_t i = 0; i < 3; ++i) {
    const Vector3d expected = (r.transpose() * (kInput[i] - Vector3d(1, -2, 3))).cwiseQuotient(Vector3d(2, 3, 0.5));
    EXPECT_LT((point(out, i) - expected).norm(), 1e-12) << "point " << i;
    EXPECT_LT((point(back, i) - kInput[i]).norm(), 1e-12) << "point " << i;
  }
}

TEST(TransformEngine, QuaternionTurnsAfterTheEulerAngles) {
  // A unit quaternion about (1, 2, 3) by 0.7 rad, written qx qy qz qw, with and without Euler angles
  // (which do not commute with it: the order shows).
  const Eigen::Quaterniond q(AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()));
  const std::string quaternion = text(q.x()) + " " + text(q.y()) + " " + text(q.z()) + " " + text(q.w());
  Data data("<TransformEngine name=\"q\" input_position=\"" + kPoints + "\" quaternion=\"" + quaternion + "\"/>"
            "<TransformEngine name=\"both\" input_position=\"" + kPoints + "\" quaternion=\"" + quaternion +
            "\" rotation=\"90 0 0\" translation=\"0 0 1\"/>");
  const Numbers alone = data("q", "output_position");
  const Numbers both = data("both", "output_position");
  const Eigen::Matrix3d r = AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT((point(alone, i) - r * kInput[i]).norm(), 1e-12) << "point " << i;
    const Vector3d expected = r * (euler(90, 0, 0) * kInput[i]) + Vector3d(0, 0, 1);
    EXPECT_LT((point(both, i) - expected).norm(), 1e-12) << "point " << i;
    const Vector3d wrong_order = euler(90, 0, 0) * (r * kInput[i]) + Vector3d(0, 0, 1);
    if (i < 2) {
      EXPECT_GT((point(both, i) - wrong_order).norm(), 0.1) << "point " << i;
    }
  }
}

TEST(TransformEngine, QuaternionIsUsedAsWrittenAndInvertedNormalised) {
  // q = (0, 0, 1, 1), not normalised. SOFA's rotation v + 2w (q×v) + 2 q×(q×v) takes (1, 0, 0) to
  // (1, 0, 0) + (0, 2, 0) + (-2, 0, 0) = (-1, 2, 0). Its inverse is the normalised conjugate, a
  // quarter turn about -z: (1, 0, 0) -> (0, -1, 0).
  Data data("<TransformEngine name=\"q\" input_position=\"1 0 0\" quaternion=\"0 0 1 1\"/>"
            "<TransformEngine name=\"inv\" input_position=\"1 0 0\" quaternion=\"0 0 1 1\" inverse=\"true\"/>");
  const Numbers q = data("q", "output_position");
  EXPECT_DOUBLE_EQ(q[0], -1);
  EXPECT_DOUBLE_EQ(q[1], 2);
  EXPECT_DOUBLE_EQ(q[2], 0);
  const Numbers inv = data("inv", "output_position");
  EXPECT_NEAR(inv[0], 0, 1e-15);
  EXPECT_NEAR(inv[1], -1, 1e-15);
  EXPECT_NEAR(inv[2], 0, 1e-15);
}

TEST(TransformEngine, StepsWithinSofasThresholdOfTheIdentityAreSkipped) {
  // SOFA compares scale with (1, 1, 1) at 1e-6: 1 + 1e-7 is the identity, 1 + 1e-5 is not.
  Data data("<TransformEngine name=\"same\" input_position=\"3 5 7\" scale=\"1.0000001 1 1\"/>"
            "<TransformEngine name=\"scaled\" input_position=\"3 5 7\" scale=\"1.00001 1 1\"/>"
            "<TransformEngine name=\"none\" input_position=\"3 5 7\"/>");
  EXPECT_EQ(data("same", "output_position"), (Numbers{3, 5, 7}));
  EXPECT_EQ(data("scaled", "output_position"), (Numbers{3 * 1.00001, 5, 7}));
  EXPECT_EQ(data("none", "output_position"), (Numbers{3, 5, 7}));
}

TEST(TransformEngine, Rigid3CentresMoveAndOrientationsTurn) {
  // A rigid at (1, 0, 0), turned 30 degrees about x: scale 2 (centre only), a quarter turn about z,
  // then up by 1 along z. Centre (2, 0, 0) -> (0, 2, 0) -> (0, 2, 1); orientation Rz(90) Rx(30).
  const Eigen::Quaterniond start(AngleAxisd(radians(30), Vector3d::UnitX()));
  Data data("<TransformEngine name=\"t\" template=\"Rigid3d\" input_position=\"1 0 0 " + text(start.x()) + " 0 0 " +
            text(start.w()) + "\" scale=\"2 2 2\" rotation=\"0 0 90\" translation=\"0 0 1\"/>");
  const Numbers out = data("t", "output_position");
  ASSERT_EQ(out.size(), 7u);
  EXPECT_NEAR(out[0], 0, 1e-15);
  EXPECT_NEAR(out[1], 2, 1e-15);
  EXPECT_NEAR(out[2], 1, 1e-15);
  const Eigen::Quaterniond expected(AngleAxisd(radians(90), Vector3d::UnitZ()) * AngleAxisd(radians(30), Vector3d::UnitX()));
  EXPECT_NEAR(out[3], expected.x(), 1e-15);
  EXPECT_NEAR(out[4], expected.y(), 1e-15);
  EXPECT_NEAR(out[5], expected.z(), 1e-15);
  EXPECT_NEAR(out[6], expected.w(), 1e-15);
}

TEST(TransformEngine, Vec2PointsTurnInTheirPlane) {
  // (1, 2) scaled by 2 -> (2, 4), a quarter turn about z -> (-4, 2).
  Data data("<TransformEngine name=\"t\" template=\"Vec2d\" input_position=\"1 2\" scale=\"2 2 2\" rotation=\"0 0 90\"/>");
  const Numbers out = data("t", "output_position");
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out[0], -4, 1e-15);
  EXPECT_NEAR(out[1], 2, 1e-15);
}

TEST(TransformEngine, FeedsAStateAndATopologyFromALoader) {
  // InextensiblePendulum.scn's form: a StringMeshCreator's points (x / 2 along x for 3 points)
  // moved by (0, 0, -2), read by a topology and, through it, the state; TorusFall.scn's: a state's
  // position linked to the engine's output.
  Data data("<StringMeshCreator name=\"loader\" resolution=\"3\"/>"
            "<TransformEngine name=\"translate\" input_position=\"@loader.position\" translation=\"0 0 -2\"/>"
            "<EdgeSetTopologyContainer name=\"topology\" position=\"@translate.output_position\" edges=\"@loader.edges\"/>"
            "<MechanicalObject name=\"dofs\"/>"
            "<MechanicalObject name=\"linked\" position=\"@translate.output_position\" rotation=\"0 0 90\"/>");
  const Numbers expected = {0, 0, -2, 0.5, 0, -2, 1, 0, -2};
  EXPECT_EQ(data("topology", "position"), expected);
  EXPECT_EQ(data("dofs", "position"), expected);
  const Numbers linked = data("linked", "position");  // the state's own rotation still applies
  ASSERT_EQ(linked.size(), 9u);
  EXPECT_NEAR(linked[3], 0, 1e-15);
  EXPECT_NEAR(linked[4], 0.5, 1e-15);
  EXPECT_NEAR(linked[5], -2, 1e-15);
}

TEST(TransformEngine, BadInputIsAnErrorNamingTheEngine) {
  const std::string sizes = error_of("<TransformEngine name=\"t\" input_position=\"1 2 3 4\"/>", "t", "output_position");
  EXPECT_NE(sizes.find("TransformEngine 't'"), std::string::npos) << sizes;
  EXPECT_NE(sizes.find("input_position"), std::string::npos) << sizes;
  const std::string rigid = error_of("<TransformEngine name=\"t\" template=\"Rigid3d\" input_position=\"1 2 3\"/>", "t",
                                     "output_position");
  EXPECT_NE(rigid.find("7 numbers"), std::string::npos) << rigid;
  const std::string quaternion = error_of("<TransformEngine name=\"t\" input_position=\"1 2 3\" quaternion=\"0 0 1\"/>",
                                          "t", "output_position");
  EXPECT_NE(quaternion.find("quaternion"), std::string::npos) << quaternion;
  const std::string tmpl = error_of("<TransformEngine name=\"t\" template=\"Rigid2d\" input_position=\"1 2 3\"/>", "t",
                                    "output_position");
  EXPECT_NE(tmpl.find("Rigid2d"), std::string::npos) << tmpl;
  const std::string zero = error_of("<TransformEngine name=\"t\" input_position=\"1 2 3\" scale=\"0 1 1\" inverse=\"1\"/>",
                                    "t", "output_position");
  EXPECT_NE(zero.find("zero scale"), std::string::npos) << zero;
  const std::string rotation = error_of("<TransformEngine name=\"t\" input_position=\"1 2 3\" rotation=\"0 90\"/>", "t",
                                        "output_position");
  EXPECT_NE(rotation.find("rotation"), std::string::npos) << rotation;
}

}  // namespace
}  // namespace fastcorot::scene_detail
