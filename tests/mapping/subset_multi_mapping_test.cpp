// SubsetMultiMapping (mapping/subset_multi_mapping.h) over inputs that mix a simulated state's own
// points, a barycentric-like linear mapping and points carried by a rigid body: its positions
// against the points worked out directly (c + R p for carried points), J against central finite
// differences of apply, Jᵀ against J by the dot-product test, J's row blocks against apply_j,
// velocities against J v; bad index pairs refused naming indexPairs.
#include "fastcorot/mapping/subset_multi_mapping.h"

#include "fastcorot/core/error.h"

#include "../support/block_vectors.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

using V3 = Vec3<double>;

// Six blocks: plain points at 0, 1, 2 and 5, one rigid at blocks 3 (centre) and 4 (rotation offset).
struct System {
  std::shared_ptr<RigidBlocks<double>> frames = std::make_shared<RigidBlocks<double>>();
  std::vector<V3> x{V3(0, 0, 0), V3(1, 0.2, 0), V3(0.3, 1, -0.4), V3(2, -1, 0.5), V3(0, 0, 0), V3(-1, 2, 3)};
  const Eigen::Quaterniond q{Eigen::AngleAxisd(1.1, V3(1, -2, 0.5).normalized())};
  const std::vector<V3> local{V3(1, 0, 0), V3(0, 2, -1), V3(0.5, -0.5, 0.25)};
  System() {
    frames->block = {3};
    frames->orientation = {q};
    frames->rest_orientation = frames->orientation;
  }
  // Input 0: the plain points 0, 1, 2, 5; input 1: three points the rigid carries; input 2: the
  // midpoints of (0, 1) and (2, 5).
  std::unique_ptr<SubsetMultiMapping<double>> mapping() const {
    std::vector<std::unique_ptr<MechanicalMapping<double>>> inputs;
    const std::vector<Index> own{0, 1, 2, 5};
    inputs.push_back(std::make_unique<LinearMapping<double>>(PointMapping<double>::subset(own)));
    RigidPoints<double> carried;
    carried.frames = frames;
    carried.local = local;
    carried.rigid = {0, 0, 0};
    inputs.push_back(std::make_unique<RigidPointMapping<double>>(carried));
    PointMapping<double> mid = PointMapping<double>::subset(std::vector<Index>{0, 2});
    mid.vertices[0][1] = 1;
    mid.vertices[1][1] = 5;
    mid.weights[0][0] = mid.weights[0][1] = 0.5;
    mid.weights[1][0] = mid.weights[1][1] = 0.5;
    inputs.push_back(std::make_unique<LinearMapping<double>>(mid));
    return std::make_unique<SubsetMultiMapping<double>>(std::move(inputs), kPairs);
  }
  static inline const std::vector<std::pair<std::size_t, Index>> kPairs{{1, 0}, {0, 2}, {2, 0}, {1, 2}, {0, 3}, {1, 1}, {2, 1}, {0, 0}};
};

using testing::dot;
using testing::random_vectors;

TEST(SubsetMultiMapping, EachPointIsThePickedPointOfItsInput) {
  System s;
  auto map = s.mapping();
  ASSERT_EQ(map->size(), 8u);
  std::vector<V3> y(8);
  map->apply(s.x, y);
  const auto carried = [&](int i) { V3 c = s.x[3] + s.q * s.local[static_cast<std::size_t>(i)]; return c; };
  const std::vector<V3> expected{carried(0), s.x[2], 0.5 * (s.x[0] + s.x[1]), carried(2), s.x[5], carried(1), 0.5 * (s.x[2] + s.x[5]), s.x[0]};
  for (std::size_t i = 0; i < 8; ++i) EXPECT_LT((y[i] - expected[i]).norm(), 1e-14) << i;
  std::vector<V3> again(8);
  map->positions(s.x, again);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(again[i], y[i]) << i;
  EXPECT_EQ(map->parent_extent(), 6);
}

TEST(SubsetMultiMapping, JacobianIsTheDerivativeOfApply) {
  System s;
  auto map = s.mapping();
  std::vector<V3> y(8), jdx(8), plus(8), minus(8);
  map->apply(s.x, y);
  const auto dx = random_vectors(6, 4);
  map->apply_j(dx, jdx);
  // An angular increment is a rotation offset in block 4, which apply reads as SOFA's x += dx.
  const double eps = 1e-6;
  std::vector<V3> xp = s.x, xm = s.x;
  for (std::size_t b = 0; b < 6; ++b) xp[b] += eps * dx[b], xm[b] -= eps * dx[b];
  auto other = s.mapping();
  other->apply(xp, plus);
  other->apply(xm, minus);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_LT(((plus[i] - minus[i]) / (2 * eps) - jdx[i]).norm(), 1e-8) << i;
}

TEST(SubsetMultiMapping, TransposeRowBlocksAndVelocitiesAgreeWithJ) {
  System s;
  auto map = s.mapping();
  std::vector<V3> y(8), jdx(8);
  map->apply(s.x, y);
  const auto dx = random_vectors(6, 9), f = random_vectors(8, 10);
  map->apply_j(dx, jdx);
  std::vector<V3> jtf(6, V3::Zero());
  map->apply_jt(f, jtf);
  EXPECT_NEAR(dot(jdx, f), dot(dx, jtf), 1e-13);
  // Jᵀ adds to what is there, and a second call gives the same sum (its gather starts from zero).
  std::vector<V3> twice(6, V3::Zero());
  map->apply_jt(f, twice);
  map->apply_jt(f, twice);
  for (std::size_t b = 0; b < 6; ++b) EXPECT_LT((twice[b] - 2 * jtf[b]).norm(), 1e-14) << b;
  std::vector<std::pair<Index, Mat3<double>>> row;
  for (std::size_t i = 0; i < 8; ++i) {
    map->row_blocks(i, row);
    V3 sum = V3::Zero();
    for (const auto& [p, block] : row) sum += block * dx[static_cast<std::size_t>(p)];
    EXPECT_LT((sum - jdx[i]).norm(), 1e-14) << i;
  }
  std::vector<V3> v(8);
  map->velocities(s.x, dx, v);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_LT((v[i] - jdx[i]).norm(), 1e-14) << i;
}

TEST(SubsetMultiMapping, PairsOutOfRangeAreRefusedNamingIndexPairs) {
  const auto message = [](std::size_t input, Index point) {
    std::vector<std::unique_ptr<MechanicalMapping<double>>> inputs;
    inputs.push_back(std::make_unique<LinearMapping<double>>(PointMapping<double>::identity(3)));
    try {
      SubsetMultiMapping<double> map(std::move(inputs), {{0, 1}, {input, point}});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(1, 0).find("indexPairs: point 1 takes input 1, there are 1 inputs"), std::string::npos) << message(1, 0);
  EXPECT_NE(message(0, 3).find("takes point 3 of input 0, which has 3 points"), std::string::npos) << message(0, 3);
  EXPECT_NE(message(0, -1).find("takes point -1"), std::string::npos) << message(0, -1);
}

}  // namespace
}  // namespace fastcorot
