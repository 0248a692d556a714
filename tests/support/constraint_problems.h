// Small constraint problems for the solvers' tests: random well-conditioned compliances, bilateral
// problems, and the complementarity solution of unilateral rows found by enumerating active sets
// (an independent reference for projected Gauss–Seidel and LCP solvers).
#pragma once

#include "fastcorot/constraint/constraint_problem.h"

#include <Eigen/LU>

#include <memory>
#include <optional>
#include <random>
#include <vector>

namespace fastcorot::testing {

// A random symmetric positive definite n × n matrix (well conditioned: diagonally dominant).
inline DenseMatrix<double> spd(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) a(i, j) = uniform(random);
  }
  Eigen::MatrixXd w = a * a.transpose() * 0.2 + 2.0 * Eigen::MatrixXd::Identity(n, n);
  return w;
}

inline DenseVector<double> random_vector(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  DenseVector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = uniform(random);
  return v;
}

// `dfree.size() / 3` bilateral 3-row blocks on W, δ_free; warm starts kept in `previous`.
inline ConstraintProblem<double> bilateral_problem(const DenseMatrix<double>& w, const DenseVector<double>& dfree,
                                                   std::vector<Vec3<double>>& previous) {
  ConstraintProblem<double> problem;
  problem.clear(static_cast<int>(dfree.size()));
  problem.w = w;
  problem.dfree = dfree;
  previous.resize(static_cast<std::size_t>(dfree.size() / 3), Vec3<double>::Zero());
  for (auto& p : previous) problem.add_block(std::make_unique<BilateralResolution3<double>>(&p));
  return problem;
}

// λ >= 0, d = δ + W λ >= 0, λ·d = 0: tries every active set (rows with λ > 0) and returns the
// first that satisfies all three conditions (small n only: 2ⁿ sets).
inline std::optional<Eigen::VectorXd> complementarity_solution(const Eigen::MatrixXd& w, const Eigen::VectorXd& dfree) {
  const int n = static_cast<int>(dfree.size());
  for (int set = 0; set < (1 << n); ++set) {
    std::vector<int> active;
    for (int i = 0; i < n; ++i) {
      if (set & (1 << i)) active.push_back(i);
    }
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    if (!active.empty()) {
      const auto m = static_cast<Eigen::Index>(active.size());
      Eigen::MatrixXd a(m, m);
      Eigen::VectorXd b(m);
      for (Eigen::Index r = 0; r < m; ++r) {
        b[r] = -dfree[active[static_cast<std::size_t>(r)]];
        for (Eigen::Index c = 0; c < m; ++c) a(r, c) = w(active[static_cast<std::size_t>(r)], active[static_cast<std::size_t>(c)]);
      }
      const Eigen::VectorXd x = a.lu().solve(b);
      for (Eigen::Index r = 0; r < m; ++r) f[active[static_cast<std::size_t>(r)]] = x[r];
    }
    const Eigen::VectorXd d = dfree + w * f;
    if ((f.array() >= -1e-15).all() && (d.array() >= -1e-12).all()) return f;
  }
  return std::nullopt;
}

}  // namespace fastcorot::testing
