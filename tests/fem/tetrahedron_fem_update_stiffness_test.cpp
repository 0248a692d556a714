// TetrahedronFEMForceField's updateStiffnessMatrix (SOFA: J recomputed at each addForce from the
// element's current positions in its frame, polar and svd): J must be that of the current shape
// (the J a `small` element built on those points has), and the force and tangent the dense
// R J K J^T products written here with it.
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fastcorot {
namespace {

using Field = TetrahedronFEMForceField<double>;
using Points = std::vector<Vec3<double>>;

TEST(TetrahedronFEMUpdateStiffness, JIsThatOfTheCurrentShapeAndForcesUseIt) {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const Points rest = {{0, 10, 0}, {10, 0, 0}, {-5, 0, 8.66}, {-5, 0, -8.66}};  // SOFA's oneTetrahedron
  const Points x = {{0, 10, 0}, {11.5, -0.4, 0.3}, {-4.2, 1.1, 9.5}, {-6.1, -0.8, -8.0}};
  for (auto method : {TetrahedronFEMMethod::polar, TetrahedronFEMMethod::svd}) {
    Field::Parameters p;
    p.method = method;
    p.young_modulus = {6};
    p.update_stiffness_matrix = true;
    Field field(mesh, rest, p);
    Points f(4, Vec3<double>::Zero());
    field.add_force(x, f);
    const Mat3<double> rotation = field.element(0).rotation;  // element frame to world
    Points shape(4);
    for (std::size_t i = 0; i < 4; ++i) shape[i] = rotation.transpose() * x[i];
    Field::Parameters small = p;
    small.method = TetrahedronFEMMethod::small;
    small.update_stiffness_matrix = false;
    const Eigen::Matrix<double, 12, 6> j = Field(mesh, shape, small).strain_displacement(0);
    EXPECT_LT((field.strain_displacement(0) - j).norm(), 1e-12 * j.norm()) << to_string(method);
    // f_i = R (J K J^T D)_i with D = rest in the element's rest frame - current in its frame.
    Eigen::Matrix<double, 12, 1> d;
    for (int i = 0; i < 4; ++i) d.segment<3>(3 * i) = field.element(0).rotated_rest[static_cast<std::size_t>(i)] - shape[static_cast<std::size_t>(i)];
    const Eigen::Matrix<double, 12, 1> local = j * (field.material_matrix(0) * (j.transpose() * d));
    for (int i = 0; i < 4; ++i) {
      const Vec3<double> expected = rotation * local.segment<3>(3 * i);
      EXPECT_LT((f[static_cast<std::size_t>(i)] - expected).norm(), 1e-10 * local.norm()) << to_string(method) << " " << i;
    }
    // The tangent: df = -R J K J^T R^T dx.
    const Points dx = {{0.1, -0.2, 0.3}, {0.0, 0.4, -0.1}, {-0.3, 0.1, 0.2}, {0.2, 0.2, -0.2}};
    Points df(4, Vec3<double>::Zero());
    field.add_dforce(dx, df, 1.0);
    Eigen::Matrix<double, 12, 1> u;
    for (int i = 0; i < 4; ++i) u.segment<3>(3 * i) = rotation.transpose() * dx[static_cast<std::size_t>(i)];
    const Eigen::Matrix<double, 12, 1> k = j * (field.material_matrix(0) * (j.transpose() * u));
    for (int i = 0; i < 4; ++i) {
      EXPECT_LT((df[static_cast<std::size_t>(i)] + rotation * k.segment<3>(3 * i)).norm(), 1e-10 * k.norm()) << to_string(method);
    }
    // Without the update, J stays the rest shape's.
    Field::Parameters fixed_j = p;
    fixed_j.update_stiffness_matrix = false;
    Field plain(mesh, rest, fixed_j);
    Points g(4, Vec3<double>::Zero());
    plain.add_force(x, g);
    EXPECT_GT((plain.strain_displacement(0) - j).norm(), 1e-3 * j.norm());
  }
  Field::Parameters large;
  large.update_stiffness_matrix = true;
  EXPECT_THROW(Field(mesh, rest, large), Error);
}

}  // namespace
}  // namespace fastcorot
