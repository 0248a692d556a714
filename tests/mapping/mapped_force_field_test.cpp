// A force field on a mapped state acting on its parent (MappedForceField): springs on a subset of
// the points are the same springs written on the parent's points; on barycentrically mapped
// points, the forces are minus the gradient of the mapped energy E(J x), the products and the
// assembled matrix are the finite differences of the forces, and the diagonal blocks are the
// assembled matrix's.
#include "fastcorot/mapping/mapped_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/spring_force_field.h"

#include "../support/deformations.h"
#include "../support/finite_difference.h"

#include <gtest/gtest.h>

#include <random>

namespace fastcorot {
namespace {

using testing::flatten;
using testing::unflatten;

std::vector<Vec3<double>> random_points(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3<double>> p(n);
  for (auto& v : p) v = {u(rng), u(rng), u(rng)};
  return p;
}

std::shared_ptr<ForceField<double>> springs(Index points, const std::vector<std::array<Index, 2>>& pairs) {
  std::vector<Spring<double>> list;
  for (const auto& [a, b] : pairs) list.push_back({a, b, 100.0 + a + 2 * b, 0, 0.5 + 0.1 * a, false, true});
  return std::make_shared<SpringForceField<double>>(std::make_shared<TetMesh>(points, std::vector<Tetrahedron>{}), list);
}

std::vector<Vec3<double>> force(ForceField<double>& field, const std::vector<Vec3<double>>& x) {
  std::vector<Vec3<double>> f(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  return f;
}

TEST(MappedForceField, SpringsOnASubsetAreTheSpringsOnTheParentsPoints) {
  const std::vector<Index> subset = {5, 2, 7, 0};
  MappedForceField<double> mapped(springs(4, {{0, 1}, {1, 2}, {2, 3}, {0, 3}}), PointMapping<double>::subset(subset), 8);
  // The same springs on the parent's points (stiffness and rest length as the mapped ones have them).
  std::vector<Spring<double>> list;
  for (const auto& [a, b] : std::vector<std::array<Index, 2>>{{0, 1}, {1, 2}, {2, 3}, {0, 3}}) {
    list.push_back({subset[static_cast<std::size_t>(a)], subset[static_cast<std::size_t>(b)], 100.0 + a + 2 * b, 0, 0.5 + 0.1 * a, false, true});
  }
  auto direct = std::make_shared<SpringForceField<double>>(std::make_shared<TetMesh>(8, std::vector<Tetrahedron>{}), list);
  const auto x = random_points(8, 1), dx = random_points(8, 2);
  const auto f_mapped = force(mapped, x), f_direct = force(*direct, x);
  std::vector<Vec3<double>> df_mapped(8, Vec3<double>::Zero()), df_direct(8, Vec3<double>::Zero());
  mapped.add_dforce(dx, df_mapped, 0.7);
  direct->add_dforce(dx, df_direct, 0.7);
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_LT((f_mapped[i] - f_direct[i]).norm(), 1e-12) << i;
    EXPECT_LT((df_mapped[i] - df_direct[i]).norm(), 1e-12) << i;
  }
  EXPECT_LT((Eigen::MatrixXd(mapped.stiffness_matrix(0.7)) - Eigen::MatrixXd(direct->stiffness_matrix(0.7))).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_NEAR(mapped.potential_energy(x), direct->potential_energy(x), 1e-12);
  EXPECT_EQ(mapped.mesh().num_points(), 8);
}

// Six mapped points, each a barycentric combination of four of nine parents (weights outside
// [0, 1] included), with springs between them.
MappedForceField<double> barycentric_springs() {
  PointMapping<double> map;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 0.6);
  for (Index i = 0; i < 6; ++i) {
    std::array<Index, 8> v{};
    std::array<double, 8> w{};
    for (std::size_t k = 0; k < 4; ++k) {
      v[k] = (i + 2 * static_cast<Index>(k)) % 9;
      w[k] = u(rng);
    }
    w[3] = 1 - w[0] - w[1] - w[2];
    map.vertices.push_back(v);
    map.weights.push_back(w);
  }
  return MappedForceField<double>(springs(6, {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {0, 5}, {1, 4}}), map, 9);
}

TEST(MappedForceField, ForcesAreMinusTheGradientOfTheMappedEnergy) {
  auto mapped = barycentric_springs();
  const Eigen::VectorXd x = flatten(random_points(9, 3));
  const Eigen::VectorXd gradient =
      testing::fd_gradient([&](const Eigen::VectorXd& y) { return mapped.potential_energy(unflatten(y)); }, x, 1e-6);
  const Eigen::VectorXd f = flatten(force(mapped, unflatten(x)));
  EXPECT_LT(testing::relative_error(f, Eigen::VectorXd(-gradient)), 1e-7);
}

TEST(MappedForceField, ProductsAndMatrixAreTheDerivativesOfTheForces) {
  auto mapped = barycentric_springs();
  const auto x = random_points(9, 4);
  const Eigen::MatrixXd fd = testing::fd_jacobian(
      [&](const Eigen::VectorXd& y) { return flatten(force(mapped, unflatten(y))); }, flatten(x), 1e-6);
  force(mapped, x);  // linearise at x
  const Eigen::MatrixXd k = Eigen::MatrixXd(mapped.stiffness_matrix(1.0));
  EXPECT_LT(testing::relative_error(k, fd), 1e-7);
  const auto dx = random_points(9, 5);
  std::vector<Vec3<double>> df(9, Vec3<double>::Zero());
  mapped.add_dforce(dx, df, 2.0);
  EXPECT_LT(testing::relative_error(flatten(df), Eigen::VectorXd(2.0 * k * flatten(dx))), 1e-12);
  std::vector<Mat3<double>> diagonal(9, Mat3<double>::Zero());
  mapped.add_diagonal_blocks(diagonal, 1.0);
  for (Index p = 0; p < 9; ++p) {
    EXPECT_LT((diagonal[static_cast<std::size_t>(p)] - k.block<3, 3>(3 * p, 3 * p)).cwiseAbs().maxCoeff(), 1e-9) << p;
  }
}

TEST(MappedForceField, AMappingThatDoesNotFitIsRefused) {
  EXPECT_THROW(MappedForceField<double>(springs(3, {{0, 1}}), PointMapping<double>::subset(std::vector<Index>{0, 1}), 4), Error);
  EXPECT_THROW(MappedForceField<double>(springs(2, {{0, 1}}), PointMapping<double>::subset(std::vector<Index>{0, 4}), 4), Error);
  MappedForceField<double> field(springs(2, {{0, 1}}), PointMapping<double>::subset(std::vector<Index>{0, 1}), 2);
  EXPECT_THROW(field.check_new_tetrahedra(std::vector<Tetrahedron>{{0, 1, 0, 1}}), Error);
}

}  // namespace
}  // namespace fastcorot
