// TetrahedronFEMForceField's plasticity (SOFA's computeForce with plasticMaxThreshold > 0), against
// the update written out here on SOFA's full J (12x6) and K (6x6) matrices, over several force
// evaluations of one element; and its refusals.
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>

namespace fastcorot {
namespace {

using Field = TetrahedronFEMForceField<double>;

TEST(TetrahedronFEMPlasticity, StrainUpdateAndForceFollowSofasFormula) {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const std::vector<Vec3<double>> rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Field::Parameters p;
  p.young_modulus = {1000};
  p.poisson_ratio = {0.3};
  p.method = TetrahedronFEMMethod::small;
  p.plastic_max_threshold = 0.05;
  p.plastic_yield_threshold = 0.01;
  p.plastic_creep = 0.5;
  Field field(mesh, rest, p);
  const Eigen::Matrix<double, 12, 6> j = field.strain_displacement(0);
  const Eigen::Matrix<double, 6, 6> k = field.material_matrix(0);
  Eigen::Matrix<double, 6, 1> plastic = Eigen::Matrix<double, 6, 1>::Zero();
  for (int evaluation = 0; evaluation < 4; ++evaluation) {
    const double stretch = 0.02 * (evaluation + 1);
    const std::vector<Vec3<double>> x = {{0, 0, 0}, {1 + stretch, 0, 0}, {0, 1, 0.5 * stretch}, {0, 0, 1}};
    std::vector<Vec3<double>> f(4, Vec3<double>::Zero());
    field.add_force(x, f);
    // SOFA's small displacement: D_i = (X_i - X_0) - (x_i - x_0), D_0 = 0.
    Eigen::Matrix<double, 12, 1> d = Eigen::Matrix<double, 12, 1>::Zero();
    for (int i = 1; i < 4; ++i) d.segment<3>(3 * i) = (rest[static_cast<std::size_t>(i)] - rest[0]) - (x[static_cast<std::size_t>(i)] - x[0]);
    const Eigen::Matrix<double, 6, 1> total = j.transpose() * d;
    const Eigen::Matrix<double, 6, 1> elastic = total - plastic;
    if (elastic.squaredNorm() > 0.01 * 0.01) plastic += 0.5 * elastic;
    if (plastic.squaredNorm() > 0.05 * 0.05) plastic *= 0.05 / plastic.norm();
    const Eigen::Matrix<double, 12, 1> expected = j * (k * (total - plastic));
    for (int i = 0; i < 4; ++i) {
      EXPECT_LT((f[static_cast<std::size_t>(i)] - expected.segment<3>(3 * i)).norm(), 1e-9 * expected.norm()) << evaluation;
    }
    const auto& element_plastic = field.element(0).plastic_strain;
    for (int c = 0; c < 6; ++c) EXPECT_NEAR(element_plastic[static_cast<std::size_t>(c)], plastic[c], 1e-12);
  }
  EXPECT_NEAR(plastic.norm(), 0.05, 1e-12);  // capped by the last evaluations
  EXPECT_NE(field.unsaved_state(), "");
}

TEST(TetrahedronFEMPlasticity, OffByDefaultAndBadThresholdsAreRefused) {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const std::vector<Vec3<double>> rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Field::Parameters p;
  Field elastic(mesh, rest, p);
  std::vector<Vec3<double>> f(4, Vec3<double>::Zero());
  elastic.add_force(std::vector<Vec3<double>>{{0, 0, 0}, {1.5, 0, 0}, {0, 1, 0}, {0, 0, 1}}, f);
  for (double v : elastic.element(0).plastic_strain) EXPECT_EQ(v, 0);
  EXPECT_EQ(elastic.unsaved_state(), "");
  EXPECT_EQ(p.plastic_creep, static_cast<double>(0.9f));
  p.plastic_max_threshold = std::nan("");
  EXPECT_THROW(Field(mesh, rest, p), Error);
  p.plastic_max_threshold = 0.1;
  p.plastic_creep = -1;
  EXPECT_THROW(Field(mesh, rest, p), Error);
}

}  // namespace
}  // namespace fastcorot
