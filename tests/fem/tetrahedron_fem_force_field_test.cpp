// TetrahedronFEMForceField against the values SOFA's own test holds (Sofa/Component/SolidMechanics/
// FEM/Elastic/tests/BaseTetrahedronFEMForceField_test.h at SOFA master 2a278d891f: a single
// tetrahedron's rest data, and a beam's state and element data after 100 steps), and against an
// independent reference: the textbook linear tetrahedron |V| B^T C B (shape gradients from the
// inverse of the edge matrix, C from the Lamé parameters) in each method's frame.
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"
#include "support/deformations.h"
#include "support/force_fields.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

namespace fastcorot {
namespace {

using testing::affine_map;
using testing::flatten;
using testing::perturbed;
using testing::random_rotation;
using Field = TetrahedronFEMForceField<double>;
using Points = std::vector<Vec3<double>>;

void expect_matrix_near(const Eigen::MatrixXd& expected, const Eigen::MatrixXd& actual, double tolerance,
                        const std::string& what) {
  ASSERT_EQ(expected.rows(), actual.rows()) << what;
  ASSERT_EQ(expected.cols(), actual.cols()) << what;
  for (Eigen::Index i = 0; i < expected.rows(); ++i) {
    for (Eigen::Index j = 0; j < expected.cols(); ++j) {
      EXPECT_NEAR(expected(i, j), actual(i, j), tolerance) << what << " (" << i << ", " << j << ")";
    }
  }
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-300);
}

// SOFA's BaseTetrahedronFEMForceField_test::checkInit: the unit tetrahedron as "2 3 1 0", E 1000,
// nu 0.3, method large. Expected values copied from that test (six significant digits, hence the
// tolerance of 1e-4 the test itself uses).
TEST(TetrahedronFEMForceField, RestDataOfSofasSingleTetrahedronTest) {
  const Points points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{2, 3, 1, 0}});
  Field::Parameters parameters;
  parameters.young_modulus = {1000};
  parameters.poisson_ratio = {0.3};
  Field field(mesh, points, parameters);
  const auto& element = field.element(0);
  Eigen::Matrix3d initial_rotation;
  initial_rotation << 0, 0.816497, 0.57735, -0.707107, -0.408248, 0.57735, 0.707107, -0.408248, 0.57735;
  expect_matrix_near(initial_rotation, element.initial_rotation, 1e-4, "initial rotation");
  expect_matrix_near(initial_rotation, element.rotation, 1e-4, "current rotation");
  Eigen::Matrix<double, 4, 3> rest;
  rest << 0, 0, 0, 1.41421, 0, 0, 0.707107, 1.22474, 0, 0.707107, 0.408248, -0.57735;
  for (int i = 0; i < 4; ++i) {
    expect_matrix_near(rest.row(i).transpose(), element.rotated_rest[static_cast<std::size_t>(i)], 1e-4,
                       "rotated rest vertex " + std::to_string(i));
  }
  Eigen::Matrix<double, 6, 6> material = Eigen::Matrix<double, 6, 6>::Zero();
  material.topLeftCorner<3, 3>().setConstant(96.1538);
  material.topLeftCorner<3, 3>().diagonal().setConstant(224.359);
  material.bottomRightCorner<3, 3>().diagonal().setConstant(64.1026);
  expect_matrix_near(material, field.material_matrix(0), 1e-3, "material stiffness");
  Eigen::Matrix<double, 12, 6> j;
  j << 0.707107, 0, 0, 0.408248, 0, -0.57735,  //
      0, 0.408248, 0, 0.707107, -0.57735, 0,   //
      0, 0, -0.57735, 0, 0.408248, 0.707107,   //
      -0.707107, 0, 0, 0.408248, 0, -0.57735,  //
      0, 0.408248, 0, -0.707107, -0.57735, 0,  //
      0, 0, -0.57735, 0, 0.408248, -0.707107,  //
      0, 0, 0, -0.816497, 0, -0.57735,         //
      0, -0.816497, 0, 0, -0.57735, 0,         //
      0, 0, -0.57735, 0, -0.816497, 0,         //
      0, 0, 0, 0, 0, 1.73205,                  //
      0, 0, 0, 0, 1.73205, 0,                  //
      0, 0, 1.73205, 0, 0, 0;
  expect_matrix_near(j, field.strain_displacement(0), 1e-4, "strain displacement");
}

// SOFA's checkFEMValues: a 4×10×4 grid over [0 0 20, 10 40 30] split by Hexa2TetraTopologicalMapping,
// E 600, nu 0.3, large, DiagonalMass density 1, the points with y in [-1, 1] fixed, gravity +10 y,
// implicit Euler with CG (20 iterations, tolerance 1e-5, threshold 1e-6), 100 steps of 0.01; SOFA's
// test reads point 159 and element 100. (SOFA's
// scene keeps the grid in the root and links the state to it; the grid is in the beam's node here,
// which gives the same points and tetrahedra.) Expected values copied from that test.
TEST(TetrahedronFEMForceField, BeamStateAndElementAfterSofasHundredSteps) {
  LoadedScene scene = build_scene(parse_scene_text(R"(<Node name="root" dt="0.01" gravity="0 10 0">
    <Node name="Beam">
      <EulerImplicitSolver/>
      <CGLinearSolver iterations="20" tolerance="1e-5" threshold="1e-6"/>
      <RegularGridTopology name="grid" n="4 10 4" min="0 0 20" max="10 40 30"/>
      <MechanicalObject name="dof"/>
      <TetrahedronSetTopologyContainer name="topo"/>
      <Hexa2TetraTopologicalMapping input="@grid" output="@topo"/>
      <BoxROI name="ROI1" box="-1 -1 0 10 1 50"/>
      <FixedProjectiveConstraint indices="@ROI1.indices"/>
      <DiagonalMass massDensity="1.0"/>
      <TetrahedronFEMForceField youngModulus="600" poissonRatio="0.3" method="large"/>
    </Node>
  </Node>)",
                                                   "sofa_fem_values.scn"));
  auto& object = scene.simulation.objects.at(0);
  ASSERT_EQ(object.system.size(), 160);
  EXPECT_EQ(object.system.state.position[159], Vec3<double>(10, 40, 30));
  for (int step = 0; step < 100; ++step) scene.simulation.step();
  const Vec3<double>& moved = object.system.state.position[159];
  EXPECT_NEAR(moved.x(), 9.99985, 1e-4);
  EXPECT_NEAR(moved.y(), 45.0487, 1e-4);
  EXPECT_NEAR(moved.z(), 30.0011, 1e-4);
  const Field& field = testing::field_as<Field>(object.system.force_fields.at(0));
  const Index checked = 100;  // the element SOFA's test reads
  const auto& element = field.element(checked);
  Eigen::Matrix3d initial_rotation, rotation;
  initial_rotation << -1, 0, 0, 0, -0.8, -0.6, 0, -0.6, 0.8;
  rotation << -1, 8.01488e-06, 0.000541687, -0.000320764, -0.814541, -0.580106, 0.000436576, -0.580106, 0.814541;
  expect_matrix_near(initial_rotation, element.initial_rotation, 1e-4, "initial rotation");
  expect_matrix_near(rotation, element.rotation, 1e-4, "current rotation");
  Eigen::Matrix<double, 4, 3> rest;
  rest << 0, 0, 0, 3.33333, 0, 0, 3.33333, 5.55556, 0, 0, 3.55556, 2.66667;
  for (int i = 0; i < 4; ++i) {
    expect_matrix_near(rest.row(i).transpose(), element.rotated_rest[static_cast<std::size_t>(i)], 1e-4,
                       "rotated rest vertex " + std::to_string(i));
  }
  Eigen::Matrix<double, 6, 6> material = Eigen::Matrix<double, 6, 6>::Zero();
  material.topLeftCorner<3, 3>().setConstant(1.16827);
  material.topLeftCorner<3, 3>().diagonal().setConstant(2.72596);
  material.bottomRightCorner<3, 3>().diagonal().setConstant(0.778846);
  expect_matrix_near(material, field.material_matrix(checked), 1e-4, "material stiffness");
  const Eigen::Matrix<double, 12, 6> j = field.strain_displacement(checked);
  EXPECT_NEAR(j(0, 0), -14.8148, 1e-4);
  EXPECT_NEAR(j(0, 5), -18.5185, 1e-4);
  EXPECT_NEAR(j(3, 0), 14.8148, 1e-4);
  EXPECT_NEAR(j(3, 3), -8.88889, 1e-4);
  EXPECT_NEAR(j(3, 5), 11.8519, 1e-4);
  EXPECT_NEAR(j(6, 3), 8.88889, 1e-4);
  EXPECT_NEAR(j(6, 5), -11.8519, 1e-4);
  EXPECT_NEAR(j(9, 5), 18.5185, 1e-4);
  EXPECT_NEAR(j(11, 2), 18.5185, 1e-4);
  EXPECT_NEAR(j(9, 3), 0, 1e-12);
}

// ---- The reference: the textbook linear tetrahedron in each method's frame --------------------

struct Reference {
  Eigen::Matrix<double, 12, 12> stiffness;  // |V| B^T C B in the element's rest frame
  Mat3<double> rest_frame;                  // world to rest frame
  std::array<Vec3<double>, 4> rest_in_frame;
};

Mat3<double> reference_large_frame(const Vec3<double>& a, const Vec3<double>& b, const Vec3<double>& c) {
  const Vec3<double> x = (b - a).normalized();
  const Vec3<double> z = x.cross(c - a).normalized();
  Mat3<double> frame;
  frame.row(0) = x.transpose();
  frame.row(1) = z.cross(x).transpose();
  frame.row(2) = z.transpose();
  return frame;
}

// The orthogonal polar factor of the rows of the edge matrix (an SVD; for det > 0).
Mat3<double> reference_polar_frame(const std::array<Vec3<double>, 4>& p) {
  Mat3<double> rows;
  for (int i = 0; i < 3; ++i) rows.row(i) = (p[static_cast<std::size_t>(i) + 1] - p[0]).transpose();
  const Eigen::JacobiSVD<Mat3<double>> svd(rows, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

Mat3<double> reference_frame(TetrahedronFEMMethod method, const std::array<Vec3<double>, 4>& p) {
  switch (method) {
    case TetrahedronFEMMethod::small: return Mat3<double>::Identity();
    case TetrahedronFEMMethod::large: return reference_large_frame(p[0], p[1], p[2]);
    default: return reference_polar_frame(p);
  }
}

Reference reference_element(const std::array<Vec3<double>, 4>& rest, double young, double nu,
                            TetrahedronFEMMethod method) {
  Reference r;
  r.rest_frame = reference_frame(method, rest);
  for (std::size_t i = 0; i < 4; ++i) r.rest_in_frame[i] = r.rest_frame * rest[i];
  const auto& q = r.rest_in_frame;
  Mat3<double> edges;
  for (int i = 0; i < 3; ++i) edges.col(i) = q[static_cast<std::size_t>(i) + 1] - q[0];
  const Mat3<double> inverse = edges.inverse();  // row k: gradient of the barycentric coordinate k+1
  std::array<Vec3<double>, 4> gradient;
  for (std::size_t k = 1; k < 4; ++k) gradient[k] = inverse.row(static_cast<Eigen::Index>(k) - 1).transpose();
  gradient[0] = -(gradient[1] + gradient[2] + gradient[3]);
  Eigen::Matrix<double, 6, 12> b = Eigen::Matrix<double, 6, 12>::Zero();
  for (int i = 0; i < 4; ++i) {
    const Vec3<double>& g = gradient[static_cast<std::size_t>(i)];
    b(0, 3 * i) = g.x();
    b(1, 3 * i + 1) = g.y();
    b(2, 3 * i + 2) = g.z();
    b(3, 3 * i) = g.y(), b(3, 3 * i + 1) = g.x();          // xy
    b(4, 3 * i + 1) = g.z(), b(4, 3 * i + 2) = g.y();      // yz
    b(5, 3 * i) = g.z(), b(5, 3 * i + 2) = g.x();          // zx
  }
  const double lambda = young * nu / ((1 + nu) * (1 - 2 * nu)), mu = young / (2 * (1 + nu));
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  c.topLeftCorner<3, 3>().setConstant(lambda);
  c.topLeftCorner<3, 3>().diagonal().array() += 2 * mu;
  c.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  const double volume = std::abs(edges.determinant()) / 6;
  r.stiffness = volume * b.transpose() * c * b;
  return r;
}

// Forces of the whole mesh at x, and the assembled df/dx (SOFA's tangent: R K R^T per element).
struct ReferenceLinearisation {
  Eigen::VectorXd force;
  Eigen::MatrixXd df_dx;
};

ReferenceLinearisation reference(const TetMesh& mesh, const Points& rest, const Points& x, double young, double nu,
                                 TetrahedronFEMMethod method) {
  const auto n = static_cast<Eigen::Index>(3 * mesh.num_points());
  ReferenceLinearisation out{Eigen::VectorXd::Zero(n), Eigen::MatrixXd::Zero(n, n)};
  for (const Tetrahedron& tet : mesh.tetrahedra()) {
    std::array<Vec3<double>, 4> p0, p;
    for (std::size_t i = 0; i < 4; ++i) {
      p0[i] = rest[static_cast<std::size_t>(tet[i])];
      p[i] = x[static_cast<std::size_t>(tet[i])];
    }
    const Reference r = reference_element(p0, young, nu, method);
    const Mat3<double> frame = reference_frame(method, p);
    Eigen::Matrix<double, 12, 1> d;
    for (std::size_t i = 0; i < 4; ++i) {
      d.segment<3>(3 * static_cast<Eigen::Index>(i)) = r.rest_in_frame[i] - frame * p[i];
    }
    const Eigen::Matrix<double, 12, 1> f = r.stiffness * d;
    for (std::size_t i = 0; i < 4; ++i) {
      out.force.segment<3>(3 * tet[i]) += frame.transpose() * f.segment<3>(3 * static_cast<Eigen::Index>(i));
      for (std::size_t k = 0; k < 4; ++k) {
        out.df_dx.block<3, 3>(3 * tet[i], 3 * tet[k]) -=
            frame.transpose() * r.stiffness.block<3, 3>(3 * static_cast<Eigen::Index>(i), 3 * static_cast<Eigen::Index>(k)) *
            frame;
      }
    }
  }
  return out;
}

// A 3×2×2-cell block of 72 tetrahedra (SOFA's split of a grid), rest points and a deformed state.
struct Block {
  std::shared_ptr<TetMesh> mesh;
  Points rest;
};

Block make_block() {
  LoadedScene scene = build_scene(parse_scene_text(R"(<Node name="root">
    <Node name="b"><EulerImplicitSolver/><EigenSimplicialLDLT/>
      <RegularGridTopology name="grid" n="4 3 3" min="0 0 0" max="3 1.5 2"/>
      <MechanicalObject/><TetrahedronSetTopologyContainer name="tets"/>
      <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
      <UniformMass totalMass="1"/>
      <TetrahedronFEMForceField/>
    </Node></Node>)",
                                                   "block.scn"));
  const auto& system = scene.simulation.objects.at(0).system;
  return {std::make_shared<TetMesh>(system.force_fields.at(0)->mesh()), system.state.rest_position};
}

Points deformed(const Points& rest, std::mt19937& rng, double amplitude) {
  Mat3<double> stretch;
  stretch << 1.1, 0.05, 0, -0.02, 0.93, 0.04, 0.03, 0, 1.06;
  return perturbed(affine_map(rest, random_rotation(rng), stretch, Vec3<double>(0.3, -1, 2)), amplitude, rng);
}

class EveryMethod : public ::testing::TestWithParam<TetrahedronFEMMethod> {};

TEST_P(EveryMethod, ForcesAndStiffnessMatchTheTextbookElement) {
  const TetrahedronFEMMethod method = GetParam();
  const Block block = make_block();
  std::mt19937 rng(7);
  const Points x = deformed(block.rest, rng, 0.05);
  Field::Parameters parameters;
  parameters.young_modulus = {1234};
  parameters.poisson_ratio = {0.32};
  parameters.method = method;
  Field field(block.mesh, block.rest, parameters);
  Points f(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  const ReferenceLinearisation expected = reference(*block.mesh, block.rest, x, 1234, 0.32, method);
  EXPECT_LT(relative_difference(flatten(f), expected.force), 1e-10);
  const Eigen::MatrixXd assembled(field.stiffness_matrix(1.0));
  EXPECT_LT((assembled - expected.df_dx).norm() / expected.df_dx.norm(), 1e-10);
  EXPECT_LT((assembled - assembled.transpose()).norm() / assembled.norm(), 1e-14);
  // add_dforce is the assembled product, with the k factor and Rayleigh's b factor.
  const Points dx = perturbed(Points(x.size(), Vec3<double>::Zero()), 1.0, rng);
  Points df(x.size(), Vec3<double>::Zero());
  field.add_dforce(dx, df, -0.7);
  EXPECT_LT(relative_difference(flatten(df), -0.7 * (assembled * flatten(dx))), 1e-12);
}

TEST_P(EveryMethod, RigidMotionsGiveNoForceAndForcesRotateWithTheBody) {
  const TetrahedronFEMMethod method = GetParam();
  const Block block = make_block();
  std::mt19937 rng(11);
  Field::Parameters parameters;
  parameters.method = method;
  Field field(block.mesh, block.rest, parameters);
  const Points x = deformed(block.rest, rng, 0.04);
  Points f(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  Vec3<double> sum = Vec3<double>::Zero();
  for (const auto& v : f) sum += v;
  EXPECT_LT(sum.norm(), 1e-10 * flatten(f).norm());  // translation invariance
  if (method == TetrahedronFEMMethod::small) return;  // small is not rotation invariant
  const Mat3<double> q = random_rotation(rng);
  const Points rigid = affine_map(block.rest, q, Mat3<double>::Identity(), Vec3<double>(1, 2, 3));
  Points at_rest(x.size(), Vec3<double>::Zero());
  field.add_force(rigid, at_rest);
  EXPECT_LT(flatten(at_rest).norm(), 1e-10 * flatten(f).norm());
  const Points turned = affine_map(x, q, Mat3<double>::Identity(), Vec3<double>(-4, 0, 1));
  Points g(x.size(), Vec3<double>::Zero());
  field.add_force(turned, g);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_LT((g[i] - q * f[i]).norm(), 1e-10 * flatten(f).norm());
}

INSTANTIATE_TEST_SUITE_P(TetrahedronFEMForceField, EveryMethod,
                         ::testing::Values(TetrahedronFEMMethod::small, TetrahedronFEMMethod::large,
                                           TetrahedronFEMMethod::polar, TetrahedronFEMMethod::svd),
                         [](const auto& info) { return to_string(info.param); });

TEST(TetrahedronFEMForceField, SmallIsLinearAndItsStiffnessIsTheExactDerivative) {
  const Block block = make_block();
  std::mt19937 rng(3);
  Field::Parameters parameters;
  parameters.method = TetrahedronFEMMethod::small;
  Field field(block.mesh, block.rest, parameters);
  const Points x = deformed(block.rest, rng, 0.05);
  Points f(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  const Eigen::MatrixXd k(field.stiffness_matrix(1.0));
  // f = K (x - rest) exactly for a linear field.
  EXPECT_LT(relative_difference(flatten(f), k * (flatten(x) - flatten(block.rest))), 1e-12);
  // Energy 1/2 u^T (-K) u, SOFA's getPotentialEnergy for small.
  const Eigen::VectorXd u = flatten(x) - flatten(block.rest);
  EXPECT_NEAR(field.potential_energy(x), -0.5 * u.dot(k * u), 1e-10 * std::abs(u.dot(k * u)));
}

TEST(TetrahedronFEMForceField, SvdTurnsAnInvertedElementBackWherePolarMirrorsIt) {
  // An element pushed through itself: vertex 3 below the face (0, 1, 2).
  const Points rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const Points inverted = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -0.5}};
  for (auto method : {TetrahedronFEMMethod::svd, TetrahedronFEMMethod::polar}) {
    Field::Parameters parameters;
    parameters.method = method;
    Field field(mesh, rest, parameters);
    Points f(4, Vec3<double>::Zero());
    field.add_force(inverted, f);
    EXPECT_TRUE(flatten(f).allFinite());
    EXPECT_NEAR(field.rotations()[0].determinant(), method == TetrahedronFEMMethod::svd ? 1.0 : -1.0, 1e-9)
        << to_string(method);
    if (method == TetrahedronFEMMethod::svd) EXPECT_GT(f[3].z(), 0);  // pushed back up
  }
}

TEST(TetrahedronFEMForceField, ResultsAreBitwiseTheSameOnAnyThreadCount) {
  const Block block = make_block();
  std::mt19937 rng(5);
  const Points x = deformed(block.rest, rng, 0.05);
  const Points dx = perturbed(Points(x.size(), Vec3<double>::Zero()), 1.0, rng);
  std::vector<Points> forces, products;
  for (int threads : {1, 2, 3}) {
    Field field(block.mesh, block.rest, {});
    field.set_threads(threads);
    Points f(x.size(), Vec3<double>::Zero()), df(x.size(), Vec3<double>::Zero());
    field.add_force(x, f);
    field.add_dforce(dx, df, 1.0);
    forces.push_back(f);
    products.push_back(df);
  }
  for (std::size_t k = 1; k < forces.size(); ++k) {
    EXPECT_EQ(forces[k], forces[0]);
    EXPECT_EQ(products[k], products[0]);
  }
}

// The batched kernels (large, polar, svd) against the element-by-element path, which the field takes
// when plasticity is on: with a yield threshold no strain reaches, the plastic strain stays zero and
// the two compute the same forces and blocks, apart from rounding. On 1 and 3 threads, with batches
// of every length (the schedule's ranges end mid-batch), and add_force_only bitwise add_force.
TEST(TetrahedronFEMForceField, BatchedKernelsMatchTheElementByElementPath) {
  const Block block = make_block();
  std::mt19937 rng(13);
  const Points x = deformed(block.rest, rng, 0.05);
  const Points dx = perturbed(Points(x.size(), Vec3<double>::Zero()), 1.0, rng);
  for (const auto method : {TetrahedronFEMMethod::large, TetrahedronFEMMethod::polar, TetrahedronFEMMethod::svd}) {
    for (const int threads : {1, 3}) {
      SCOPED_TRACE(to_string(method) + ", " + std::to_string(threads) + " thread(s)");
      Field::Parameters batched;
      batched.young_modulus = {870};
      batched.poisson_ratio = {0.41};
      batched.method = method;
      Field::Parameters elementwise = batched;
      elementwise.plastic_max_threshold = 1e30;
      elementwise.plastic_yield_threshold = 1e30;
      Field fast(block.mesh, block.rest, batched), reference(block.mesh, block.rest, elementwise);
      fast.set_threads(threads);
      reference.set_threads(threads);
      Points f(x.size(), Vec3<double>::Zero()), f_only(x.size(), Vec3<double>::Zero()), f_ref(x.size(), Vec3<double>::Zero());
      fast.add_force_only(x, f_only);
      fast.add_force(x, f);
      reference.add_force(x, f_ref);
      EXPECT_EQ(f, f_only);
      EXPECT_LT(relative_difference(flatten(f), flatten(f_ref)), 1e-14);
      Points df(x.size(), Vec3<double>::Zero()), df_ref(x.size(), Vec3<double>::Zero());
      fast.add_dforce(dx, df, 1.0);
      reference.add_dforce(dx, df_ref, 1.0);
      EXPECT_LT(relative_difference(flatten(df), flatten(df_ref)), 1e-14);
      for (Index t = 0; t < block.mesh->num_tetrahedra(); ++t) {
        EXPECT_EQ(fast.element(t).rotation, reference.element(t).rotation) << "tetrahedron " << t;
      }
    }
  }
}

TEST(TetrahedronFEMForceField, PerTetrahedronPoissonRatiosMatchTheTextbookElements) {
  // Elements of two Poisson ratios (whose blocks are made whole per element, where one ratio lets
  // them be factored): the textbook matrix of each half of the mesh, summed.
  const Block block = make_block();
  std::mt19937 rng(11);
  const Points x = deformed(block.rest, rng, 0.05);
  const auto n = static_cast<std::size_t>(block.mesh->num_tetrahedra());
  std::vector<Tetrahedron> halves[2];
  Field::Parameters parameters;
  parameters.young_modulus = {1234};
  parameters.poisson_ratio.clear();
  for (std::size_t t = 0; t < n; ++t) {
    parameters.poisson_ratio.push_back(t % 2 == 0 ? 0.25 : 0.4);
    halves[t % 2].push_back(block.mesh->tetrahedron(static_cast<Index>(t)));
  }
  for (const TetrahedronFEMMethod method : {TetrahedronFEMMethod::large, TetrahedronFEMMethod::polar}) {
    parameters.method = method;
    Field field(block.mesh, block.rest, parameters);
    Points f(x.size(), Vec3<double>::Zero());
    field.add_force(x, f);
    const auto points = block.mesh->num_points();
    const ReferenceLinearisation even = reference(TetMesh(points, halves[0]), block.rest, x, 1234, 0.25, method);
    const ReferenceLinearisation odd = reference(TetMesh(points, halves[1]), block.rest, x, 1234, 0.4, method);
    EXPECT_LT(relative_difference(flatten(f), even.force + odd.force), 1e-10);
    const Eigen::MatrixXd expected = even.df_dx + odd.df_dx;
    const Eigen::MatrixXd assembled(field.stiffness_matrix(1.0));
    EXPECT_LT((assembled - expected).norm() / expected.norm(), 1e-10);
    const Points dx = perturbed(Points(x.size(), Vec3<double>::Zero()), 1.0, rng);
    Points df(x.size(), Vec3<double>::Zero());
    field.add_dforce(dx, df, 1.0);
    EXPECT_LT(relative_difference(flatten(df), assembled * flatten(dx)), 1e-12);
  }
}

TEST(TetrahedronFEMForceField, PerTetrahedronYoungModulusAndLocalFactors) {
  const Block block = make_block();
  const auto n = static_cast<std::size_t>(block.mesh->num_tetrahedra());
  Field::Parameters listed;
  listed.young_modulus.resize(n);
  for (std::size_t t = 0; t < n; ++t) listed.young_modulus[t] = 1000 + 10 * static_cast<double>(t);
  Field field(block.mesh, block.rest, listed);
  for (std::size_t t = 0; t < n; t += 17) {
    // K scales with E: K(0,0) = E (1 - nu) / ((1 + nu) (1 - 2 nu)) / (36 |V|).
    const double nu = 0.45;
    const double volume = std::abs(signed_volume(tetrahedron_points<double>(block.mesh->tetrahedron(static_cast<Index>(t)), block.rest)));
    EXPECT_NEAR(field.element(static_cast<Index>(t)).material[0],
                listed.young_modulus[t] * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / (36 * volume), 1e-9);
  }
  // localStiffnessFactor: M factors over N tetrahedra, tetrahedron t taking factor[t M / N].
  Field::Parameters factored;
  factored.local_stiffness_factor = {1, 2, 3};
  Field scaled(block.mesh, block.rest, factored);
  Field plain(block.mesh, block.rest, {});
  for (std::size_t t = 0; t < n; ++t) {
    const double factor = factored.local_stiffness_factor[t * 3 / n];
    EXPECT_NEAR(scaled.element(static_cast<Index>(t)).material[0], factor * plain.element(static_cast<Index>(t)).material[0],
                1e-12 * scaled.element(static_cast<Index>(t)).material[0]);
  }
}

TEST(TetrahedronFEMForceField, VonMisesStressOfAUniaxialStrain) {
  // u = (e x, 0, 0): Green strain E_xx = e + e^2 / 2, stresses s_xx = (lambda + 2 mu) E_xx and
  // s_yy = s_zz = lambda E_xx, so von Mises sqrt(...) = |s_xx - s_yy| = 2 mu E_xx.
  const Points rest = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 1, 1}};
  auto mesh = std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{{0, 1, 2, 3}, {1, 2, 3, 4}});
  const double e = 0.01, young = 3000, nu = 0.25, mu = young / (2 * (1 + nu));
  Points x = rest;
  for (auto& p : x) p.x() *= 1 + e;
  for (int von_mises : {1, 2}) {
    Field::Parameters parameters;
    parameters.young_modulus = {young};
    parameters.poisson_ratio = {nu};
    parameters.method = TetrahedronFEMMethod::large;
    parameters.von_mises = von_mises;
    Field field(mesh, rest, parameters);
    field.update_von_mises_stress(x);
    // The corotational strain of a pure stretch is the linear strain e. SOFA forms it from D in
    // the element's frame and the shape functions of the world rest positions, so only elements
    // whose frame is the world's (tetrahedron 0: first edge along x, second in the xy plane) give
    // the textbook value; tetrahedron 1's frame is turned and gets SOFA's own value.
    const double strain = von_mises == 2 ? e + e * e / 2 : e;
    ASSERT_EQ(field.von_mises_per_element().size(), 2u);
    EXPECT_NEAR(field.von_mises_per_element()[0], 2 * mu * strain, 1e-9 * mu);
    ASSERT_EQ(field.von_mises_per_node().size(), 5u);
    EXPECT_NEAR(field.von_mises_per_node()[0], 2 * mu * strain, 1e-9 * mu);  // only in tetrahedron 0
    const auto per_element = field.von_mises_per_element();
    EXPECT_NEAR(field.von_mises_per_node()[1], (per_element[0] + per_element[1]) / 2, 1e-12 * mu);
    if (von_mises == 2) EXPECT_NEAR(per_element[1], 2 * mu * strain, 1e-9 * mu);
  }
  // SOFA computes none for 1 with small.
  Field::Parameters small;
  small.method = TetrahedronFEMMethod::small;
  small.von_mises = 1;
  Field none(mesh, rest, small);
  none.update_von_mises_stress(x);
  EXPECT_TRUE(none.von_mises_per_element().empty());
}

TEST(TetrahedronFEMForceField, RemovedTetrahedraGiveTheFieldOfTheRemainingMesh) {
  const Block block = make_block();
  std::mt19937 rng(9);
  const Points x = deformed(block.rest, rng, 0.05);
  auto mesh = std::make_shared<TetMesh>(*block.mesh);
  Field field(mesh, block.rest, {});
  const std::vector<Index> removed = {3, 40, 17};
  const TopologyChange change = mesh->remove_tetrahedra(removed);
  field.apply(change);
  Field fresh(std::make_shared<TetMesh>(*mesh), block.rest, {});
  Points f(x.size(), Vec3<double>::Zero()), g(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  fresh.add_force(x, g);
  EXPECT_LT(relative_difference(flatten(f), flatten(g)), 1e-14);
  EXPECT_LT((Eigen::MatrixXd(field.stiffness_matrix()) - Eigen::MatrixXd(fresh.stiffness_matrix())).norm(), 1e-9);
}

TEST(TetrahedronFEMForceField, BadParametersAreErrorsNamingThem) {
  const Block block = make_block();
  const auto error_of = [&](Field::Parameters parameters) -> std::string {
    try {
      Field field(block.mesh, block.rest, parameters);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  Field::Parameters p;
  p.young_modulus = {-1};
  EXPECT_NE(error_of(p).find("youngModulus = -1"), std::string::npos) << error_of(p);
  p = {};
  p.poisson_ratio = {0.5};
  EXPECT_NE(error_of(p).find("poissonRatio = 0.5"), std::string::npos);
  p = {};
  p.young_modulus = {1, 2};
  EXPECT_NE(error_of(p).find("youngModulus: 2 values given"), std::string::npos);
  p = {};
  p.von_mises = 3;
  EXPECT_NE(error_of(p).find("computeVonMisesStress = 3"), std::string::npos);
  p = {};
  p.local_stiffness_factor = {1, 0};
  EXPECT_NE(error_of(p).find("localStiffnessFactor[1] = 0"), std::string::npos);
  EXPECT_THROW(parse_tetrahedron_fem_method("qr"), Error);
  Points flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  auto one = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  EXPECT_THROW(Field(one, flat, {}), Error);
}

}  // namespace
}  // namespace fastcorot
