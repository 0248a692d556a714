// SOFA's RigidMapping<Rigid3, Vec3> (RigidMapping.inl). References: the closed form y = c + R p
// with R from Eigen's AngleAxis; SOFA's RigidMapping_test cases (one rigid at (1, -2, 3) turned by
// rotationEuler(-1, 2, -3) = Rz(-3) Ry(2) Rx(-1), the unit tetrahedron's vertices as local points,
// and as world points for a rigid starting at (-3, 1, -2) turned by rotationEuler(3, -1, 2));
// central finite differences of apply through integrate for J; the adjoint identity for Jᵀ.
#include "fastcorot/mapping/rigid_mapping.h"

#include "fastcorot/core/error.h"

#include "../support/error_text.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

using Quat = Eigen::Quaterniond;
using V3 = Vec3<double>;
using M3 = Mat3<double>;

using testing::contains;
using testing::error_of;

M3 euler_zyx(double x, double y, double z) {  // SOFA's rotationEuler(x, y, z)
  return (Eigen::AngleAxisd(z, V3::UnitZ()) * Eigen::AngleAxisd(y, V3::UnitY()) * Eigen::AngleAxisd(x, V3::UnitX()))
      .toRotationMatrix();
}

RigidCoord<double> rigid(const V3& c, const M3& r) {
  RigidCoord<double> x;
  x.center = c;
  x.orientation = Quat(r);
  return x;
}

const std::vector<V3> tetrahedron = {V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)};

TEST(RigidMapping, SofaTestLocalCoordinates) {
  const M3 r = euler_zyx(-1, 2, -3);
  const std::vector<RigidCoord<double>> rigids = {rigid(V3(1, -2, 3), r)};
  RigidMapping<double> mapping("RigidMapping", rigids, tetrahedron, {}, {});  // globalToLocalCoords false
  const std::vector<V3> y = mapping.apply(rigids);
  ASSERT_EQ(y.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((y[i] - (V3(1, -2, 3) + r * tetrahedron[i])).norm(), 1e-14);
}

TEST(RigidMapping, SofaTestWorldCoordinates) {
  const M3 r0 = euler_zyx(3, -1, 2);
  const M3 r = euler_zyx(-1, 2, -3);
  const std::vector<RigidCoord<double>> start = {rigid(V3(-3, 1, -2), r0)};
  RigidMappingOptions<double> options;
  options.global_to_local_coords = true;
  RigidMapping<double> mapping("RigidMapping", start, tetrahedron, {}, options);
  for (std::size_t i = 0; i < 4; ++i) {
    const V3 local = r0.transpose() * (tetrahedron[i] - V3(-3, 1, -2));
    EXPECT_LT((mapping.local_points()[i] - local).norm(), 1e-14);
  }
  // At the start the points are where they were.
  const std::vector<V3> y0 = mapping.apply(start);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((y0[i] - tetrahedron[i]).norm(), 1e-14);
  const std::vector<RigidCoord<double>> moved = {rigid(V3(1, -2, 3), r)};
  const std::vector<V3> y = mapping.apply(moved);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_LT((y[i] - (V3(1, -2, 3) + r * r0.transpose() * (tetrahedron[i] - V3(-3, 1, -2)))).norm(), 1e-13);
  }
}

TEST(RigidMapping, LocalPointsSources) {
  const std::vector<RigidCoord<double>> rigids = {rigid(V3(5, 0, 0), M3::Identity()),
                                                  rigid(V3(0, 5, 0), euler_zyx(0, 0, 1))};
  const std::vector<V3> child = {V3(1, 1, 1), V3(2, 2, 2)};
  const std::vector<V3> rest = {V3(0, 0, 1), V3(0, 1, 0)};
  // initialPoints win over the child's positions and are never converted.
  RigidMappingOptions<double> given;
  given.initial_points = std::vector<V3>{V3(1, 0, 0)};
  given.global_to_local_coords = true;
  RigidMapping<double> a("m", rigids, child, rest, given);
  ASSERT_EQ(a.size(), 1u);  // SOFA resizes the child to the initial points
  EXPECT_EQ(a.local_points()[0], V3(1, 0, 0));
  // useX0: the child's rest positions, as they are.
  RigidMappingOptions<double> x0;
  x0.use_x0 = true;
  x0.global_to_local_coords = true;
  RigidMapping<double> b("m", rigids, child, rest, x0);
  EXPECT_EQ(b.local_points()[1], V3(0, 1, 0));
  // index from the end, rigidIndexPerPoint.
  RigidMappingOptions<double> from_end;
  from_end.index_from_end = true;
  RigidMapping<double> c("m", rigids, child, rest, from_end);
  EXPECT_EQ(c.rigid_of_point()[0], 1);
  RigidMappingOptions<double> per_point;
  per_point.rigid_index_per_point = {1, 0};
  per_point.global_to_local_coords = true;
  RigidMapping<double> d("m", rigids, child, rest, per_point);
  EXPECT_EQ(d.rigid_of_point()[0], 1);
  EXPECT_LT((d.local_points()[0] - euler_zyx(0, 0, 1).transpose() * V3(1, -4, 1)).norm(), 1e-14);
  EXPECT_EQ(d.local_points()[1], V3(-3, 2, 2));
}

TEST(RigidMapping, ErrorsNameTheMappingAndIndex) {
  const std::vector<RigidCoord<double>> rigids(2);
  const std::vector<V3> child(3, V3::Zero());
  const std::string where = "scene.scn:12 RigidMapping";
  RigidMappingOptions<double> wrong_size;
  wrong_size.rigid_index_per_point = {0, 1};
  std::string e = error_of([&] { RigidMapping<double>(where, rigids, child, {}, wrong_size); });
  EXPECT_TRUE(contains(e, where + ": rigidIndexPerPoint has 2 entries for 3 mapped points")) << e;
  RigidMappingOptions<double> out_of_range;
  out_of_range.rigid_index_per_point = {0, 2, 1};
  e = error_of([&] { RigidMapping<double>(where, rigids, child, {}, out_of_range); });
  EXPECT_TRUE(contains(e, "rigidIndexPerPoint[1] = 2 is out of range [0, 2)")) << e;
  RigidMappingOptions<double> index;
  index.index = 5;
  e = error_of([&] { RigidMapping<double>(where, rigids, child, {}, index); });
  EXPECT_TRUE(contains(e, where + ": index 5 is out of range")) << e;
  e = error_of([&] { RigidMapping<double>(where, {}, child, {}, {}); });
  EXPECT_TRUE(contains(e, "no rigid")) << e;
  RigidMapping<double> ok(where, rigids, child, {}, {});
  const std::vector<RigidCoord<double>> three(3);
  e = error_of([&] { ok.apply(three); });
  EXPECT_TRUE(contains(e, where + ": apply for 3 rigids")) << e;
}

struct Fixture {
  std::vector<RigidCoord<double>> rigids;
  std::vector<V3> points;
  RigidMappingOptions<double> options;

  Fixture() {
    rigids = {rigid(V3(0.3, -0.2, 1.0), euler_zyx(0.4, -0.7, 1.9)), rigid(V3(-1, 2, 0.5), euler_zyx(-2.2, 0.3, 0.1))};
    points = {V3(0.5, -0.1, 0.2), V3(-0.3, 0.8, 1.1), V3(1.2, 0.4, -0.6), V3(0.0, -0.9, 0.3), V3(0.7, 0.7, 0.7)};
    options.rigid_index_per_point = {0, 1, 1, 0, 1};
  }
};

std::vector<V3> random_blocks(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<V3> v(n);
  for (V3& b : v) b = V3(u(rng), u(rng), u(rng));
  return v;
}

TEST(RigidMapping, ApplyJMatchesFiniteDifferencesThroughIntegrate) {
  Fixture f;
  RigidMapping<double> mapping("m", f.rigids, f.points, {}, f.options);
  std::mt19937 rng(7);
  const std::vector<V3> dv = random_blocks(4, rng);
  const std::vector<V3> jv = mapping.apply_j(dv);
  // Central differences of apply along the rigid motion x ⊕ (±ε dv) (SOFA's x += dx).
  const double eps = 1e-6;
  auto moved = [&](double s) {
    std::vector<RigidCoord<double>> x = f.rigids;
    for (std::size_t k = 0; k < x.size(); ++k) integrate(x[k], V3(s * dv[2 * k]), V3(s * dv[2 * k + 1]));
    RigidMapping<double> probe = mapping;
    return probe.apply(x);
  };
  const std::vector<V3> plus = moved(eps), minus = moved(-eps);
  for (std::size_t i = 0; i < jv.size(); ++i) {
    const V3 fd = (plus[i] - minus[i]) / (2 * eps);
    EXPECT_LT((fd - jv[i]).norm(), 1e-8 * (1 + jv[i].norm())) << "point " << i;
  }
}

TEST(RigidMapping, ApplyJTIsTheAdjointOfApplyJ) {
  Fixture f;
  RigidMapping<double> mapping("m", f.rigids, f.points, {}, f.options);
  std::mt19937 rng(11);
  const std::vector<V3> v = random_blocks(4, rng);
  const std::vector<V3> u = random_blocks(5, rng);
  const std::vector<V3> jv = mapping.apply_j(v);
  std::vector<V3> jtu(4, V3::Zero());
  mapping.apply_jt(u, jtu);
  double left = 0, right = 0;
  for (std::size_t i = 0; i < u.size(); ++i) left += u[i].dot(jv[i]);
  for (std::size_t k = 0; k < v.size(); ++k) right += jtu[k].dot(v[k]);
  EXPECT_NEAR(left, right, 1e-13 * (std::abs(left) + 1));
  // It accumulates.
  std::vector<V3> twice = jtu;
  mapping.apply_jt(u, twice);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_LT((twice[k] - 2 * jtu[k]).norm(), 1e-14);
}

TEST(RigidMapping, SparseJacobianEqualsApplyJColumnByColumn) {
  Fixture f;
  RigidMapping<double> mapping("m", f.rigids, f.points, {}, f.options);
  const auto j = mapping.jacobian();
  ASSERT_EQ(j.rows(), 15);
  ASSERT_EQ(j.cols(), 12);
  const Eigen::MatrixXd dense(j);
  for (int c = 0; c < 12; ++c) {
    std::vector<V3> e(4, V3::Zero());
    e[std::size_t(c / 3)][c % 3] = 1;
    const std::vector<V3> column = mapping.apply_j(e);
    for (int r = 0; r < 15; ++r) EXPECT_EQ(dense(r, c), column[std::size_t(r / 3)][r % 3]) << r << ", " << c;
  }
  EXPECT_EQ(j.nonZeros(), 45);  // 3 entries a row
}

TEST(RigidMapping, JacobianFollowsTheLastApply) {
  Fixture f;
  RigidMapping<double> mapping("m", f.rigids, f.points, {}, f.options);
  std::vector<RigidCoord<double>> x = f.rigids;
  integrate(x[1], V3(0.1, 0, 0), V3(0.5, -0.3, 0.2));
  const std::vector<V3> y = mapping.apply(x);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const std::size_t k = std::size_t(mapping.rigid_of_point()[i]);
    EXPECT_LT((mapping.rotated_points()[i] - (y[i] - x[k].center)).norm(), 1e-14);
  }
}

TEST(RigidMapping, Float) {
  const std::vector<RigidCoord<float>> rigids(1);
  const std::vector<Vec3<float>> child = {Vec3<float>(1, 0, 0)};
  RigidMapping<float> mapping("m", rigids, child, {}, {});
  const std::vector<Vec3<float>> dv = {Vec3<float>::Zero(), Vec3<float>(0, 0, 1)};
  EXPECT_EQ(mapping.apply_j(dv)[0], Vec3<float>(0, 1, 0));  // ω × r = z × x = y
}

}  // namespace
}  // namespace fastcorot
