// The constraint problem of one step, as SOFA's constraint solvers pose it (GenericConstraintProblem):
// n rows, the compliance W = H A⁻¹ Hᵀ (n × n, dense), the free violations δ_free, the unknowns λ,
// and the rows cut into blocks, each with its resolution (SOFA's ConstraintResolution: the local
// update of the block's λ given the violations d = δ_free + W λ). λ is an impulse (SOFA's unit:
// force times the step). Design: docs/constraints.md.
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <array>
#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
using DenseMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
template <class Real>
using DenseVector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

// The local update of one block of rows (SOFA's ConstraintResolution): `line` is the block's first
// row; w the problem's W; d the current violations (δ_free + W λ), f the unknowns.
template <class Real>
class ConstraintResolution {
 public:
  explicit ConstraintResolution(int lines, Real tolerance = 0) : lines_(lines), tolerance_(tolerance) {}
  virtual ~ConstraintResolution() = default;
  int lines() const { return lines_; }
  // The block's own tolerance (0: the solver's), as SOFA's getTolerance.
  Real tolerance() const { return tolerance_; }
  // Before the iterations: what the update needs from W, and λ's warm start.
  virtual void init(int line, const DenseMatrix<Real>& w, Real* f) {
    static_cast<void>(line), static_cast<void>(w), static_cast<void>(f);
  }
  virtual void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real* dfree) = 0;
  // After the solve: what the next step starts from.
  virtual void store(int line, const Real* f) { static_cast<void>(line), static_cast<void>(f); }

 private:
  int lines_;
  Real tolerance_;
};

// Three rows held at zero violation (SOFA's BilateralConstraintResolution3Dof): λ -= load W_bb⁻¹ d,
// W_bb the block's 3×3 diagonal block; λ starts from `previous` and is kept there (null: from 0).
template <class Real>
class BilateralResolution3 final : public ConstraintResolution<Real> {
 public:
  explicit BilateralResolution3(Vec3<Real>* previous = nullptr, Real load = 1)
      : ConstraintResolution<Real>(3), previous_(previous), load_(load) {}
  void init(int line, const DenseMatrix<Real>& w, Real* f) override;
  void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real* dfree) override;
  void store(int line, const Real* f) override;

 private:
  Vec3<Real>* previous_;
  Real load_;
  Mat3<Real> inverse_ = Mat3<Real>::Zero();
};

// N rows held at zero violation (SOFA's BilateralConstraintResolutionNDof): λ -= W_bb⁻¹ d by an
// LDLᵀ of the block; no warm start.
template <class Real>
class BilateralResolutionN final : public ConstraintResolution<Real> {
 public:
  explicit BilateralResolutionN(int lines) : ConstraintResolution<Real>(lines) {}
  void init(int line, const DenseMatrix<Real>& w, Real* f) override;
  void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real* dfree) override;

 private:
  Eigen::LDLT<Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>> block_;
};

// One row held at zero violation (SOFA's BilateralConstraintResolution without a warm start):
// λ -= d / W_jj.
template <class Real>
class BilateralResolution1 final : public ConstraintResolution<Real> {
 public:
  BilateralResolution1() : ConstraintResolution<Real>(1) {}
  void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real*) override { f[line] -= d[line] / w(line, line); }
};

// One row that may only push (SOFA's UnilateralConstraintResolution): λ ← max(0, λ - d / W_jj).
template <class Real>
class UnilateralResolution final : public ConstraintResolution<Real> {
 public:
  UnilateralResolution() : ConstraintResolution<Real>(1) {}
  void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real* dfree) override;
};

template <class Real>
struct ConstraintProblem {
  DenseMatrix<Real> w;      // compliance
  DenseVector<Real> dfree;  // violations at the free motion
  DenseVector<Real> f;      // λ (impulses)
  DenseVector<Real> d;      // work: violations with λ
  // One entry per block, in row order; first_line[b] is block b's first row.
  std::vector<std::unique_ptr<ConstraintResolution<Real>>> resolutions;
  std::vector<int> first_line;
  // Work for the sweeps: the columns where block b's rows of W may not be zero, as spans
  // [spans[k][0], spans[k][1]) for k in [span_begin[b], span_begin[b + 1]). W is exactly zero
  // between rows on no common object (no correction ever adds there), so that a row's product
  // with λ skips those columns; find_column_spans() makes them from W.
  std::vector<int> span_begin;
  std::vector<std::array<int, 2>> spans;

  int size() const { return static_cast<int>(dfree.size()); }
  // n rows, everything zero, no blocks.
  void clear(int rows);
  // Appends a block starting where the last one ended.
  void add_block(std::unique_ptr<ConstraintResolution<Real>> resolution);
  // Throws fastcorot::Error when the blocks do not cover the rows exactly.
  void check_blocks() const;
  // The spans above, from W as it is now (gaps of fewer than a few columns are kept in a span).
  void find_column_spans();
  // Row `row` of W times λ over the spans of `block` (the block holding the row): the full row's
  // product to round-off.
  Real row_times_lambda(int row, std::size_t block) const;
};

}  // namespace fastcorot
