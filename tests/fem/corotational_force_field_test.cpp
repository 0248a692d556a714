#include "fastcorot/fem/corotational_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"
#include "support/deformations.h"
#include "support/finite_difference.h"
#include "support/reference_element.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>

namespace fastcorot {
namespace {

using testing::flatten;
using testing::relative_error;
using Field = CorotationalForceField<double>;
using Points = std::vector<Vec3<double>>;

struct TestMesh {
  std::shared_ptr<TetMesh> mesh;
  Points rest;
};

// A 3×3×3-point grid (8 cells, 40 tetrahedra with SOFA's alternating split) over an irregular box.
TestMesh grid_mesh(std::array<Index, 3> n = {3, 3, 3}) {
  RegularGrid grid;
  grid.n = n;
  grid.min = Vec3<double>(-0.5, 0.0, 0.2);
  grid.max = Vec3<double>(1.0, 0.8, 1.6);
  return {std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true)), grid_points<double>(grid)};
}

Field::Parameters parameters_for(RotationMethod method) {
  Field::Parameters parameters;
  parameters.young_modulus = {1000.0};
  parameters.poisson_ratio = {0.3};
  parameters.method = method;
  return parameters;
}

Points deformed(const Points& rest, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  Mat3<double> stretch;
  stretch << 1.1, 0.05, 0.0, -0.02, 0.92, 0.04, 0.03, 0.0, 1.05;
  const Mat3<double> rotation = testing::random_rotation(rng);
  return testing::perturbed(testing::affine_map(rest, rotation, stretch, Vec3<double>(0.3, -0.1, 0.7)),
                            amplitude, rng);
}

Points zeros(std::size_t n) { return Points(n, Vec3<double>::Zero()); }

// Straightforward reference: loop over elements with SPEC's per-edge element, assemble densely.
struct Reference {
  Points force;
  Eigen::MatrixXd stiffness;
};

Reference reference(const TetMesh& mesh, const Points& rest, const Points& x, const Field::Parameters& parameters) {
  Reference out{zeros(x.size()), Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(x.size()), 3 * static_cast<Eigen::Index>(x.size()))};
  for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
    const auto& tet = mesh.tetrahedron(t);
    const auto e = static_cast<std::size_t>(t);
    const double young = parameters.young_modulus.size() > e ? parameters.young_modulus[e] : parameters.young_modulus[0];
    const double poisson = parameters.poisson_ratio.size() > e ? parameters.poisson_ratio[e] : parameters.poisson_ratio[0];
    const auto p = tetrahedron_points<double>(tet, rest);
    const auto xt = tetrahedron_points<double>(tet, x);
    const auto data = tetrahedron_rest(p, lame_parameters(young, poisson), parameters.method);
    const Mat3<double> r = tetrahedron_rotation(data, xt, parameters.method);
    const auto f = testing::reference_force(data, p, xt, r);
    for (int j = 0; j < 4; ++j) out.force[static_cast<std::size_t>(tet[j])] += f[j];
    for (int j = 0; j < 4; ++j) {
      out.stiffness.block<3, 3>(3 * tet[j], 3 * tet[j]) -= r * vertex_block(data, j) * r.transpose();
    }
    for (int edge = 0; edge < 6; ++edge) {
      const int k = kTetrahedronEdges[edge][0], l = kTetrahedronEdges[edge][1];
      const Mat3<double> block = r * edge_block(data, edge) * r.transpose();
      out.stiffness.block<3, 3>(3 * tet[l], 3 * tet[k]) -= block;
      out.stiffness.block<3, 3>(3 * tet[k], 3 * tet[l]) -= block.transpose();
    }
  }
  return out;
}

class ForceFieldMethod : public ::testing::TestWithParam<RotationMethod> {};

TEST_P(ForceFieldMethod, MatchesTheStraightforwardReference) {
  const auto [mesh, rest] = grid_mesh();
  const auto parameters = parameters_for(GetParam());
  Field field(mesh, rest, parameters);
  const Points x = deformed(rest, 0.05, 1);
  Points force(rest.size(), Vec3<double>(1.0, -2.0, 0.5));  // forces accumulate into f
  field.add_force(x, force);
  const Reference ref = reference(*mesh, rest, x, parameters);
  for (auto& f : force) f -= Vec3<double>(1.0, -2.0, 0.5);
  EXPECT_LT(relative_error(flatten(force), flatten(ref.force)), 1e-12);
  const double k_factor = 1.7;
  EXPECT_LT(relative_error(Eigen::MatrixXd(field.stiffness_matrix(k_factor)), k_factor * ref.stiffness), 1e-12);
}

// Elements pushed through themselves during a run (docs/robustness.md, "Inverted and collapsed elements"): the
// SIMD kernels (their own QR frame, a batch of elements at once) treat them exactly as the
// per-element reference does, with finite results.
TEST_P(ForceFieldMethod, InvertedElementsMatchTheReference) {
  const auto [mesh, rest] = grid_mesh();
  const auto parameters = parameters_for(GetParam());
  Field field(mesh, rest, parameters);
  std::mt19937 rng(21);
  const Points x = testing::perturbed(rest, 0.6, rng);  // grid cells are 0.75 × 0.4 × 0.7
  int inverted = 0;
  for (const Tetrahedron& tet : mesh->tetrahedra()) {
    const double before = signed_volume(tetrahedron_points<double>(tet, rest));
    inverted += before * signed_volume(tetrahedron_points<double>(tet, x)) < 0;
  }
  ASSERT_GE(inverted, 5) << "the configuration must invert several of the 40 elements";
  Points force = zeros(rest.size());
  field.add_force(x, force);
  const Reference ref = reference(*mesh, rest, x, parameters);
  EXPECT_TRUE(flatten(force).allFinite());
  EXPECT_LT(relative_error(flatten(force), flatten(ref.force)), 1e-11);
  EXPECT_LT(relative_error(Eigen::MatrixXd(field.stiffness_matrix(1.0)), ref.stiffness), 1e-11);
  Points dforce = zeros(rest.size());
  field.add_dforce(deformed(rest, 0.1, 22), dforce, 1.0);
  EXPECT_TRUE(flatten(dforce).allFinite());
}

TEST_P(ForceFieldMethod, DforceIsStiffnessTimesDx) {
  const auto [mesh, rest] = grid_mesh();
  Field field(mesh, rest, parameters_for(GetParam()));
  Points force = zeros(rest.size());
  field.add_force(deformed(rest, 0.05, 2), force);
  const Points dx = deformed(rest, 0.1, 3);
  const double k_factor = -0.37;
  Points dforce(rest.size(), Vec3<double>(0.5, 0.5, 0.5));
  field.add_dforce(dx, dforce, k_factor);
  for (auto& f : dforce) f -= Vec3<double>(0.5, 0.5, 0.5);
  const Eigen::VectorXd expected = field.stiffness_matrix(k_factor) * flatten(dx);
  EXPECT_LT(relative_error(flatten(dforce), expected), 1e-12);
}

TEST_P(ForceFieldMethod, StiffnessIsSymmetricAndTranslationInvariant) {
  const auto [mesh, rest] = grid_mesh();
  Field field(mesh, rest, parameters_for(GetParam()));
  Points force = zeros(rest.size());
  field.add_force(deformed(rest, 0.05, 4), force);
  const Eigen::MatrixXd k = field.stiffness_matrix(1.0);
  EXPECT_LT(relative_error(k, Eigen::MatrixXd(k.transpose())), 1e-13);
  // A uniform translation produces no force change.
  const Points shift(rest.size(), Vec3<double>(0.3, -0.7, 1.1));
  EXPECT_LT((k * flatten(shift)).cwiseAbs().maxCoeff(), 1e-11 * k.cwiseAbs().maxCoeff());
}

TEST_P(ForceFieldMethod, RestStateInvariancesAndZeroSum) {
  const RotationMethod method = GetParam();
  const auto [mesh, rest] = grid_mesh();
  Field field(mesh, rest, parameters_for(method));
  Points force = zeros(rest.size());
  field.add_force(rest, force);
  EXPECT_LT(flatten(force).cwiseAbs().maxCoeff(), 1e-11);

  const Points x = deformed(rest, 0.05, 5);
  Points f = zeros(rest.size());
  field.add_force(x, f);
  Vec3<double> sum = Vec3<double>::Zero();
  for (const auto& v : f) sum += v;
  EXPECT_LT(sum.norm(), 1e-11 * flatten(f).cwiseAbs().maxCoeff());

  Points shifted = x;
  for (auto& v : shifted) v += Vec3<double>(-2.0, 5.0, 0.25);
  Points g = zeros(rest.size());
  field.add_force(shifted, g);
  EXPECT_LT(relative_error(flatten(g), flatten(f)), 1e-11);

  if (method != RotationMethod::none) {
    std::mt19937 rng(99);
    const Mat3<double> q = testing::random_rotation(rng);
    Points rotated = x;
    for (auto& v : rotated) v = q * v;
    Points h = zeros(rest.size());
    field.add_force(rotated, h);
    Points qf = f;
    for (auto& v : qf) v = q * v;
    EXPECT_LT(relative_error(flatten(h), flatten(qf)), 1e-10);
  }
}

TEST_P(ForceFieldMethod, EnergyGradient) {
  // Exact for none and polar at finite strain; qr and polar2 drop the rotation derivative, an error
  // of relative order the strain, so they are checked at small strain.
  const RotationMethod method = GetParam();
  const bool exact = method == RotationMethod::none || method == RotationMethod::polar;
  const auto [mesh, rest] = grid_mesh({2, 3, 2});
  Field field(mesh, rest, parameters_for(method));
  std::mt19937 rng(6);
  const double amplitude = exact ? 0.05 : 1e-4;
  const Points x = testing::perturbed(rest, amplitude, rng);
  Points force = zeros(rest.size());
  field.add_force(x, force);
  const Eigen::VectorXd gradient = testing::fd_gradient(
      [&](const Eigen::VectorXd& v) { return field.potential_energy(testing::unflatten(v)); }, flatten(x),
      amplitude * 1e-3);
  EXPECT_LT(relative_error(-gradient, flatten(force)), exact ? 1e-6 : 2e-3);
  EXPECT_GT(field.potential_energy(x), 0.0);
}

TEST_P(ForceFieldMethod, IndependentOfEdgeOrderAndOrientation) {
  // SOFA once produced wrong stiffness when mesh edges were not created in the tetrahedra's
  // direction; an explicit edge list in a shuffled order with reversed edges must change nothing.
  const auto [mesh, rest] = grid_mesh();
  std::vector<Edge> edges(mesh->edges().begin(), mesh->edges().end());
  std::mt19937 rng(8);
  std::shuffle(edges.begin(), edges.end(), rng);
  for (std::size_t i = 0; i < edges.size(); i += 2) std::swap(edges[i][0], edges[i][1]);
  auto other = std::make_shared<TetMesh>(mesh->num_points(),
                                         std::vector<Tetrahedron>(mesh->tetrahedra().begin(), mesh->tetrahedra().end()),
                                         edges);
  Field a(mesh, rest, parameters_for(GetParam()));
  Field b(other, rest, parameters_for(GetParam()));
  const Points x = deformed(rest, 0.05, 10);
  Points fa = zeros(rest.size()), fb = zeros(rest.size());
  a.add_force(x, fa);
  b.add_force(x, fb);
  EXPECT_LT(relative_error(flatten(fb), flatten(fa)), 1e-13);
  const Points dx = deformed(rest, 0.1, 11);
  Points da = zeros(rest.size()), db = zeros(rest.size());
  a.add_dforce(dx, da, 1.0);
  b.add_dforce(dx, db, 1.0);
  EXPECT_LT(relative_error(flatten(db), flatten(da)), 1e-13);
  EXPECT_LT(relative_error(Eigen::MatrixXd(b.stiffness_matrix()), Eigen::MatrixXd(a.stiffness_matrix())), 1e-13);
}

TEST_P(ForceFieldMethod, SetMethodEqualsAFreshField) {
  const auto [mesh, rest] = grid_mesh();
  Field switched(mesh, rest, parameters_for(GetParam() == RotationMethod::qr ? RotationMethod::polar : RotationMethod::qr));
  switched.set_method(GetParam());
  Field fresh(mesh, rest, parameters_for(GetParam()));
  const Points x = deformed(rest, 0.05, 12);
  Points fs = zeros(rest.size()), ff = zeros(rest.size());
  switched.add_force(x, fs);
  fresh.add_force(x, ff);
  EXPECT_EQ(flatten(fs), flatten(ff));
  EXPECT_EQ(switched.method(), GetParam());
}

TEST_P(ForceFieldMethod, FloatAgreesWithDouble) {
  const auto [mesh, rest] = grid_mesh();
  Field field(mesh, rest, parameters_for(GetParam()));
  CorotationalForceField<float>::Parameters pf;
  pf.young_modulus = {1000.0f};
  pf.poisson_ratio = {0.3f};
  pf.method = GetParam();
  CorotationalForceField<float> field_f(mesh, testing::cast_points<float>(rest), pf);
  const Points x = deformed(rest, 0.05, 13);
  Points f = zeros(rest.size());
  field.add_force(x, f);
  auto xf = testing::cast_points<float>(x);
  std::vector<Vec3<float>> ff(rest.size(), Vec3<float>::Zero());
  field_f.add_force(xf, ff);
  Points ffd;
  for (const auto& v : ff) ffd.push_back(v.cast<double>());
  EXPECT_LT(relative_error(flatten(ffd), flatten(f)), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, ForceFieldMethod,
                         ::testing::Values(RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2,
                                           RotationMethod::none),
                         [](const auto& info) { return to_string(info.param); });

TEST(ForceField, LinearMethodStiffnessIsTheForceJacobian) {
  const auto [mesh, rest] = grid_mesh({2, 3, 2});
  Field field(mesh, rest, parameters_for(RotationMethod::none));
  const Points x = deformed(rest, 0.1, 14);
  const Eigen::MatrixXd jacobian = testing::fd_jacobian(
      [&](const Eigen::VectorXd& v) {
        Points f = zeros(rest.size());
        field.add_force(testing::unflatten(v), f);
        return flatten(f);
      },
      flatten(x), 1e-4);
  EXPECT_LT(relative_error(jacobian, Eigen::MatrixXd(field.stiffness_matrix())), 1e-8);
}

TEST(ForceField, PerElementParametersSuperpose) {
  // Two tetrahedra with their own E and nu: the field equals the sum of two one-element fields.
  const Points rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  const std::vector<Tetrahedron> tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  Field::Parameters both = parameters_for(RotationMethod::qr);
  both.young_modulus = {1000.0, 3000.0};
  both.poisson_ratio = {0.3, 0.1};
  Field field(std::make_shared<TetMesh>(5, tets), rest, both);
  Points x = rest;
  x[4] += Vec3<double>(0.1, -0.05, 0.2);
  x[0] += Vec3<double>(-0.05, 0.02, 0.0);
  Points f = zeros(5), expected = zeros(5);
  field.add_force(x, f);
  for (std::size_t t = 0; t < 2; ++t) {
    Field::Parameters one = parameters_for(RotationMethod::qr);
    one.young_modulus = {both.young_modulus[t]};
    one.poisson_ratio = {both.poisson_ratio[t]};
    Field single(std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{tets[t]}), rest, one);
    single.add_force(x, expected);
  }
  EXPECT_LT(relative_error(flatten(f), flatten(expected)), 1e-13);
}

TEST(ForceField, RayleighDampingScalesTheStiffnessProduct) {
  const auto [mesh, rest] = grid_mesh();
  Field::Parameters parameters = parameters_for(RotationMethod::qr);
  parameters.rayleigh_stiffness = 0.1;
  Field field(mesh, rest, parameters);
  Points force = zeros(rest.size());
  field.add_force(deformed(rest, 0.05, 15), force);
  const Points dx = deformed(rest, 0.1, 16);
  Points with_b = zeros(rest.size()), combined = zeros(rest.size());
  field.add_dforce(dx, with_b, -0.0001, -0.01);     // k = -h², b = -h for h = 0.01
  field.add_dforce(dx, combined, -0.0001 + -0.01 * 0.1);
  EXPECT_LT(relative_error(flatten(with_b), flatten(combined)), 1e-14);
}

TEST(ForceField, StiffnessGoesAtTheRequestedOffset) {
  const auto [mesh, rest] = grid_mesh({2, 2, 2});
  Field field(mesh, rest, parameters_for(RotationMethod::polar));
  TripletSink<double> sink;
  field.add_stiffness(sink, 2.0, 6);
  const Index n = 3 * mesh->num_points();
  const Eigen::MatrixXd shifted = Eigen::MatrixXd(sink.to_sparse(n + 6));
  EXPECT_EQ(shifted.topRows(6).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(shifted.leftCols(6).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(Eigen::MatrixXd(shifted.bottomRightCorner(n, n)), Eigen::MatrixXd(field.stiffness_matrix(2.0)));
}

TEST(ForceField, TopologyChangesEqualAFreshField) {
  const auto [mesh, rest] = grid_mesh();
  const std::vector<Tetrahedron> all(mesh->tetrahedra().begin(), mesh->tetrahedra().end());
  Field field(mesh, rest, parameters_for(RotationMethod::qr));
  const std::vector<Index> removed = {3, 0, 17};
  field.remove_tetrahedra(removed);
  std::vector<Tetrahedron> kept;
  for (std::size_t t = 0; t < all.size(); ++t) {
    if (std::find(removed.begin(), removed.end(), static_cast<Index>(t)) == removed.end()) kept.push_back(all[t]);
  }
  ASSERT_EQ(field.mesh().num_tetrahedra(), static_cast<Index>(kept.size()));
  const Points x = deformed(rest, 0.05, 17);
  auto check_against_fresh = [&](const std::vector<Tetrahedron>& tets) {
    Field fresh(std::make_shared<TetMesh>(mesh->num_points(), tets), rest, parameters_for(RotationMethod::qr));
    Points f = zeros(rest.size()), g = zeros(rest.size());
    field.add_force(x, f);
    fresh.add_force(x, g);
    EXPECT_LT(relative_error(flatten(f), flatten(g)), 1e-13);
    EXPECT_LT(relative_error(Eigen::MatrixXd(field.stiffness_matrix()), Eigen::MatrixXd(fresh.stiffness_matrix())), 1e-13);
  };
  check_against_fresh(kept);
  const std::vector<Tetrahedron> back = {all[3], all[0]};
  field.add_tetrahedra(back);
  kept.insert(kept.end(), back.begin(), back.end());
  check_against_fresh(kept);
}

std::string construction_error(std::shared_ptr<TetMesh> mesh, const Points& rest, const Field::Parameters& parameters) {
  try {
    Field field(std::move(mesh), rest, parameters);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(ForceField, BadInputIsAnErrorNamingTheProblem) {
  const auto [mesh, rest] = grid_mesh({2, 2, 2});
  const Index n = mesh->num_tetrahedra();
  auto expect_error = [&](std::shared_ptr<TetMesh> m, const Points& r, const Field::Parameters& p,
                          const std::string& needle) {
    const std::string message = construction_error(std::move(m), r, p);
    EXPECT_NE(message.find(needle), std::string::npos) << "message: \"" << message << "\" lacks \"" << needle << "\"";
  };
  auto with = [&](auto change) {
    Field::Parameters p = parameters_for(RotationMethod::qr);
    change(p);
    return p;
  };
  expect_error(std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{}), Points(4, Vec3<double>::Zero()),
               parameters_for(RotationMethod::qr), "no tetrahedra");
  expect_error(mesh, rest, with([](auto& p) { p.young_modulus = {1000.0, 2000.0}; }), "youngModulus: 2 values");
  expect_error(mesh, rest, with([](auto& p) { p.poisson_ratio = {0.3, 0.3, 0.3}; }), "poissonRatio: 3 values");
  expect_error(mesh, rest, with([](auto& p) { p.young_modulus = {-5.0}; }), "youngModulus = -5");
  expect_error(mesh, rest, with([](auto& p) { p.poisson_ratio = {0.5}; }), "poissonRatio = 0.5");
  expect_error(mesh, rest, with([&](auto& p) {
                 p.young_modulus.assign(static_cast<std::size_t>(n), 1000.0);
                 p.young_modulus[3] = 0.0;
               }),
               "tetrahedron 3");
  expect_error(mesh, rest, with([](auto& p) { p.rayleigh_stiffness = -0.1; }), "rayleighStiffness");
  expect_error(mesh, Points(rest.begin(), rest.end() - 1), parameters_for(RotationMethod::qr), "points");
  Points flat = rest;
  const Tetrahedron& t2 = mesh->tetrahedron(2);
  flat[static_cast<std::size_t>(t2[3])] = (flat[static_cast<std::size_t>(t2[0])] + flat[static_cast<std::size_t>(t2[1])]) / 2;
  EXPECT_NE(construction_error(mesh, flat, parameters_for(RotationMethod::qr)).find("degenerate"), std::string::npos);

  Field field(mesh, rest, parameters_for(RotationMethod::qr));
  Points short_x(rest.size() - 1, Vec3<double>::Zero()), f = zeros(rest.size());
  EXPECT_THROW(field.add_force(short_x, f), Error);
  EXPECT_THROW(field.add_dforce(rest, short_x, 1.0), Error);
  EXPECT_THROW(field.add_tetrahedra(std::vector<Tetrahedron>{{0, 1, 2, 99}}), Error);
  EXPECT_EQ(field.mesh().num_tetrahedra(), n);  // a failed change leaves the field as it was
}

}  // namespace
}  // namespace fastcorot
