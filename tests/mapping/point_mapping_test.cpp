// PointMapping as a mechanical mapping: J against finite differences of apply, Jᵀ against J by the
// dot-product test, the assembled J against apply, and chains against applying one mapping after
// the other.
#include "fastcorot/mapping/point_mapping.h"

#include "fastcorot/core/error.h"

#include "../support/deformations.h"
#include "../support/finite_difference.h"

#include <gtest/gtest.h>

#include <random>

namespace fastcorot {
namespace {

using testing::flatten;
using testing::unflatten;

// A mapping of 5 points onto 7 with arbitrary weights (some negative, as outside a tetrahedron),
// repeated parents included.
PointMapping<double> some_mapping() {
  PointMapping<double> m = PointMapping<double>::subset(std::vector<Index>{3, 0, 6, 2, 2});
  m.vertices[1] = {0, 4, 5, 1, 0, 0, 0, 0};
  m.weights[1] = {0.25, 0.5, -0.125, 0.375, 0, 0, 0, 0};
  m.vertices[3] = {2, 6, 2, 0, 0, 0, 0, 0};
  m.weights[3] = {0.5, 0.25, 0.25, 0, 0, 0, 0, 0};
  return m;
}

std::vector<Vec3<double>> random_points(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3<double>> p(n);
  for (auto& v : p) v = {u(rng), u(rng), u(rng)};
  return p;
}

TEST(PointMapping, JacobianIsTheFiniteDifferenceOfApply) {
  const auto map = some_mapping();
  const auto apply = [&](const Eigen::VectorXd& x) {
    std::vector<Vec3<double>> y(map.size());
    map.apply(unflatten(x), y);
    return flatten(y);
  };
  std::mt19937 rng(3);
  const Eigen::MatrixXd fd = testing::fd_jacobian(apply, flatten(random_points(7, rng)), 1e-3);
  const Eigen::MatrixXd j = Eigen::MatrixXd(map.matrix(7));
  // The 3D Jacobian is J ⊗ I3.
  Eigen::MatrixXd j3 = Eigen::MatrixXd::Zero(15, 21);
  for (Index i = 0; i < 5; ++i) {
    for (Index p = 0; p < 7; ++p) j3.block(3 * i, 3 * p, 3, 3) = j(i, p) * Eigen::Matrix3d::Identity();
  }
  EXPECT_LT((fd - j3).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_DOUBLE_EQ(j(3, 2), 0.75);  // the repeated parent's weights summed
}

TEST(PointMapping, TransposeIsTheAdjointOfApply) {
  const auto map = some_mapping();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    const auto dx = random_points(7, rng), f = random_points(5, rng);
    std::vector<Vec3<double>> jdx(5), jtf(7, Vec3<double>::Zero());
    map.apply(dx, jdx);
    map.apply_jt(f, jtf);
    EXPECT_NEAR(flatten(f).dot(flatten(jdx)), flatten(jtf).dot(flatten(dx)), 1e-14);
  }
}

TEST(PointMapping, TransposeAccumulates) {
  const auto map = PointMapping<double>::subset(std::vector<Index>{1, 1});
  std::vector<Vec3<double>> parent(2, Vec3<double>(1, 2, 3));
  map.apply_jt(std::vector<Vec3<double>>{{1, 0, 0}, {0, 1, 0}}, parent);
  EXPECT_EQ(parent[0], Vec3<double>(1, 2, 3));
  EXPECT_EQ(parent[1], Vec3<double>(2, 3, 3));
}

TEST(PointMapping, AChainIsOneMappingAfterTheOther) {
  const auto inner = some_mapping();  // 7 → 5
  PointMapping<double> outer = PointMapping<double>::subset(std::vector<Index>{4, 1, 1});
  outer.vertices[2] = {1, 3, 0, 0, 0, 0, 0, 0};
  outer.weights[2] = {0.5, 0.5, 0, 0, 0, 0, 0, 0};
  const auto chain = outer.after(inner);
  std::mt19937 rng(7);
  const auto x = random_points(7, rng);
  std::vector<Vec3<double>> middle(5), twice(3), once(3);
  inner.apply(x, middle);
  outer.apply(middle, twice);
  chain.apply(x, once);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_LT((once[i] - twice[i]).norm(), 1e-15);
  // Point 2 depends on parents {0, 4, 5, 1} (from middle 1) and {2, 6} (from middle 3) once each.
  int used = 0;
  for (double w : chain.weights[2]) used += w != 0;
  EXPECT_EQ(used, 6);
}

TEST(PointMapping, AChainOfMoreThanEightParentsIsRefused) {
  PointMapping<double> inner = PointMapping<double>::subset(std::vector<Index>{0, 0});
  inner.vertices[0] = {0, 1, 2, 3, 4, 5, 6, 7};
  inner.vertices[1] = {8, 9, 10, 11, 12, 13, 14, 15};
  inner.weights[0].fill(0.125);
  inner.weights[1].fill(0.125);
  PointMapping<double> outer = PointMapping<double>::subset(std::vector<Index>{0});
  outer.vertices[0] = {0, 1, 0, 0, 0, 0, 0, 0};
  outer.weights[0] = {0.5, 0.5, 0, 0, 0, 0, 0, 0};
  EXPECT_THROW(outer.after(inner), Error);
}

TEST(PointMapping, WrongSizesAreRefused) {
  const auto map = some_mapping();
  std::vector<Vec3<double>> x(7), y(4), parent(7);
  EXPECT_THROW(map.apply(x, y), Error);
  EXPECT_THROW(map.apply_jt(y, parent), Error);
  EXPECT_EQ(map.parent_extent(), 7);
}

}  // namespace
}  // namespace fastcorot
