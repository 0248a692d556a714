// Packed: four values in one SIMD register, loaded from and stored to any address, with lane-wise
// arithmetic that gives the scalar results exactly.
#include "fastcorot/core/packed.h"

#include <gtest/gtest.h>

#include <array>

namespace fastcorot {
namespace {

template <class Real>
class PackedTest : public ::testing::Test {};
using Reals = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PackedTest, Reals);

TYPED_TEST(PackedTest, LoadsAndStoresFourValuesAtAnyOffset) {
  using Real = TypeParam;
  std::array<Real, 9> values{};
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = Real(i) + Real(0.5);
  // Offsets 1 and 3 are not aligned for a whole register.
  for (const std::size_t offset : {std::size_t(0), std::size_t(1), std::size_t(3), std::size_t(5)}) {
    const Packed<Real> v = load_packed(values.data() + offset);
    for (int lane = 0; lane < 4; ++lane) EXPECT_EQ(v[lane], values[offset + static_cast<std::size_t>(lane)]);
  }
  std::array<Real, 6> out{};
  out.fill(Real(-1));
  store_packed(out.data() + 1, Packed<Real>{Real(1), Real(2), Real(3), Real(4)});
  EXPECT_EQ(out, (std::array<Real, 6>{Real(-1), Real(1), Real(2), Real(3), Real(4), Real(-1)}));
}

TYPED_TEST(PackedTest, ArithmeticIsTheScalarArithmeticLaneByLane) {
  using Real = TypeParam;
  const Real a[4] = {Real(0.1), Real(-2.5), Real(1e7), Real(3)};
  const Real b[4] = {Real(0.7), Real(0.3), Real(1e-7), Real(-3)};
  const Real c = Real(1.0 / 3.0);
  const Packed<Real> r = load_packed(a) * load_packed(b) + broadcast(c) - load_packed(b);
  for (int lane = 0; lane < 4; ++lane) {
    const Real expected = a[lane] * b[lane] + c - b[lane];
    EXPECT_EQ(r[lane], expected) << "lane " << lane;
  }
  EXPECT_EQ(Packed<Real>{}[2], Real(0));
}

TYPED_TEST(PackedTest, PermuteReordersAndRepeatsLanes) {
  using Real = TypeParam;
  const Packed<Real> v = {Real(10), Real(11), Real(12), Real(13)};
  const Packed<Real> p = permute<2, 0, 0, 3>(v);
  const Real expected[4] = {Real(12), Real(10), Real(10), Real(13)};
  for (int lane = 0; lane < 4; ++lane) EXPECT_EQ(p[lane], expected[lane]) << "lane " << lane;
}

TYPED_TEST(PackedTest, PointsToLanesAndBackTransposes) {
  using Real = TypeParam;
  using P = Packed<Real>;
  // Point i is (10 i + 1, 10 i + 2, 10 i + 3, 10 i + 4); the fourth value must not matter.
  P points[4];
  for (int i = 0; i < 4; ++i) points[i] = P{Real(10 * i + 1), Real(10 * i + 2), Real(10 * i + 3), Real(10 * i + 4)};
  P x, y, z;
  points_to_lanes(points[0], points[1], points[2], points[3], x, y, z);
  for (int lane = 0; lane < 4; ++lane) {
    EXPECT_EQ(x[lane], Real(10 * lane + 1)) << "lane " << lane;
    EXPECT_EQ(y[lane], Real(10 * lane + 2)) << "lane " << lane;
    EXPECT_EQ(z[lane], Real(10 * lane + 3)) << "lane " << lane;
  }
  P back[4];
  lanes_to_points(x, y, z, back);
  for (int i = 0; i < 4; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(back[i][c], Real(10 * i + c + 1)) << "point " << i << ", coordinate " << c;
    EXPECT_EQ(back[i][3], Real(0)) << "point " << i;
  }
}

}  // namespace
}  // namespace fastcorot
