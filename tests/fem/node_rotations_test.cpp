// node_rotations: SOFA's TetrahedronFEMForceField::getRotations, checked on rigid motions, where
// every element's rotation from its rest frame is the motion's rotation, whatever the method's
// frame: a point gets the mean of the rotations of its tetrahedra.
#include "fastcorot/fem/node_rotations.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

Mat3<double> turn(double angle, const Vec3<double>& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

TEST(NodeRotations, MeanOfTheRigidRotationsOfEachPointsTetrahedra) {
  // Two tetrahedra sharing point 0 at the origin, each turned rigidly about it by its own rotation;
  // point 7 is in none.
  const Points rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {5, 5, 5}};
  auto mesh = std::make_shared<TetMesh>(8, std::vector<Tetrahedron>{{0, 1, 2, 3}, {0, 4, 6, 5}});
  const Mat3<double> qa = turn(0.7, {1, 2, 3}), qb = turn(-0.4, {0, 1, -1});
  Points x = rest;
  for (int i = 1; i <= 3; ++i) x[static_cast<std::size_t>(i)] = qa * rest[static_cast<std::size_t>(i)];
  for (int i = 4; i <= 6; ++i) x[static_cast<std::size_t>(i)] = qb * rest[static_cast<std::size_t>(i)];
  for (auto method : {TetrahedronFEMMethod::large, TetrahedronFEMMethod::polar, TetrahedronFEMMethod::svd}) {
    TetrahedronFEMForceField<double>::Parameters p;
    p.method = method;
    TetrahedronFEMForceField<double> field(mesh, rest, p);
    Points f(8, Vec3<double>::Zero());
    field.add_force(x, f);
    const auto r = node_rotations<double>(field, 8);
    ASSERT_EQ(r.size(), 8u);
    EXPECT_LT((r[0] - 0.5 * (qa + qb)).norm(), 1e-12) << to_string(method);  // not re-orthogonalised
    EXPECT_LT((r[2] - qa).norm(), 1e-12) << to_string(method);
    EXPECT_LT((r[5] - qb).norm(), 1e-12) << to_string(method);
    EXPECT_EQ(r[7], Mat3<double>::Identity());
    EXPECT_THROW(node_rotations<double>(field, 6), Error);  // the mesh names point 6
  }
  TetrahedronFEMForceField<double>::Parameters small;
  small.method = TetrahedronFEMMethod::small;
  TetrahedronFEMForceField<double> field(mesh, rest, small);
  Points f(8, Vec3<double>::Zero());
  field.add_force(x, f);
  EXPECT_EQ(node_rotations<double>(field, 8)[2], Mat3<double>::Identity());
}

}  // namespace
}  // namespace fastcorot
