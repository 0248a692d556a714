// SpringForceField and MeshSpringForceField's springs, against the spring law written out here
// (SOFA's SpringForceField: f = (ks (d - L) + kd U.w) U), finite differences of its energy and of
// its forces, and the spring list worked out by hand for two tetrahedra.
#include "fastcorot/fem/spring_force_field.h"

#include "fastcorot/core/error.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using testing::fd_gradient;
using testing::fd_jacobian;

std::shared_ptr<TetMesh> two_tets() {
  return std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{{0, 1, 2, 3}, {0, 2, 1, 4}});
}
Points two_tets_rest() {
  return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -2}};
}
Points deformed() {
  return {{0.05, -0.02, 0.01}, {1.1, 0.03, -0.04}, {-0.02, 0.94, 0.05}, {0.03, 0.02, 1.2}, {0.1, -0.05, -1.8}};
}

Eigen::VectorXd flat(const Points& p) {
  Eigen::VectorXd v(3 * static_cast<Eigen::Index>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i) v.segment<3>(3 * static_cast<Eigen::Index>(i)) = p[i];
  return v;
}
Points points(const Eigen::VectorXd& v) {
  Points p(static_cast<std::size_t>(v.size() / 3));
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = v.segment<3>(3 * static_cast<Eigen::Index>(i));
  return p;
}

TEST(MeshSprings, TetrahedraGiveEachEdgeOnceInSofasOrderWithStiffnessOverLength) {
  MeshSpringParameters<double> p;
  p.tetrahedra_stiffness = 10;
  p.tetrahedra_damping = 2;
  const Points rest = two_tets_rest();
  const auto springs = mesh_springs<double>(*two_tets(), rest, p);
  // Tetrahedron 0: 0-1 0-2 0-3 1-2 1-3 2-3; tetrahedron 1 (0 2 1 4) adds 0-4, 2-4, 1-4.
  const std::vector<std::pair<Index, Index>> expected = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}, {0, 4}, {2, 4}, {1, 4}};
  ASSERT_EQ(springs.size(), expected.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    EXPECT_EQ(springs[s].a, expected[s].first);
    EXPECT_EQ(springs[s].b, expected[s].second);
    const double length = (rest[static_cast<std::size_t>(expected[s].second)] - rest[static_cast<std::size_t>(expected[s].first)]).norm();
    EXPECT_DOUBLE_EQ(springs[s].rest_length, length);
    EXPECT_DOUBLE_EQ(springs[s].stiffness, 10 / length);
    EXPECT_DOUBLE_EQ(springs[s].damping, 2 / length);
  }
  // Lines come first and are not repeated by the tetrahedra.
  p.lines_stiffness = 3;
  const auto both = mesh_springs<double>(*two_tets(), rest, p);
  EXPECT_EQ(both.size(), expected.size());
  EXPECT_DOUBLE_EQ(both[0].stiffness * both[0].rest_length, 3);
  MeshSpringParameters<double> none;
  EXPECT_TRUE(mesh_springs<double>(*two_tets(), rest, none).empty());
}

TEST(SpringForceField, OneSpringByHand) {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  SpringForceField<double> field(mesh, {{0, 1, 100.0, 0.0, 1.0, false}});
  Points x = {{0, 0, 0}, {0, 2, 0}, {5, 0, 0}, {0, 0, 5}};
  Points f(4, Vec3<double>::Zero());
  field.add_force(x, f);
  // Stretched by 1 along +y: 100 N pulls point 0 up and point 1 down.
  EXPECT_NEAR(f[0].y(), 100, 1e-12);
  EXPECT_NEAR(f[1].y(), -100, 1e-12);
  EXPECT_NEAR(f[0].x(), 0, 1e-12);
  EXPECT_NEAR(field.potential_energy(x), 50, 1e-12);
  // The tangent: ks along the spring, f/d = 50 across it.
  const Eigen::MatrixXd k(field.stiffness_matrix());
  EXPECT_NEAR(k(4, 1), 100, 1e-12);   // df_1y / dx_0y
  EXPECT_NEAR(k(3, 0), 50, 1e-12);    // df_1x / dx_0x
  EXPECT_NEAR(k(0, 0), -50, 1e-12);
}

TEST(SpringForceField, ForceIsMinusTheEnergyGradientAndTheTangentItsJacobian) {
  MeshSpringParameters<double> p;
  p.tetrahedra_stiffness = 40;
  auto mesh = two_tets();
  SpringForceField<double> field(mesh, mesh_springs<double>(*mesh, two_tets_rest(), p), 0.0);
  const Points x = deformed();
  Points f(5, Vec3<double>::Zero());
  field.add_force(x, f);
  const auto energy = [&](const Eigen::VectorXd& y) { return field.potential_energy(points(y)); };
  EXPECT_LT((flat(f) + fd_gradient(energy, flat(x), 1e-6)).cwiseAbs().maxCoeff(), 1e-7);
  SpringForceField<double> probe(mesh, field.springs());
  const auto force = [&](const Eigen::VectorXd& y) {
    Points g(5, Vec3<double>::Zero());
    probe.add_force_only(points(y), g);
    return flat(g);
  };
  const Eigen::MatrixXd k(field.stiffness_matrix());
  EXPECT_LT((k - fd_jacobian(force, flat(x), 1e-6)).cwiseAbs().maxCoeff(), 1e-6);
  // add_dforce is the same matrix, with the Rayleigh factor added in.
  SpringForceField<double> damped(mesh, field.springs(), 0.25);
  Points g(5, Vec3<double>::Zero());
  damped.add_force(x, g);
  const Points dx = {{0.1, 0.2, -0.3}, {0.0, 1.0, 0.5}, {-0.2, 0.1, 0.0}, {0.3, 0.3, 0.3}, {1.0, -1.0, 0.0}};
  Points df(5, Vec3<double>::Zero());
  damped.add_dforce(dx, df, 2.0, 4.0);  // factor 2 + 4 * 0.25 = 3
  EXPECT_LT((flat(df) - 3 * k * flat(dx)).cwiseAbs().maxCoeff(), 1e-12);
  std::vector<Mat3<double>> diagonal(5, Mat3<double>::Zero());
  field.add_diagonal_blocks(diagonal, 1.0);
  for (Eigen::Index i = 0; i < 5; ++i) EXPECT_LT((diagonal[static_cast<std::size_t>(i)] - k.block<3, 3>(3 * i, 3 * i)).norm(), 1e-12);
}

TEST(SpringForceField, DampingActsOnTheRelativeVelocityAlongTheSpring) {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  SpringForceField<double> field(mesh, {{0, 1, 0.0, 3.0, 1.0, false}});
  const Points x = {{0, 0, 0}, {1, 0, 0}, {5, 0, 0}, {0, 0, 5}};
  const Points v = {{0, 0, 0}, {2, 7, 0}, {0, 0, 0}, {0, 0, 0}};  // 2 along the spring, 7 across
  Points f(4, Vec3<double>::Zero());
  field.set_velocity(v);
  field.add_force(x, f);
  EXPECT_NEAR(f[0].x(), 6, 1e-12);
  EXPECT_NEAR(f[1].x(), -6, 1e-12);
  EXPECT_NEAR(f[1].y(), 0, 1e-12);
  // Without velocities, no damping force.
  Points g(4, Vec3<double>::Zero());
  field.set_velocity({});
  field.add_force(x, g);
  EXPECT_EQ(g[0].x(), 0);
}

TEST(SpringForceField, ElongationOnlySpringsDoNotPush) {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  SpringForceField<double> field(mesh, {{0, 1, 10.0, 0.0, 1.0, true}});
  const Points x = {{0, 0, 0}, {0.5, 0, 0}, {5, 0, 0}, {0, 0, 5}};
  Points f(4, Vec3<double>::Zero());
  field.add_force(x, f);
  EXPECT_EQ(f[0].norm(), 0);
  EXPECT_EQ(Eigen::MatrixXd(field.stiffness_matrix()).norm(), 0);
  EXPECT_EQ(field.potential_energy(x), 0);
}

TEST(SpringForceField, DisabledSpringsActNot) {
  // SOFA's `enabled` = false: a broken spring gives no force, no tangent, no energy.
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  Spring<double> broken{0, 1, 10.0, 1.0, 1.0, false, false};
  SpringForceField<double> field(mesh, {broken});
  const Points x = {{0, 0, 0}, {3, 0, 0}, {5, 0, 0}, {0, 0, 5}};
  Points f(4, Vec3<double>::Zero());
  field.add_force(x, f);
  EXPECT_EQ(f[0].norm(), 0);
  EXPECT_EQ(Eigen::MatrixXd(field.stiffness_matrix()).norm(), 0);
  EXPECT_EQ(field.potential_energy(x), 0);
}

TEST(SpringForceField, OnlyTheAssembledSpringsEnterTheMatrixButAllActInTheProduct) {
  // RegularGridSpringForceField's springs beyond its listed ones: add_dforce has them, the matrix not
  // (SOFA's SpringForceField::addKToMatrix loops over its listed springs only).
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  SpringForceField<double> field(mesh, {{0, 1, 100.0, 0.0, 1.0, false}, {2, 3, 50.0, 0.0, 1.0, false}});
  const Points x = {{0, 0, 0}, {0, 2, 0}, {5, 0, 0}, {5, 0, 3}};
  Points f(4, Vec3<double>::Zero());
  field.add_force(x, f);
  const Eigen::MatrixXd all(field.stiffness_matrix());
  field.set_assembled_springs(1);
  const Eigen::MatrixXd first(field.stiffness_matrix());
  EXPECT_NEAR(first(4, 1), 100, 1e-12);                       // spring 0's ks along y
  EXPECT_EQ(first.block(6, 6, 6, 6).norm(), 0);              // spring 1 absent
  EXPECT_NEAR(all(11, 8), 50, 1e-12);                        // but in the full matrix
  const Points dx = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 1}};
  Points df(4, Vec3<double>::Zero());
  field.add_dforce(dx, df, 1.0);
  EXPECT_NEAR(df[3].z(), -50, 1e-12);                        // the product keeps spring 1
  std::vector<Mat3<double>> diagonal(4, Mat3<double>::Zero());
  field.add_diagonal_blocks(diagonal, 1.0);
  EXPECT_EQ(diagonal[3].norm(), 0);
  EXPECT_THROW(field.set_assembled_springs(3), Error);
}

TEST(SpringForceField, BadSpringsAndTopologicalChangesAreRefused) {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  EXPECT_THROW(SpringForceField<double>(mesh, {{0, 4, 1.0, 0.0, 1.0, false}}), Error);
  EXPECT_THROW(SpringForceField<double>(mesh, {{2, 2, 1.0, 0.0, 1.0, false}}), Error);
  EXPECT_THROW(SpringForceField<double>(mesh, {{0, 1, -1.0, 0.0, 1.0, false}}), Error);
  EXPECT_THROW(SpringForceField<double>(mesh, {{0, 1, 1.0, 0.0, 1.0, false}}, -1.0), Error);
  SpringForceField<double> field(mesh, {{0, 1, 1.0, 0.0, 1.0, false}});
  const std::vector<Tetrahedron> more = {{0, 1, 2, 3}};
  EXPECT_THROW(field.check_new_tetrahedra(more), Error);
  try {
    SpringForceField<double>(mesh, {{0, 9, 1.0, 0.0, 1.0, false}}, 0.0, "MeshSpringForceField");
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("MeshSpringForceField: spring 0 (0, 9): index out of range"), std::string::npos);
  }
}

}  // namespace
}  // namespace fastcorot
