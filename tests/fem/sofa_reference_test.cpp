// The force field against SOFA's own numbers for one deformed tetrahedron, each method
// (tests/data/sofa_reference/single_tet_<method>.json; see the README there for the case).
#include "fastcorot/fem/corotational_force_field.h"

#include "support/deformations.h"
#include "support/finite_difference.h"
#include "support/sofa_reference.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using testing::flatten;
using testing::relative_error;

class SofaSingleTet : public ::testing::TestWithParam<std::string> {};

TEST_P(SofaSingleTet, ForceDforceAndStiffnessMatchSofa) {
  const auto c = testing::load_sofa_single_tet(GetParam());
  ASSERT_EQ(c.raw["method"].get<std::string>(), GetParam());
  auto mesh = std::make_shared<TetMesh>(4, c.tetrahedra);
  // Our derived edge list is SOFA's, in SOFA's order and orientation.
  ASSERT_EQ(std::vector<Edge>(mesh->edges().begin(), mesh->edges().end()), c.edges);

  CorotationalForceField<double>::Parameters parameters;
  parameters.young_modulus = {c.raw["youngModulus"].get<double>()};
  parameters.poisson_ratio = {c.raw["poissonRatio"].get<double>()};
  parameters.method = parse_rotation_method(GetParam());
  CorotationalForceField<double> field(mesh, c.rest, parameters);

  std::vector<Vec3<double>> force(4, Vec3<double>::Zero());
  field.add_force(c.x, force);
  EXPECT_LT(relative_error(flatten(force), flatten(c.force)), 1e-9);

  std::vector<Vec3<double>> dforce(4, Vec3<double>::Zero());
  field.add_dforce(c.dx, dforce, 1.0);
  EXPECT_LT(relative_error(flatten(dforce), flatten(c.dforce)), 1e-9);

  const Eigen::MatrixXd stiffness = Eigen::MatrixXd(field.stiffness_matrix(1.0));
  EXPECT_LT(relative_error(stiffness, c.stiffness), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, SofaSingleTet, ::testing::Values("qr", "polar", "polar2", "none"));

}  // namespace
}  // namespace fastcorot
