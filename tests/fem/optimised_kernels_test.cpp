// The optimised force field (structure of arrays, SIMD batches, scheduled scatter on threads)
// against the straightforward element-by-element reference of SPEC.md, for every rotation method,
// in float and double, on 1 and 2 threads; and bitwise equality of everything across thread counts.
// The mesh is large enough (3 parts in its scatter schedule, several SIMD batches with a ragged
// tail) for every parallel path to be taken, and its rest points are jittered so that no two
// tetrahedra share their rest data. Each check runs on the grid's own numbering and on the same mesh
// with its points and tetrahedra shuffled, which the force field renumbers internally.
#include "fastcorot/fem/corotational_force_field.h"

#include "fastcorot/topology/regular_grid.h"
#include "support/deformations.h"
#include "support/reference_element.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <tuple>
#include <vector>

namespace fastcorot {
namespace {

template <class Real>
using Points = std::vector<Vec3<Real>>;

struct Case {
  std::shared_ptr<TetMesh> mesh;
  Points<double> rest;
  Points<double> x;   // a large rotation, a stretch and noise
  Points<double> dx;  // random
};

Case make_case() {
  {
    RegularGrid grid;
    grid.n = {24, 8, 8};
    grid.min = Vec3<double>(0.0, -0.5, 0.1);
    grid.max = Vec3<double>(6.0, 1.5, 2.0);
    Case out;
    out.mesh = std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true));
    std::mt19937 rng(7);
    out.rest = testing::perturbed(grid_points<double>(grid), 0.02, rng);
    Mat3<double> stretch;
    stretch << 1.08, 0.04, 0.0, -0.03, 0.93, 0.05, 0.02, 0.0, 1.04;
    out.x = testing::perturbed(
        testing::affine_map(out.rest, testing::random_rotation(rng), stretch, Vec3<double>(0.2, 0.1, -0.4)), 0.03, rng);
    out.dx = testing::perturbed(Points<double>(out.rest.size(), Vec3<double>::Zero()), 1.0, rng);
    return out;
  }
}

// The same mesh and configurations with the points and the tetrahedra in a random order.
Case shuffled(const Case& c) {
  std::mt19937 rng(11);
  std::vector<Index> point(c.rest.size()), order(static_cast<std::size_t>(c.mesh->num_tetrahedra()));
  std::iota(point.begin(), point.end(), Index(0));
  std::iota(order.begin(), order.end(), Index(0));
  std::shuffle(point.begin(), point.end(), rng);
  std::shuffle(order.begin(), order.end(), rng);
  Case out;
  for (auto [from, to] : {std::pair{&c.rest, &out.rest}, std::pair{&c.x, &out.x}, std::pair{&c.dx, &out.dx}}) {
    to->resize(from->size());
    for (std::size_t i = 0; i < from->size(); ++i) (*to)[static_cast<std::size_t>(point[i])] = (*from)[i];
  }
  std::vector<Tetrahedron> tets;
  for (const Index t : order) {
    Tetrahedron tet = c.mesh->tetrahedron(t);
    for (Index& v : tet) v = point[static_cast<std::size_t>(v)];
    tets.push_back(tet);
  }
  out.mesh = std::make_shared<TetMesh>(c.mesh->num_points(), tets);
  return out;
}

bool g_shuffled = false;  // which case the current test uses (set by the test fixtures)

const Case& test_case() {
  static const Case grid = make_case();
  static const Case scattered = shuffled(grid);
  return g_shuffled ? scattered : grid;
}

template <class Real>
typename CorotationalForceField<Real>::Parameters parameters(RotationMethod method) {
  typename CorotationalForceField<Real>::Parameters p;
  p.young_modulus = {Real(1500)};
  p.poisson_ratio = {Real(0.35)};
  p.method = method;
  return p;
}

template <class Real>
struct Reference {
  Points<Real> force;
  Eigen::SparseMatrix<Real> stiffness;  // df/dx as SPEC assembles it
};

// Element by element, with SPEC's per-edge element (tests/support/reference_element.h).
template <class Real>
Reference<Real> reference(const TetMesh& mesh, const Points<Real>& rest, const Points<Real>& x, RotationMethod method) {
  const auto p = parameters<Real>(method);
  Reference<Real> out{Points<Real>(x.size(), Vec3<Real>::Zero()), {}};
  std::vector<Eigen::Triplet<Real>> triplets;
  auto add_block = [&](Index row, Index col, const Mat3<Real>& block) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * row + r, 3 * col + c, block(r, c));
    }
  };
  for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
    const auto& tet = mesh.tetrahedron(t);
    const auto pt = tetrahedron_points<Real>(tet, rest);
    const auto xt = tetrahedron_points<Real>(tet, x);
    const auto data = tetrahedron_rest(pt, lame_parameters(p.young_modulus[0], p.poisson_ratio[0]), method);
    const Mat3<Real> r = tetrahedron_rotation(data, xt, method);
    const auto f = testing::reference_force(data, pt, xt, r);
    for (int j = 0; j < 4; ++j) {
      out.force[static_cast<std::size_t>(tet[j])] += f[j];
      add_block(tet[j], tet[j], -(r * vertex_block(data, j) * r.transpose()));
    }
    for (int e = 0; e < 6; ++e) {
      const int k = kTetrahedronEdges[e][0], l = kTetrahedronEdges[e][1];
      const Mat3<Real> block = r * edge_block(data, e) * r.transpose();
      add_block(tet[l], tet[k], -block);
      add_block(tet[k], tet[l], -block.transpose());
    }
  }
  out.stiffness.resize(3 * mesh.num_points(), 3 * mesh.num_points());
  out.stiffness.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

template <class Real>
Eigen::Matrix<Real, Eigen::Dynamic, 1> flat(const Points<Real>& points) {
  Eigen::Matrix<Real, Eigen::Dynamic, 1> v(3 * static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) v.template segment<3>(3 * static_cast<Eigen::Index>(i)) = points[i];
  return v;
}

template <class Real>
double relative(const Points<Real>& a, const Points<Real>& b) {
  return static_cast<double>((flat(a) - flat(b)).norm() / flat(b).norm());
}

// What the field computes at the case's x, on `threads` threads.
template <class Real>
struct Results {
  Points<Real> force, force_only, dforce;
  Eigen::SparseMatrix<Real> stiffness;
  Real energy = 0;
};

template <class Real>
Results<Real> evaluate(RotationMethod method, int threads) {
  const Case& c = test_case();
  const auto rest = testing::cast_points<Real>(c.rest);
  const auto x = testing::cast_points<Real>(c.x);
  const auto dx = testing::cast_points<Real>(c.dx);
  CorotationalForceField<Real> field(c.mesh, rest, parameters<Real>(method));
  field.set_threads(threads);
  Results<Real> out;
  const Vec3<Real> offset(Real(0.5), Real(-1), Real(2));  // outputs accumulate
  out.force.assign(x.size(), offset);
  out.force_only.assign(x.size(), offset);
  out.dforce.assign(x.size(), offset);
  field.add_force_only(x, out.force_only);
  field.add_force(x, out.force);
  field.add_dforce(dx, out.dforce, Real(1.3), Real(0));
  for (auto* v : {&out.force, &out.force_only, &out.dforce}) {
    for (auto& f : *v) f -= offset;
  }
  out.stiffness = field.stiffness_matrix(Real(1));
  out.energy = field.potential_energy(x);
  return out;
}

class OptimisedKernels : public ::testing::TestWithParam<std::tuple<RotationMethod, int, bool>> {
 protected:
  void SetUp() override { g_shuffled = std::get<2>(GetParam()); }
};

template <class Real>
void check_against_reference(RotationMethod method, int threads, double tolerance) {
  SCOPED_TRACE(std::string(sizeof(Real) == 4 ? "float" : "double") + ", " + to_string(method) + ", " +
               std::to_string(threads) + " thread(s)");
  const Case& c = test_case();
  const auto ref = reference<Real>(*c.mesh, testing::cast_points<Real>(c.rest), testing::cast_points<Real>(c.x), method);
  const Results<Real> got = evaluate<Real>(method, threads);
  EXPECT_LT(relative(got.force, ref.force), tolerance);
  EXPECT_LT(relative(got.force_only, ref.force), tolerance);
  const Eigen::Matrix<Real, Eigen::Dynamic, 1> expected_df = Real(1.3) * (ref.stiffness * flat(testing::cast_points<Real>(c.dx)));
  EXPECT_LT(static_cast<double>((flat(got.dforce) - expected_df).norm() / expected_df.norm()), tolerance);
  const Eigen::SparseMatrix<Real> difference = got.stiffness - ref.stiffness;
  EXPECT_LT(static_cast<double>(difference.norm() / ref.stiffness.norm()), tolerance);
  EXPECT_EQ(got.stiffness.nonZeros(), ref.stiffness.nonZeros());
}

TEST_P(OptimisedKernels, DoubleMatchesTheReference) {
  const auto [method, threads, shuffled] = GetParam();
  check_against_reference<double>(method, threads, 1e-12);
}

TEST_P(OptimisedKernels, FloatMatchesTheFloatReference) {
  const auto [method, threads, shuffled] = GetParam();
  check_against_reference<float>(method, threads, 2e-5);
}

template <class Real>
void check_bitwise_across_threads(RotationMethod method, int threads) {
  SCOPED_TRACE(std::string(sizeof(Real) == 4 ? "float" : "double") + ", " + std::to_string(threads) + " threads");
  const Results<Real> one = evaluate<Real>(method, 1);
  const Results<Real> many = evaluate<Real>(method, threads);
  EXPECT_TRUE(one.force == many.force);
  EXPECT_TRUE(one.force_only == many.force_only);
  EXPECT_TRUE(one.dforce == many.dforce);
  EXPECT_EQ(one.energy, many.energy);
  const Eigen::SparseMatrix<Real> difference = one.stiffness - many.stiffness;
  EXPECT_EQ(difference.cwiseAbs().sum(), Real(0));
  // add_force_only and add_force share their arithmetic: the same bits.
  EXPECT_TRUE(one.force == one.force_only);
}

class OptimisedKernelsThreads : public ::testing::TestWithParam<RotationMethod> {};

TEST_P(OptimisedKernelsThreads, BitwiseTheSameOnAnyThreadCount) {
  for (const bool shuffled : {false, true}) {
    g_shuffled = shuffled;
    SCOPED_TRACE(shuffled ? "shuffled" : "grid order");
    for (int threads : {2, 3}) {
      check_bitwise_across_threads<double>(GetParam(), threads);
      check_bitwise_across_threads<float>(GetParam(), threads);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllMethods, OptimisedKernelsThreads,
                         ::testing::Values(RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2,
                                           RotationMethod::none),
                         [](const auto& info) { return to_string(info.param); });

INSTANTIATE_TEST_SUITE_P(MethodsAndThreads, OptimisedKernels,
                         ::testing::Combine(::testing::Values(RotationMethod::qr, RotationMethod::polar,
                                                              RotationMethod::polar2, RotationMethod::none),
                                            ::testing::Values(1, 2), ::testing::Bool()),
                         [](const auto& info) {
                           return to_string(std::get<0>(info.param)) + "_" + std::to_string(std::get<1>(info.param)) +
                                  "threads" + (std::get<2>(info.param) ? "_shuffled" : "");
                         });

// The cases exercise what they are meant to: several schedule parts and groups; the force field's
// own point order for the shuffled mesh only.
TEST(OptimisedKernels, TheTestMeshIsCutIntoSeveralPartsAndRenumberedWhenShuffled) {
  for (const bool shuffled : {false, true}) {
    g_shuffled = shuffled;
    const Case& c = test_case();
    const CorotationalForceField<double> field(c.mesh, c.rest, parameters<double>(RotationMethod::qr));
    EXPECT_EQ(field.renumbers_points(), shuffled);
  }
  g_shuffled = false;
  const Case& c = test_case();
  const ScatterSchedule schedule = make_scatter_schedule<4>(c.mesh->num_points(), c.mesh->tetrahedra());
  EXPECT_GE(schedule.parts, 4);
  EXPECT_GE(schedule.phase_begin[1] - schedule.phase_begin[0], 2);
  EXPECT_GE(schedule.phase_begin[2] - schedule.phase_begin[1], 2);
}

}  // namespace
}  // namespace fastcorot
