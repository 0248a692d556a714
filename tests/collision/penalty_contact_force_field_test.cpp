// PenaltyContactForceField against SOFA's PenalityContactForceField_test values (two points, the
// second pushed along the normal), its stiffness against central differences of its force (through
// weighted row blocks on several blocks, both sides), the assembled matrix and diagonal against the
// product, inactive contacts (no force, no stiffness), and bad contacts refused.
#include "fastcorot/collision/penalty_contact_force_field.h"

#include "fastcorot/core/error.h"

#include "support/linearisation.h"

#include <gtest/gtest.h>

#include <random>

namespace fastcorot {
namespace {

using V = Vec3<double>;

std::shared_ptr<const TetMesh> points(Index n) { return std::make_shared<const TetMesh>(n, std::vector<Tetrahedron>{}); }

// SOFA's test: points 0 and 1 (identity row blocks), the normal from point 0 to point 1.
PenaltyContact<double> between(const V& x0, const V& x1, double k, double d) {
  PenaltyContact<double> c;
  c.side1 = {{0, Mat3<double>::Identity()}};
  c.side2 = {{1, Mat3<double>::Identity()}};
  c.y1 = x0;
  c.y2 = x1;
  c.normal = (x1 - x0).normalized();
  c.distance = d;
  c.stiffness = k;
  return c;
}

TEST(PenaltyContactForceField, SofasTestValues) {
  const auto run = [](const V& x1, double k, double d) {
    PenaltyContactForceField<double> field(points(2));
    const std::vector<V> x = {V::Zero(), x1};
    field.set_contacts({between(x[0], x[1], k, d)}, x);
    std::vector<V> f(2, V::Zero());
    field.add_force(x, f);
    EXPECT_LT((f[0] + f[1]).norm(), 1e-15);  // equal and opposite
    return f[0];
  };
  EXPECT_LT((run(V(2, 0, 0), 1, 3) - V(-1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((run(V(2, 0, 0), 2, 3) - V(-2, 0, 0)).norm(), 1e-15);
  EXPECT_LT((run(V(4.8, -0.4, -2.3), 2, 6) - V(-1.191361936914749, 0.099280161409562, 0.570860928104984)).norm(), 1e-12);
  // Farther than d: no force.
  EXPECT_EQ(run(V(3.5, 0, 0), 1, 3), V::Zero());
}

TEST(PenaltyContactForceField, StiffnessIsTheForcesDerivative) {
  // Side 1 a weighted point of blocks 0..2 (a contact point in a triangle), side 2 of blocks 3, 4.
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<V> x(5);
  for (auto& p : x) p = V(u(rng), u(rng), u(rng));
  PenaltyContact<double> c;
  c.side1 = {{0, 0.2 * Mat3<double>::Identity()}, {1, 0.5 * Mat3<double>::Identity()}, {2, 0.3 * Mat3<double>::Identity()}};
  c.side2 = {{3, 0.6 * Mat3<double>::Identity()}, {4, 0.4 * Mat3<double>::Identity()}};
  c.y1 = 0.2 * x[0] + 0.5 * x[1] + 0.3 * x[2];
  c.y2 = 0.6 * x[3] + 0.4 * x[4];
  c.normal = V(0.3, 0.9, -0.1).normalized();
  c.distance = (c.y2 - c.y1).dot(c.normal) + 0.4;  // pushing by 0.4
  c.stiffness = 7;
  // A second contact whose side 2 has full 3×3 blocks (a point carried by a rigid body's rotation)
  // against an obstacle, and shares block 3 with the first.
  PenaltyContact<double> full;
  Mat3<double> j1, j2;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) j1(r, k) = u(rng), j2(r, k) = u(rng);
  full.side2 = {{3, j1}, {1, j2}};
  full.y1 = V(0.1, -0.2, 0.3);
  full.y2 = V(0.2, 0.1, 0.2);
  full.normal = V(-0.5, 0.2, 0.8).normalized();
  full.distance = (full.y2 - full.y1).dot(full.normal) + 0.3;
  full.stiffness = 3;
  PenaltyContactForceField<double> field(points(5));
  field.set_contacts({c, full}, x);
  std::vector<V> f(5, V::Zero());
  field.add_force(x, f);
  EXPECT_NEAR(field.forces()[0].norm(), 7 * 0.4, 1e-12);
  EXPECT_NEAR(field.forces()[1].norm(), 3 * 0.3, 1e-12);
  std::vector<V> dx(5);
  for (auto& p : dx) p = V(u(rng), u(rng), u(rng));
  PenaltyContactForceField<double> probe(points(5));
  probe.set_contacts({c, full}, x);
  testing::expect_linearisation_is_the_forces_derivative(field, probe, x, dx);
  // The energy's derivative is minus the force.
  EXPECT_NEAR(field.potential_energy(x), 0.5 * 7 * 0.4 * 0.4 + 0.5 * 3 * 0.3 * 0.3, 1e-12);
}

TEST(PenaltyContactForceField, AnObstacleSideAndInactiveContactsAndBadInput) {
  // Side 1 an obstacle (no rows): only side 2's block feels the force.
  PenaltyContact<double> c;
  c.side2 = {{0, Mat3<double>::Identity()}};
  c.y1 = V(0, -1, 0);
  c.y2 = V(0, 0, 0);
  c.normal = V(0, 1, 0);
  c.distance = 1.5;
  c.stiffness = 10;
  PenaltyContactForceField<double> field(points(1));
  const std::vector<V> x = {V::Zero()};
  field.set_contacts({c}, x);
  std::vector<V> f(1, V::Zero());
  field.add_force(x, f);
  EXPECT_LT((f[0] - V(0, 5, 0)).norm(), 1e-15);
  // Lifted out of reach: inactive, no stiffness either.
  const std::vector<V> lifted = {V(0, 1, 0)};
  std::vector<V> g(1, V::Zero()), dg(1, V::Zero());
  field.add_force(lifted, g);
  EXPECT_EQ(g[0], V::Zero());
  field.add_dforce(std::vector<V>{V(1, 1, 1)}, dg, 1.0);
  EXPECT_EQ(dg[0], V::Zero());
  c.stiffness = -1;
  EXPECT_THROW(field.set_contacts({c}, x), Error);
  c.stiffness = 1;
  c.side2 = {{3, Mat3<double>::Identity()}};
  EXPECT_THROW(field.set_contacts({c}, x), Error);
}

}  // namespace
}  // namespace fastcorot
