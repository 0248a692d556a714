// BlockLDLT: the 3×3-block LDLᵀ against the scalar reference (Eigen's SimplicialLDLT) and dense
// linear algebra, on matrices with an FEM pattern (a grid's neighbours), held points (identity
// blocks), projected blocks (entries left out of a nonzero block), indefinite and singular
// matrices, and lower-only input.
#include "fastcorot/sim/block_ldlt.h"

#include "fastcorot/core/error.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace fastcorot {
namespace {

using Dense = Eigen::MatrixXd;
using Sparse = Eigen::SparseMatrix<double>;

// A symmetric matrix on an nx × ny × nz grid of points, coupling each point to its 26
// neighbours with random 3×3 blocks; `shift` on the diagonal (large: positive definite). Points
// in `held` get an identity block and no coupling (SOFA's treatment of fixed points); in
// `projected` the x row and column are cleared except a 1 on the diagonal.
Sparse grid_matrix(int nx, int ny, int nz, double shift, unsigned seed, const std::vector<int>& held = {},
                   const std::vector<int>& projected = {}) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = nx * ny * nz;
  Dense a = Dense::Zero(3 * n, 3 * n);
  const auto id = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (int dk = 0; dk <= 1; ++dk) {
          for (int dj = -1; dj <= 1; ++dj) {
            for (int di = -1; di <= 1; ++di) {
              const int i2 = i + di, j2 = j + dj, k2 = k + dk;
              if (i2 < 0 || j2 < 0 || i2 >= nx || j2 >= ny || k2 >= nz) continue;
              const int p = id(i, j, k), q = id(i2, j2, k2);
              if (q < p) continue;
              for (int r = 0; r < 3; ++r) {
                for (int c = 0; c < 3; ++c) {
                  const double v = u(rng);
                  a(3 * p + r, 3 * q + c) += v;
                  a(3 * q + c, 3 * p + r) += v;
                }
              }
            }
          }
        }
      }
    }
  }
  a.diagonal().array() += shift;
  for (int p : held) {
    a.middleRows(3 * p, 3).setZero();
    a.middleCols(3 * p, 3).setZero();
    a.block(3 * p, 3 * p, 3, 3).setIdentity();
  }
  for (int p : projected) {
    a.row(3 * p).setZero();
    a.col(3 * p).setZero();
    a(3 * p, 3 * p) = 1;
  }
  Sparse s = a.sparseView();
  s.makeCompressed();
  return s;
}

double relative(const Eigen::VectorXd& x, const Eigen::VectorXd& y) { return (x - y).norm() / y.norm(); }

// A⁻¹ b through a BlockLDLT analysed and factorised for `a` (which must factorise).
Eigen::VectorXd solved(BlockLDLT<double>& ldlt, const Sparse& a, const Eigen::VectorXd& b) {
  ldlt.analyse(a);
  EXPECT_TRUE(ldlt.factorise(a));
  Eigen::VectorXd x(a.rows());
  ldlt.solve(b.data(), x.data());
  return x;
}

TEST(BlockLDLT, SolvesAsTheScalarLDLTAndTheDenseSolve) {
  const Sparse a = grid_matrix(6, 4, 5, 30.0, 1);
  BlockLDLT<double> ldlt;
  const Eigen::VectorXd b = Eigen::VectorXd::Random(a.rows());
  const Eigen::VectorXd x = solved(ldlt, a, b);
  const Eigen::VectorXd dense = Dense(a).ldlt().solve(b);
  Eigen::SimplicialLDLT<Sparse> scalar(a);
  EXPECT_LT(relative(x, dense), 1e-12);
  EXPECT_LT(relative(x, scalar.solve(b)), 1e-12);
  EXPECT_LT((Dense(a) * x - b).norm() / b.norm(), 1e-12);
  // Fill: the block factor's nonzeros (blocks below the diagonal × 9, plus D's blocks) stay within
  // a factor 1.5 of the scalar factor's (both with AMD; the block one orders points).
  const double scalar_nonzeros = static_cast<double>(scalar.matrixL().nestedExpression().nonZeros() + a.rows());
  EXPECT_LT(9.0 * ldlt.factor_blocks() + 6.0 * a.rows() / 3, 1.5 * scalar_nonzeros);
}

TEST(BlockLDLT, ReadsTheLowerTriangleAndTreatsHeldAndProjectedPoints) {
  const Sparse full = grid_matrix(4, 3, 3, 25.0, 2, {0, 5, 17}, {3, 8});
  const Sparse lower = full.triangularView<Eigen::Lower>();
  BlockLDLT<double> from_full, from_lower;
  from_full.analyse(full);
  from_lower.analyse(lower);
  ASSERT_TRUE(from_full.factorise(full));
  ASSERT_TRUE(from_lower.factorise(lower));
  Eigen::VectorXd b = Eigen::VectorXd::Random(full.rows());
  b.segment(0, 3).setZero();  // a projected right-hand side at a held point
  Eigen::VectorXd x(full.rows()), y(full.rows());
  from_full.solve(b.data(), x.data());
  from_lower.solve(b.data(), y.data());
  EXPECT_LT(relative(x, Dense(full).ldlt().solve(b)), 1e-12);
  EXPECT_EQ(x, y);
  EXPECT_EQ(x.segment(0, 3), Eigen::Vector3d::Zero());
}

TEST(BlockLDLT, FactorisesIndefiniteMatricesAsTheScalarLDLTDoes) {
  // A small shift (0.5): random symmetric blocks, indefinite; LDLᵀ without pivoting still works
  // (nonzero pivots).
  const Sparse a = grid_matrix(3, 3, 2, 0.5, 3);
  const Dense dense(a);
  Eigen::SelfAdjointEigenSolver<Dense> eigen(dense);
  ASSERT_LT(eigen.eigenvalues().minCoeff(), 0);  // the test's premise
  BlockLDLT<double> ldlt;
  const Eigen::VectorXd b = Eigen::VectorXd::Random(a.rows());
  const Eigen::VectorXd x = solved(ldlt, a, b);
  EXPECT_LT((dense * x - b).norm() / b.norm(), 1e-9);
  // The compliance through D⁻¹ blocks (not a rank update) against the dense inverse.
  const Sparse columns = Dense::Random(a.rows(), 5).sparseView();
  const Dense expected = Dense(columns).transpose() * dense.inverse() * Dense(columns);
  EXPECT_LT((ldlt.compliance(columns) - expected).norm() / expected.norm(), 1e-9);
}

TEST(BlockLDLT, RefusesSingularMatricesAndBadShapes) {
  Sparse a = grid_matrix(3, 2, 2, 20.0, 4, {4});
  a.coeffRef(13, 13) = 0;  // the held point's identity block loses a pivot
  a.prune(0.0);
  BlockLDLT<double> ldlt;
  ldlt.analyse(a);
  EXPECT_FALSE(ldlt.factorise(a));
  Dense nan = Dense(grid_matrix(2, 2, 2, 20.0, 5));
  nan(4, 4) = std::numeric_limits<double>::quiet_NaN();
  const Sparse with_nan = nan.sparseView();
  ldlt.analyse(with_nan);
  try {
    ldlt.factorise(with_nan);
    ADD_FAILURE() << "a NaN entry was factorised";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("non-finite entry"), std::string::npos) << error.what();
  }
  EXPECT_THROW(ldlt.analyse(Sparse(7, 7)), Error);
  Sparse uncompressed = grid_matrix(2, 2, 2, 20.0, 5);
  uncompressed.uncompress();
  EXPECT_THROW(ldlt.analyse(uncompressed), Error);
  // A matrix of another pattern than the analysed one is refused, not read out of bounds.
  ldlt.analyse(grid_matrix(2, 2, 2, 20.0, 5));
  EXPECT_THROW(ldlt.factorise(grid_matrix(3, 2, 2, 20.0, 5)), Error);
}

TEST(BlockLDLT, RefactorisesNewValuesAndReanalysesNewPatterns) {
  BlockLDLT<double> ldlt;
  const Sparse first = grid_matrix(5, 3, 3, 30.0, 8);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(first.rows());
  solved(ldlt, first, b);
  // Same pattern, new values: factorise again without a new analysis.
  const Sparse second = grid_matrix(5, 3, 3, 45.0, 9);
  ASSERT_TRUE(ldlt.factorise(second));
  Eigen::VectorXd x(second.rows());
  ldlt.solve(b.data(), x.data());
  EXPECT_LT(relative(x, Dense(second).ldlt().solve(b)), 1e-12);
  // A new pattern and size: analysed anew.
  const Sparse third = grid_matrix(3, 4, 2, 30.0, 10, {1});
  const Eigen::VectorXd c = Eigen::VectorXd::Random(third.rows());
  EXPECT_LT(relative(solved(ldlt, third, c), Dense(third).ldlt().solve(c)), 1e-12);
  // No column with an entry: a zero compliance.
  EXPECT_EQ(ldlt.compliance(Sparse(third.rows(), 50)), Dense::Zero(50, 50));
}

TEST(BlockLDLT, ComplianceMatchesTheDenseProductOnAnyThreadCount) {
  const Sparse a = grid_matrix(8, 3, 3, 40.0, 6, {0, 1, 2});
  BlockLDLT<double> ldlt;
  ldlt.analyse(a);
  ASSERT_TRUE(ldlt.factorise(a));
  // Constraint-like columns: three rows on one point (unit axes), and a few spread over points.
  std::vector<Eigen::Triplet<double>> entries;
  int column = 0;
  for (int point : {5, 40, 71}) {
    for (int axis = 0; axis < 3; ++axis) entries.emplace_back(3 * point + axis, column++, 1.0);
  }
  for (int c = 0; c < 4; ++c, ++column) {
    for (int point : {10 + c, 50 - c}) entries.emplace_back(3 * point + c % 3, column, 0.5 + c);
  }
  Sparse columns(a.rows(), column);
  columns.setFromTriplets(entries.begin(), entries.end());
  const Dense c(columns);
  const Dense expected = c.transpose() * Dense(a).ldlt().solve(c);
  const Dense one = ldlt.compliance(columns, 1);
  EXPECT_LT((one - expected).norm() / expected.norm(), 1e-12);
  EXPECT_EQ(one, ldlt.compliance(columns, 2));
}

TEST(BlockLDLT, FloatAgreesWithDoubleToSinglePrecision) {
  const Sparse a = grid_matrix(4, 4, 3, 30.0, 7);
  const Eigen::SparseMatrix<float> af = a.cast<float>();
  BlockLDLT<float> ldlt;
  ldlt.analyse(af);
  ASSERT_TRUE(ldlt.factorise(af));
  const Eigen::VectorXd b = Eigen::VectorXd::Random(a.rows());
  const Eigen::VectorXf bf = b.cast<float>();
  Eigen::VectorXf x(a.rows());
  ldlt.solve(bf.data(), x.data());
  EXPECT_LT(relative(x.cast<double>(), Dense(a).ldlt().solve(b)), 1e-5);
}

}  // namespace
}  // namespace fastcorot
