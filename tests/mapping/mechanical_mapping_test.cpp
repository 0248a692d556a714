// MechanicalMapping: the RigidMapping on a system's rigid blocks (RigidPointMapping) against central
// finite differences of its apply (an angular increment displaces the rigid as SOFA's x += dx does),
// Jᵀ against J by the dot-product test, J's row blocks against apply_j; a force field on carried
// points (MappedForceField through RigidPointMapping) against the same derivatives; a mass on
// carried points (RigidMappedMass) against Jᵀ M J and Jᵀ m g through the mapping.
#include "fastcorot/mapping/mapped_force_field.h"
#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/sim/rigid_mapped_mass.h"
#include "fastcorot/fem/spring_force_field.h"

#include "../support/block_vectors.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

using V3 = Vec3<double>;

// Two rigids in a system of 5 blocks: a plain point at block 0, rigids at blocks 1 and 3.
struct Rigids {
  std::shared_ptr<RigidBlocks<double>> frames = std::make_shared<RigidBlocks<double>>();
  std::vector<V3> x;
  Rigids() {
    frames->block = {1, 3};
    frames->orientation = {Eigen::Quaterniond(Eigen::AngleAxisd(0.7, V3(1, 2, 3).normalized())),
                           Eigen::Quaterniond(Eigen::AngleAxisd(-1.9, V3(-2, 0.5, 1).normalized()))};
    frames->rest_orientation = frames->orientation;
    // Between steps the angular blocks are zero (RigidBlocks::rebase): J is the derivative there.
    x = {V3(9, 9, 9), V3(1, -2, 0.5), V3(0, 0, 0), V3(-3, 1, 2), V3(0, 0, 0)};
  }
  RigidPoints<double> points() const {
    RigidPoints<double> p;
    p.frames = frames;
    p.local = {V3(1, 0, 0), V3(0, 2, -1), V3(0.5, 0.5, 0.5), V3(-1, 1, 3)};
    p.rigid = {0, 1, 0, 1};
    return p;
  }
};

using testing::dot;
using testing::random_vectors;

TEST(RigidPointMapping, JacobianIsTheDerivativeOfApply) {
  Rigids r;
  RigidPointMapping<double> map(r.points());
  std::vector<V3> y(4), plus(4), minus(4), jdx(4);
  map.apply(r.x, y);
  auto dx = random_vectors(5, 3);
  dx[0].setZero();  // block 0 is not read
  map.apply_j(dx, jdx);
  const double eps = 1e-6;
  std::vector<V3> xp = r.x, xm = r.x;
  for (std::size_t b = 0; b < 5; ++b) {
    xp[b] = r.x[b] + eps * dx[b];
    xm[b] = r.x[b] - eps * dx[b];
  }
  RigidPointMapping<double> other(r.points());
  other.apply(xp, plus);
  other.apply(xm, minus);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT(((plus[i] - minus[i]) / (2 * eps) - jdx[i]).norm(), 1e-8) << i;
  // The rotation offset is where the angular block starts from: the same positions come out
  // with the offset folded into the orientations.
  std::vector<V3> folded = xp;
  RigidBlocks<double> copy = *r.frames;
  copy.rebase(folded);
  RigidPoints<double> moved = r.points();
  moved.frames = std::make_shared<RigidBlocks<double>>(copy);
  std::vector<V3> again(4);
  moved.positions(folded, again);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((again[i] - plus[i]).norm(), 1e-14);
}

TEST(RigidPointMapping, TransposeAndRowBlocksAgreeWithJ) {
  Rigids r;
  RigidPointMapping<double> map(r.points());
  std::vector<V3> y(4), jdx(4);
  map.apply(r.x, y);
  const auto dx = random_vectors(5, 7), f = random_vectors(4, 8);
  map.apply_j(dx, jdx);
  std::vector<V3> jtf(5, V3::Zero());
  map.apply_jt(f, jtf);
  EXPECT_NEAR(dot(jdx, f), dot(dx, jtf), 1e-13);
  std::vector<std::pair<Index, Mat3<double>>> row;
  for (std::size_t i = 0; i < 4; ++i) {
    map.row_blocks(i, row);
    V3 sum = V3::Zero();
    for (const auto& [p, block] : row) sum += block * dx[static_cast<std::size_t>(p)];
    EXPECT_LT((sum - jdx[i]).norm(), 1e-14) << i;
  }
  EXPECT_EQ(map.parent_extent(), 5);
}

TEST(RigidPointMapping, SpringsOnCarriedPointsActThroughTheRigids) {
  Rigids r;
  auto springs = std::make_shared<SpringForceField<double>>(
      std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{}),
      std::vector<Spring<double>>{{0, 1, 300, 0, 1.5}, {2, 3, 200, 0, 2.5}, {1, 2, 100, 0, 0.5}});
  MappedForceField<double> field(springs, std::make_unique<RigidPointMapping<double>>(r.points()), 5);
  const auto dx = random_vectors(5, 12);
  std::vector<V3> f(5, V3::Zero()), df(5, V3::Zero());
  field.add_force(r.x, f);
  field.add_dforce(dx, df, 1.0);
  // df = K dx against central differences of the force; the rigid mapping has no geometric
  // stiffness (SOFA's default), so K is Jᵀ K_springs J: compare with the difference of Jᵀ f at
  // fixed J.
  const double eps = 1e-6;
  std::vector<V3> xp = r.x, xm = r.x;
  for (std::size_t b = 0; b < 5; ++b) xp[b] += eps * dx[b], xm[b] -= eps * dx[b];
  const auto mapped_force = [&](const std::vector<V3>& x) {
    RigidPointMapping<double> at(r.points());
    std::vector<V3> y(4), fy(4, V3::Zero());
    at.apply(x, y);
    springs->add_force_only(y, fy);
    RigidPointMapping<double> fixed_j(r.points());
    std::vector<V3> y0(4);
    fixed_j.apply(r.x, y0);
    std::vector<V3> fx(5, V3::Zero());
    fixed_j.apply_jt(fy, fx);
    return fx;
  };
  const auto fp = mapped_force(xp), fm = mapped_force(xm);
  for (std::size_t b = 0; b < 5; ++b) EXPECT_LT(((fp[b] - fm[b]) / (2 * eps) - df[b]).norm(), 1e-8 * (1 + df[b].norm() + f[b].norm())) << b;
  // The assembled blocks give the same product.
  TripletSink<double> sink;
  field.add_stiffness(sink, 1.0);
  Eigen::SparseMatrix<double> k(15, 15);
  k.setFromTriplets(sink.triplets.begin(), sink.triplets.end());
  Eigen::VectorXd d(15);
  for (std::size_t b = 0; b < 5; ++b) d.segment<3>(3 * static_cast<Eigen::Index>(b)) = dx[b];
  const Eigen::VectorXd product = k * d;
  for (std::size_t b = 0; b < 5; ++b) EXPECT_LT((product.segment<3>(3 * static_cast<Eigen::Index>(b)) - df[b]).norm(), 1e-10) << b;
}

// The straightforward form: M dx = M_own dx + Jᵀ (m ⊙ J dx), gravity = own weights + Jᵀ (w g).
TEST(RigidMappedMass, IsJTransposeMJAndCarriesTheWeightsUp) {
  Rigids r;
  std::vector<Mat3<double>> own_blocks(5, Mat3<double>::Zero());
  own_blocks[0] = 4 * Mat3<double>::Identity();  // the plain point
  own_blocks[1] = 2 * Mat3<double>::Identity();
  own_blocks[2] = Vec3<double>(0.2, 0.3, 0.4).asDiagonal();
  own_blocks[3] = 3 * Mat3<double>::Identity();
  own_blocks[4] = Vec3<double>(0.5, 0.6, 0.7).asDiagonal();
  RigidMappedMass<double> mapped;
  mapped.own = Mass<double>::block_diagonal(own_blocks);
  mapped.own.set_gravity_masses({4, 2, 0, 3, 0});
  mapped.carried.push_back({r.points(), {1.5, 0.25, 2.0, 0.75}, {1.5, 0.25, 2.0, 0.75}});
  const Mass<double> mass = mapped.at(r.x, 5);
  ASSERT_EQ(mass.couplings().size(), 2u);

  RigidPointMapping<double> map(r.points());
  std::vector<V3> y(4);
  map.apply(r.x, y);
  const auto dx = random_vectors(5, 11);
  std::vector<V3> jdx(4), expected(5, V3::Zero()), product(5);
  map.apply_j(dx, jdx);
  for (std::size_t i = 0; i < 4; ++i) jdx[i] *= mapped.carried[0].masses[i];
  map.apply_jt(jdx, expected);
  mapped.own.add_mdx(dx, expected, 1.0);
  mass.multiply(dx, product, 2.0, 1);
  for (std::size_t b = 0; b < 5; ++b) EXPECT_LT((product[b] - 2.0 * expected[b]).norm(), 1e-12 * (1 + expected[b].norm())) << b;
  // The assembled blocks are the same matrix, and symmetric.
  TripletSink<double> sink;
  mass.add_to_matrix(sink, 2.0);
  Eigen::SparseMatrix<double> m(15, 15);
  m.setFromTriplets(sink.triplets.begin(), sink.triplets.end());
  EXPECT_LT(Eigen::MatrixXd(m - Eigen::SparseMatrix<double>(m.transpose())).norm(), 1e-14);
  Eigen::VectorXd d(15);
  for (std::size_t b = 0; b < 5; ++b) d.segment<3>(3 * static_cast<Eigen::Index>(b)) = dx[b];
  const Eigen::VectorXd assembled = m * d;
  for (std::size_t b = 0; b < 5; ++b) {
    EXPECT_LT((assembled.segment<3>(3 * static_cast<Eigen::Index>(b)) - product[b]).norm(), 1e-12 * (1 + product[b].norm())) << b;
  }
  // Kinetic energy ½ vᵀ M v, and weights: own m g plus Jᵀ (w g).
  EXPECT_NEAR(mass.kinetic_energy(dx), 0.5 * dot(dx, expected), 1e-12);
  const V3 g(0.3, -9.81, 1.2);
  std::vector<V3> weights(4), expected_weight(5, V3::Zero()), weight(5, V3::Zero());
  for (std::size_t i = 0; i < 4; ++i) weights[i] = mapped.carried[0].weights[i] * g;
  map.apply_jt(weights, expected_weight);
  mapped.own.add_gravity(g, expected_weight);
  mass.add_gravity(g, weight);
  for (std::size_t b = 0; b < 5; ++b) EXPECT_LT((weight[b] - expected_weight[b]).norm(), 1e-12 * (1 + expected_weight[b].norm())) << b;
}

}  // namespace
}  // namespace fastcorot
