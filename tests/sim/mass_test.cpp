// Masses (docs/sofa-components.md §1 DiagonalMass, §3 MeshMatrixMass). Every expected value below is
// worked out by hand from the element formulas: lumped m_v = Σ ρ|V_t|/4, consistent M_ii += ρ|V|/10,
// M_ij += ρ|V|/20.
#include "fastcorot/sim/mass.h"

#include "fastcorot/core/error.h"
#include "support/deformations.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

// The unit tetrahedron: |V| = 1/6.
Points unit_tetrahedron() {
  return {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1)};
}

// Two positively oriented tetrahedra sharing the face (0, 1, 2):
//   A = (0, 1, 2, 3) with p3 = (0, 0, 1):  |V_A| = 1/6,
//   B = (0, 2, 1, 4) with p4 = (0, 0, -2): |V_B| = |(0,1,0)·((1,0,0)×(0,0,-2))| / 6 = 2/6 = 1/3.
struct TwoTets {
  TetMesh mesh{5, {Tetrahedron{0, 1, 2, 3}, Tetrahedron{0, 2, 1, 4}}};
  Points rest{Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1),
              Vec3<double>(0, 0, -2)};
};

// The consistent matrix of TwoTets at density 6 (ρ|V_A| = 1, ρ|V_B| = 2):
//   A contributes 1/10 on its diagonal and 1/20 off it, B contributes 2/10 and 2/20.
Eigen::MatrixXd two_tets_consistent_by_hand() {
  Eigen::MatrixXd m(5, 5);
  // vertices:  0     1     2     3     4
  m << 0.30, 0.15, 0.15, 0.05, 0.10,  //
      0.15, 0.30, 0.15, 0.05, 0.10,   //
      0.15, 0.15, 0.30, 0.05, 0.10,   //
      0.05, 0.05, 0.05, 0.10, 0.00,   //
      0.10, 0.10, 0.10, 0.00, 0.20;
  return m;
}

// Lumped masses of TwoTets at density 6: A gives 1/4 to 0,1,2,3; B gives 2/4 to 0,1,2,4.
const std::vector<double> kTwoTetsLumped = {0.75, 0.75, 0.75, 0.25, 0.5};

// kron(M, I3), the 3#V × 3#V matrix a scalar mass matrix stands for.
Eigen::MatrixXd expand(const Eigen::MatrixXd& m) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3 * m.rows(), 3 * m.cols());
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.block<3, 3>(3 * i, 3 * j) = m(i, j) * Eigen::Matrix3d::Identity();
  }
  return out;
}

Mass<double> two_tets_consistent() {
  const TwoTets t;
  return Mass<double>::consistent(tetrahedral_mass_matrix<double>(t.mesh, t.rest, 6.0));
}

TEST(TetrahedralLumpedMasses, UnitTetrahedronGivesAQuarterOfItsMassToEachVertex) {
  const TetMesh mesh(4, {Tetrahedron{0, 1, 2, 3}});
  // ρ |V| / 4 = 3 · (1/6) / 4 = 0.125.
  const auto masses = tetrahedral_lumped_masses<double>(mesh, unit_tetrahedron(), 3.0);
  ASSERT_EQ(masses.size(), 4u);
  for (double m : masses) EXPECT_NEAR(m, 0.125, 1e-16);
}

TEST(TetrahedralLumpedMasses, UsesTheAbsoluteVolumeOfAnInvertedTetrahedron) {
  // (0, 2, 1, 3) is the unit tetrahedron with negative orientation: same |V| = 1/6.
  const TetMesh mesh(4, {Tetrahedron{0, 2, 1, 3}});
  const auto masses = tetrahedral_lumped_masses<double>(mesh, unit_tetrahedron(), 3.0);
  for (double m : masses) EXPECT_NEAR(m, 0.125, 1e-16);
}

TEST(TetrahedralLumpedMasses, TwoTetrahedraAccumulateOnSharedVertices) {
  const TwoTets t;
  const auto masses = tetrahedral_lumped_masses<double>(t.mesh, t.rest, 6.0);
  ASSERT_EQ(masses.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(masses[i], kTwoTetsLumped[i], 1e-15) << "vertex " << i;
  // ρ Σ|V| = 6 · (1/6 + 1/3) = 3.
  EXPECT_NEAR(total_volume<double>(t.mesh, t.rest), 0.5, 1e-15);
  EXPECT_NEAR(Mass<double>::lumped(masses).total_mass(), 3.0, 1e-14);
}

TEST(TetrahedralLumpedMasses, AnUnusedPointGetsNoMass) {
  const TetMesh mesh(5, {Tetrahedron{0, 1, 2, 3}});
  Points rest = unit_tetrahedron();
  rest.push_back(Vec3<double>(5, 5, 5));
  const auto masses = tetrahedral_lumped_masses<double>(mesh, rest, 3.0);
  EXPECT_EQ(masses[4], 0.0);
}

TEST(TetrahedralMassMatrix, UnitTetrahedronEntries) {
  const TetMesh mesh(4, {Tetrahedron{0, 1, 2, 3}});
  // ρ = 60, |V| = 1/6: ρV = 10, so ρV/10 = 1 on the diagonal and ρV/20 = 0.5 off it.
  const Eigen::MatrixXd m(tetrahedral_mass_matrix<double>(mesh, unit_tetrahedron(), 60.0));
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(m(i, j), i == j ? 1.0 : 0.5, 1e-14) << i << "," << j;
    // Row sum ρV/10 + 3 ρV/20 = ρV/4 = 2.5, the lumped mass.
    EXPECT_NEAR(m.row(i).sum(), 2.5, 1e-14);
  }
}

TEST(TetrahedralMassMatrix, TwoTetrahedraMatchTheHandAssembly) {
  const TwoTets t;
  const Eigen::MatrixXd m(tetrahedral_mass_matrix<double>(t.mesh, t.rest, 6.0));
  const Eigen::MatrixXd expected = two_tets_consistent_by_hand();
  ASSERT_EQ(m.rows(), 5);
  ASSERT_EQ(m.cols(), 5);
  EXPECT_LT((m - expected).cwiseAbs().maxCoeff(), 1e-15);
  // Row sums are the lumped masses ρ Σ|V|/4 (docs/sofa-components.md §3, lumping coefficient 2.5).
  for (Eigen::Index i = 0; i < 5; ++i) EXPECT_NEAR(m.row(i).sum(), kTwoTetsLumped[static_cast<std::size_t>(i)], 1e-15);
  EXPECT_EQ((m - m.transpose()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Mass, LumpedAccessors) {
  const auto mass = Mass<double>::lumped(kTwoTetsLumped);
  EXPECT_TRUE(mass.is_lumped());
  EXPECT_EQ(mass.size(), 5);
  ASSERT_EQ(mass.vertex_masses().size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(mass.vertex_masses()[i], kTwoTetsLumped[i]);
  EXPECT_DOUBLE_EQ(mass.total_mass(), 3.0);
}

TEST(Mass, ConsistentVertexMassesAreRowSums) {
  const auto mass = two_tets_consistent();
  EXPECT_FALSE(mass.is_lumped());
  EXPECT_EQ(mass.size(), 5);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(mass.vertex_masses()[i], kTwoTetsLumped[i], 1e-15);
  EXPECT_NEAR(mass.total_mass(), 3.0, 1e-14);
}

TEST(Mass, LumpedAddMdxAccumulatesFactorTimesMassTimesDx) {
  const auto mass = Mass<double>::lumped({2.0, 0.5});
  const Points dx = {Vec3<double>(1, -2, 3), Vec3<double>(4, 0, -8)};
  Points out = {Vec3<double>(10, 10, 10), Vec3<double>(-1, -1, -1)};
  mass.add_mdx(dx, out, -3.0);
  // out_0 = (10,10,10) - 3·2·(1,-2,3) = (4, 22, -8); out_1 = (-1,-1,-1) - 3·0.5·(4,0,-8) = (-7, -1, 11).
  EXPECT_EQ(out[0], Vec3<double>(4, 22, -8));
  EXPECT_EQ(out[1], Vec3<double>(-7, -1, 11));
}

TEST(Mass, ConsistentAddMdxAppliesTheScalarMatrixToEachAxis) {
  const auto mass = two_tets_consistent();
  Points dx(5);
  for (std::size_t i = 0; i < 5; ++i) dx[i] = Vec3<double>(double(i), 1.0, i == 3 ? 1.0 : 0.0);
  Points out(5, Vec3<double>(1, 1, 1));
  mass.add_mdx(dx, out, 2.0);
  const Eigen::VectorXd expected =
      Eigen::VectorXd::Ones(15) + 2.0 * expand(two_tets_consistent_by_hand()) * testing::flatten(dx);
  EXPECT_LT((testing::flatten(out) - expected).cwiseAbs().maxCoeff(), 1e-14);
  // One entry by hand: out_4.x = 1 + 2 (M_40·0 + M_41·1 + M_42·2 + M_43·3 + M_44·4)
  //                          = 1 + 2 (0.1 + 0.2 + 0 + 0.8) = 3.2.
  EXPECT_NEAR(out[4].x(), 3.2, 1e-14);
  // out_0.z = 1 + 2 M_03 = 1.1 (only vertex 3 has dx.z = 1).
  EXPECT_NEAR(out[0].z(), 1.1, 1e-15);
}

// multiply writes what add_mdx adds to zero, bit for bit, on one thread or two (3,001 points: more
// than one chunk of the parallel loop, the last one not a multiple of the four points the lumped
// product takes at a time).
TEST(Mass, MultiplyIsAddMdxIntoZeroOnAnyThreadCount) {
  const std::size_t n = 3001;
  std::vector<double> masses(n);
  Points dx(n);
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t i = 0; i < n; ++i) {
    masses[i] = 0.5 + std::sin(0.37 * double(i)) * 0.25;
    dx[i] = Vec3<double>(std::cos(0.1 * double(i)), -1.0 + 1e-3 * double(i), std::sin(0.7 * double(i)));
    const auto row = static_cast<Index>(i);
    triplets.emplace_back(row, row, 2.0 * masses[i]);
    if (i + 1 < n) {
      triplets.emplace_back(row, row + 1, 0.3 * masses[i]);
      triplets.emplace_back(row + 1, row, 0.3 * masses[i]);
    }
  }
  Eigen::SparseMatrix<double> matrix(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  for (const auto& mass : {Mass<double>::lumped(masses), Mass<double>::consistent(matrix)}) {
    Points expected(n, Vec3<double>::Zero());
    mass.add_mdx(dx, expected, -0.75);
    for (int threads : {1, 2}) {
      Points out(n, Vec3<double>(9, 9, 9));  // overwritten, not added to
      mass.multiply(dx, out, -0.75, threads);
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(out[i], expected[i]) << (mass.is_lumped() ? "lumped" : "consistent") << ", point " << i << ", "
                                       << threads << " threads";
      }
    }
  }
}

TEST(Mass, LumpedGravityIsMassTimesG) {
  const auto mass = Mass<double>::lumped({2.0, 0.5});
  Points f = {Vec3<double>(1, 0, 0), Vec3<double>(0, 0, 0)};
  mass.add_gravity(Vec3<double>(0, -9, 1), f);
  EXPECT_EQ(f[0], Vec3<double>(1, -18, 2));
  EXPECT_EQ(f[1], Vec3<double>(0, -4.5, 0.5));
}

TEST(Mass, ConsistentGravityUsesRowSums) {
  // MeshMatrixMass adds g times the lumped masses, the row sums of M (docs/sofa-components.md §3).
  const auto mass = two_tets_consistent();
  const Vec3<double> g(0.0, -10.0, 2.0);
  Points f(5, Vec3<double>::Zero());
  mass.add_gravity(g, f);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_LT((f[i] - kTwoTetsLumped[i] * g).norm(), 1e-13) << "vertex " << i;
  }
}

TEST(Mass, AddToMatrixPlacesScaledIdentityBlocksAtTheOffset) {
  const Index offset = 3;
  for (const bool lumped : {true, false}) {
    const auto mass = lumped ? Mass<double>::lumped(kTwoTetsLumped) : two_tets_consistent();
    const Eigen::MatrixXd scalar = lumped ? Eigen::MatrixXd(Eigen::VectorXd::Map(kTwoTetsLumped.data(), 5).asDiagonal())
                                          : two_tets_consistent_by_hand();
    TripletSink<double> sink;
    mass.add_to_matrix(sink, -0.5, offset);
    const Eigen::MatrixXd assembled(sink.to_sparse(3 * 5 + offset));
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(18, 18);
    expected.bottomRightCorner(15, 15) = -0.5 * expand(scalar);
    EXPECT_LT((assembled - expected).cwiseAbs().maxCoeff(), 1e-15) << (lumped ? "lumped" : "consistent");
  }
}

TEST(Mass, KineticEnergy) {
  Points v(5, Vec3<double>::Zero());
  for (std::size_t i = 0; i < 5; ++i) v[i].x() = double(i);
  // Lumped: 1/2 Σ m_i i² = 1/2 (0.75·1 + 0.75·4 + 0.25·9 + 0.5·16) = 1/2 · 14 = 7.
  EXPECT_NEAR(Mass<double>::lumped(kTwoTetsLumped).kinetic_energy(v), 7.0, 1e-14);
  // Consistent: v^T M v = Σ_i M_ii i² + 2 Σ_{i<j} M_ij i j
  //   = (0.3 + 1.2 + 0.9 + 3.2) + 2 (0.3 + 0.15 + 0.4 + 0.3 + 0.8 + 0) = 5.6 + 3.9 = 9.5; half is 4.75.
  EXPECT_NEAR(two_tets_consistent().kinetic_energy(v), 4.75, 1e-14);
  // The same along y and z: the scalar matrix acts on each axis.
  Points w(5, Vec3<double>::Zero());
  for (std::size_t i = 0; i < 5; ++i) w[i] = Vec3<double>(double(i), double(i), double(i));
  EXPECT_NEAR(two_tets_consistent().kinetic_energy(w), 3 * 4.75, 1e-13);
}

TEST(Mass, LumpedRejectsNegativeAndNonFiniteMasses) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {-1e-12, nan, inf, -inf}) {
    try {
      Mass<double>::lumped({1.0, bad, 2.0});
      ADD_FAILURE() << "accepted " << bad;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("vertex 1"), std::string::npos) << error.what();
    }
  }
  EXPECT_NO_THROW(Mass<double>::lumped({0.0, 1.0}));
}

TEST(Mass, ConsistentRejectsANonSquareOrNonFiniteMatrix) {
  EXPECT_THROW(Mass<double>::consistent(Eigen::SparseMatrix<double>(3, 4)), Error);
  Eigen::SparseMatrix<double> m = tetrahedral_mass_matrix<double>(TwoTets().mesh, TwoTets().rest, 6.0);
  m.coeffRef(3, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Mass<double>::consistent(m), Error);
  m.coeffRef(3, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Mass<double>::consistent(m), Error);
}

TEST(Mass, FloatInstantiationAgrees) {
  const TetMesh mesh(4, {Tetrahedron{0, 1, 2, 3}});
  const auto rest = testing::cast_points<float>(unit_tetrahedron());
  const auto masses = tetrahedral_lumped_masses<float>(mesh, rest, 3.0f);
  for (float m : masses) EXPECT_NEAR(m, 0.125f, 1e-7f);
}

}  // namespace
}  // namespace fastcorot
