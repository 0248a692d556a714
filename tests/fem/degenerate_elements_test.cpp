// Inverted and collapsed elements during a run (docs/robustness.md, "Inverted and collapsed elements"): an
// element pushed through itself, flattened onto a plane or a line, or collapsed to a point yields
// finite forces, stiffness products, stiffness matrices and energies for every rotation method, in
// float and double. Also the rest-mesh side: both orientations of a tetrahedron are accepted as
// SOFA accepts them and give the same physics, and a degenerate rest tetrahedron is an error.
#include "fastcorot/fem/corotational_force_field.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace fastcorot {
namespace {

template <class Real>
using Points = std::vector<Vec3<Real>>;

// Two tetrahedra sharing the face (1, 2, 3), the second in the opposite orientation.
const std::vector<Tetrahedron> kTetrahedra = {{0, 1, 2, 3}, {4, 1, 3, 2}};

template <class Real>
Points<Real> rest_points() {
  return {Vec3<Real>(0, 0, 0), Vec3<Real>(1, 0, 0), Vec3<Real>(0, 1, 0), Vec3<Real>(0, 0, 1),
          Vec3<Real>(1, 1, 1)};
}

// Current configurations that no rotation frame can describe, with a name for the message.
template <class Real>
std::vector<std::pair<std::string, Points<Real>>> degenerate_configurations() {
  using V = Vec3<Real>;
  std::vector<std::pair<std::string, Points<Real>>> cases;
  cases.push_back({"vertex 3 pushed through the face (0,1,2)", {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0, 0, -1), V(1, 1, 1)}});
  cases.push_back({"mirrored (all inverted)", {V(0, 0, 0), V(-1, 0, 0), V(0, 1, 0), V(0, 0, 1), V(-1, 1, 1)}});
  cases.push_back({"vertex 3 in the plane of the face", {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0.25, 0.25, 0), V(1, 1, 1)}});
  cases.push_back({"everything in one plane", {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0.5, 0.5, 0), V(1, 1, 0)}});
  cases.push_back({"everything on one line", {V(0, 0, 0), V(1, 1, 1), V(2, 2, 2), V(-1, -1, -1), V(3, 3, 3)}});
  cases.push_back({"on a line through x0 and x1", {V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), V(0, 1, 0), V(1, 1, 1)}});
  cases.push_back({"x1 on x0", {V(0, 0, 0), V(0, 0, 0), V(0, 1, 0), V(0, 0, 1), V(1, 1, 1)}});
  cases.push_back({"all at the origin", Points<Real>(5, V(0, 0, 0))});
  cases.push_back({"all at one point", Points<Real>(5, V(0.3, -2, 7))});
  // Flattened onto random planes and lines, slightly off (round-off makes the determinant tiny
  // rather than zero, which is where an iteration can blow up).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3<double> normal = Vec3<double>(u(rng), u(rng), u(rng)).normalized();
    const Vec3<double> along = Vec3<double>(u(rng), u(rng), u(rng)).normalized();
    Points<Real> plane, line;
    for (const auto& p : rest_points<double>()) {
      const Vec3<double> moved = p + Vec3<double>(u(rng), u(rng), u(rng)) * 0.3;
      plane.push_back((moved - normal * normal.dot(moved) + normal * 1e-12 * u(rng)).template cast<Real>());
      line.push_back((along * along.dot(moved) + normal * 1e-12 * u(rng)).template cast<Real>());
    }
    cases.push_back({"random plane " + std::to_string(trial), plane});
    cases.push_back({"random line " + std::to_string(trial), line});
  }
  return cases;
}

template <class Real>
bool finite(const Points<Real>& v) {
  for (const auto& p : v) {
    if (!p.allFinite()) return false;
  }
  return true;
}

template <class Real>
class DegenerateElements : public ::testing::Test {};
using RealTypes = ::testing::Types<float, double>;
TYPED_TEST_SUITE(DegenerateElements, RealTypes);

TYPED_TEST(DegenerateElements, GiveFiniteForcesStiffnessAndEnergyForEveryMethod) {
  using Real = TypeParam;
  const Points<Real> rest = rest_points<Real>();
  for (const RotationMethod method : {RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2, RotationMethod::none}) {
    typename CorotationalForceField<Real>::Parameters parameters;
    parameters.young_modulus = {Real(1000)};
    parameters.poisson_ratio = {Real(0.3)};
    parameters.method = method;
    CorotationalForceField<Real> field(std::make_shared<TetMesh>(5, kTetrahedra), rest, parameters);
    for (const auto& [name, x] : degenerate_configurations<Real>()) {
      SCOPED_TRACE(to_string(method) + ", " + name);
      Points<Real> f(5, Vec3<Real>::Zero()), df(5, Vec3<Real>::Zero());
      field.add_force(x, f);
      EXPECT_TRUE(finite(f));
      const Points<Real> dx = {Vec3<Real>(0.1, 0, 0), Vec3<Real>(0, 0.2, 0), Vec3<Real>(0, 0, -0.1),
                               Vec3<Real>(0.05, 0.05, 0.05), Vec3<Real>(-0.1, 0.3, 0)};
      field.add_dforce(dx, df, Real(-0.7));
      EXPECT_TRUE(finite(df));
      const Eigen::SparseMatrix<Real> k = field.stiffness_matrix(Real(1));
      for (int i = 0; i < k.nonZeros(); ++i) EXPECT_TRUE(std::isfinite(k.valuePtr()[i]));
      EXPECT_TRUE(std::isfinite(field.potential_energy(x)));
      for (const auto& r : field.rotations()) EXPECT_TRUE(r.allFinite());
    }
  }
}

// What an element pushed through itself does (docs/robustness.md, "Inverted and collapsed elements"), derived by
// hand for the unit tetrahedron with vertex 3 mirrored through the face (0,1,2), x = M p with
// M = diag(1, 1, -1). qr takes its frame from the edges (0,1) and (0,2), which did not move: R = I,
// and vertex 3 is pulled back up (the linear element, `none`, likewise). polar's F = M and
// polar2's row matrix P M have reflections as polar factors (SOFA's choice), R = M: the mirrored
// element is at rest and no force un-inverts it.
TYPED_TEST(DegenerateElements, MirroredElementIsPushedBackByQrAndAtRestUnderPolar) {
  using Real = TypeParam;
  using V = Vec3<Real>;
  const Points<Real> rest = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0, 0, 1)};
  const Points<Real> mirrored = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0, 0, -1)};
  for (const RotationMethod method : {RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2, RotationMethod::none}) {
    SCOPED_TRACE(to_string(method));
    typename CorotationalForceField<Real>::Parameters parameters;
    parameters.young_modulus = {Real(1000)};
    parameters.poisson_ratio = {Real(0.3)};
    parameters.method = method;
    CorotationalForceField<Real> field(std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}}), rest, parameters);
    Points<Real> f(4, V::Zero());
    field.add_force(mirrored, f);
    ASSERT_TRUE(finite(f));
    if (method == RotationMethod::qr || method == RotationMethod::none) {
      // Displacement (0, 0, -2) of vertex 3 alone: the force on it is -K33 u = 2 K33 e_z, and K33 =
      // D_3 (SPEC.md) has (lambda' + 2 mu') s_z^2 > 0 on the z diagonal, s_3 = (0, 0, 1).
      EXPECT_GT(f[3].z(), Real(100));
      EXPECT_NEAR(f[3].x(), Real(0), Real(1e-3));
      EXPECT_NEAR(f[3].y(), Real(0), Real(1e-3));
    } else {
      for (int i = 0; i < 4; ++i) EXPECT_LT(f[i].norm(), Real(1e-3)) << "vertex " << i;
      EXPECT_NEAR(field.rotations()[0].determinant(), Real(-1), Real(1e-5));
    }
  }
}

// A collapsed element still pulls its vertices apart with `none` (R = I, the linear element): the
// force is the rest-frame stiffness applied to the displacement, whatever the configuration.
TYPED_TEST(DegenerateElements, CollapsedLinearElementPushesBack) {
  using Real = TypeParam;
  typename CorotationalForceField<Real>::Parameters parameters;
  parameters.method = RotationMethod::none;
  CorotationalForceField<Real> field(std::make_shared<TetMesh>(5, kTetrahedra), rest_points<Real>(), parameters);
  Points<Real> f(5, Vec3<Real>::Zero());
  field.add_force(Points<Real>(5, Vec3<Real>(0.2, 0.2, 0.2)), f);
  // Vertex 4 (alone in the second tetrahedron) was moved towards the others: pushed back out.
  EXPECT_GT(f[4].dot(Vec3<Real>(1, 1, 1)), Real(0));
}

// SOFA accepts either orientation of a rest tetrahedron (it divides the shape vectors by the
// signed volume and scales the moduli by |V|). Swapping two vertices flips the orientation and
// changes nothing physical for the frame-free methods and polar2 (whose frame is invariant under
// a permutation of the edges); qr takes its frame from the edges (0,1) and (0,2), which a swap
// changes, so qr is compared on a mirrored mesh below instead.
TEST(RestOrientation, SwappedVerticesGiveTheSameForcesAndStiffness) {
  const Points<double> rest = rest_points<double>();
  const Points<double> x = {Vec3<double>(0.1, 0, 0), Vec3<double>(1.2, 0.1, 0), Vec3<double>(0, 0.9, 0.2),
                            Vec3<double>(0.1, 0, 1.1), Vec3<double>(1, 1.3, 0.8)};
  for (const RotationMethod method : {RotationMethod::polar, RotationMethod::polar2, RotationMethod::none}) {
    SCOPED_TRACE(to_string(method));
    CorotationalForceField<double>::Parameters parameters;
    parameters.method = method;
    CorotationalForceField<double> a(std::make_shared<TetMesh>(5, kTetrahedra), rest, parameters);
    CorotationalForceField<double> b(
        std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{{0, 1, 3, 2}, {4, 1, 2, 3}}), rest, parameters);
    EXPECT_NEAR(a.rest_volumes()[0], -b.rest_volumes()[0], 1e-15);
    Points<double> fa(5, Vec3<double>::Zero()), fb(5, Vec3<double>::Zero());
    a.add_force(x, fa);
    b.add_force(x, fb);
    const double scale = fa[0].norm() + fa[4].norm();
    ASSERT_GT(scale, 1.0);
    for (int i = 0; i < 5; ++i) EXPECT_LT((fa[i] - fb[i]).norm(), 1e-12 * scale) << "vertex " << i;
    const Eigen::MatrixXd ka = Eigen::MatrixXd(a.stiffness_matrix()), kb = Eigen::MatrixXd(b.stiffness_matrix());
    EXPECT_LT((ka - kb).cwiseAbs().maxCoeff(), 1e-12 * ka.cwiseAbs().maxCoeff());
  }
}

// Mirroring rest and current positions (x -> -x) flips the sign of every rest volume and keeps
// each method's frame edges: forces and stiffness must come out mirrored, for all four methods.
TEST(RestOrientation, MirroredMeshGivesMirroredForcesAndStiffness) {
  const Points<double> rest = rest_points<double>();
  const Points<double> x = {Vec3<double>(0.1, 0, 0), Vec3<double>(1.2, 0.1, 0), Vec3<double>(0, 0.9, 0.2),
                            Vec3<double>(0.1, 0, 1.1), Vec3<double>(1, 1.3, 0.8)};
  const Mat3<double> mirror = Vec3<double>(-1, 1, 1).asDiagonal();
  Points<double> mirrored_rest, mirrored_x;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    mirrored_rest.push_back(mirror * rest[i]);
    mirrored_x.push_back(mirror * x[i]);
  }
  Eigen::MatrixXd big_mirror = Eigen::MatrixXd::Zero(15, 15);
  for (int i = 0; i < 5; ++i) big_mirror.block<3, 3>(3 * i, 3 * i) = mirror;
  for (const RotationMethod method : {RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2, RotationMethod::none}) {
    SCOPED_TRACE(to_string(method));
    CorotationalForceField<double>::Parameters parameters;
    parameters.method = method;
    CorotationalForceField<double> a(std::make_shared<TetMesh>(5, kTetrahedra), rest, parameters);
    CorotationalForceField<double> b(std::make_shared<TetMesh>(5, kTetrahedra), mirrored_rest, parameters);
    EXPECT_NEAR(a.rest_volumes()[1], -b.rest_volumes()[1], 1e-15);
    Points<double> fa(5, Vec3<double>::Zero()), fb(5, Vec3<double>::Zero());
    a.add_force(x, fa);
    b.add_force(mirrored_x, fb);
    const double scale = fa[0].norm() + fa[4].norm();
    ASSERT_GT(scale, 1.0);
    for (int i = 0; i < 5; ++i) EXPECT_LT((mirror * fa[i] - fb[i]).norm(), 1e-12 * scale) << "vertex " << i;
    const Eigen::MatrixXd ka = Eigen::MatrixXd(a.stiffness_matrix()), kb = Eigen::MatrixXd(b.stiffness_matrix());
    EXPECT_LT((big_mirror * ka * big_mirror - kb).cwiseAbs().maxCoeff(), 1e-12 * ka.cwiseAbs().maxCoeff());
  }
}

TEST(RestOrientation, FlatRestTetrahedronIsAnErrorNamingIt) {
  Points<double> rest = rest_points<double>();
  rest[4] = Vec3<double>(1, 1, 0);  // the second tetrahedron (4, 1, 2, 0) lies in the plane z = 0
  const std::vector<Tetrahedron> tetrahedra = {{0, 1, 2, 3}, {4, 1, 2, 0}};
  try {
    CorotationalForceField<double> field(std::make_shared<TetMesh>(5, tetrahedra), rest, {});
    FAIL() << "expected fastcorot::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("tetrahedron 1"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fastcorot
