// Constraint solvers (SOFA's Lagrangian constraint solvers): iterate on a ConstraintProblem until
// its blocks' updates change the violations by less than the tolerance. Defaults and stopping rules
// are SOFA's (GenericConstraintSolver.cpp): 1000 iterations, tolerance 1e-3 scaled by the row count
// unless scaleTolerance is off or allVerified on. Design: docs/constraints.md.
#pragma once

#include "fastcorot/constraint/constraint_problem.h"

#include <string>

namespace fastcorot {

template <class Real>
struct ConstraintSolverParameters {
  int max_iterations = 1000;
  Real tolerance = Real(1e-3);
  Real sor = 1;                 // successive over-relaxation
  Real regularization = 0;      // added to W's diagonal when above machine epsilon
  bool scale_tolerance = true;  // tolerance × rows
  bool all_verified = false;    // stop only when every block's error is below the tolerance
  // SOFA's useSVDForRegularization (built solvers): the regularisation only on the rows that take
  // part in W's near-null space, found by a singular value decomposition of W: singular values
  // below svd_value_factor × the largest, and on their vectors the rows whose entry exceeds
  // svd_vector_factor in magnitude.
  bool svd_regularization = false;
  Real svd_value_factor = Real(0.01);
  Real svd_vector_factor = Real(0.001);
};

// What one solve did.
struct ConstraintSolveReport {
  int iterations = 0;
  double error = 0;      // the last iteration's summed block errors (SOFA's currentError)
  double tolerance = 0;  // the tolerance it was compared with (scaled)
  bool converged = true;
};

template <class Real>
class ConstraintSolver {
 public:
  virtual ~ConstraintSolver() = default;
  // Solves `problem` in place (problem.f holds λ on return; W is not changed except for the
  // regularisation the solver adds).
  virtual ConstraintSolveReport solve(ConstraintProblem<Real>& problem) = 0;
  virtual const char* name() const = 0;
  // Whether SOFA's version is unbuilt (reads the corrections' block-diagonal compliance and
  // displacements rather than an assembled W: ConstraintCorrection::set_unbuilt).
  virtual bool unbuilt() const { return false; }
  // Whether SOFA's version stores λ on the states after its solve (GenericConstraintSolver's
  // family does; LCPConstraintSolver does not): what a nonlinear mapping's geometric stiffness
  // then reads.
  virtual bool stores_lambda() const { return true; }
  const ConstraintSolverParameters<Real>& parameters() const { return parameters_; }

 protected:
  explicit ConstraintSolver(ConstraintSolverParameters<Real> parameters);
  // The tolerance the summed error is compared with (SOFA: tolerance × rows when scaled).
  Real effective_tolerance(int rows) const;
  // One Gauss–Seidel sweep over the blocks in row order (SOFA's gaussSeidel_increment): for each
  // block, d = δ_free + W λ on its rows, its resolution, and its error (|W_jj Δλ_j| for one row, Σ_l
  // |W_bb Δλ|_l for a block, rescaled by a block's own tolerance). Returns the summed error; sets
  // `verified` false when a row's error exceeds `tolerance`.
  Real sweep(ConstraintProblem<Real>& problem, Real tolerance, bool& verified) const;
  // W's diagonal += the regularisation (on every row, or on the near-null space's rows with SVD).
  void regularize(ConstraintProblem<Real>& problem) const;
  // Regularisation, then each block's init (warm starts).
  void init_blocks(ConstraintProblem<Real>& problem) const;
  // Each block's store (what the next step starts from), after the solve.
  void store_blocks(ConstraintProblem<Real>& problem) const;

  ConstraintSolverParameters<Real> parameters_;
};

// SOFA's BlockGaussSeidelConstraintSolver (and the default of GenericConstraintSolver): projected
// block Gauss–Seidel on the built W, warm-started by the resolutions that keep their λ.
template <class Real>
class BlockGaussSeidelSolver : public ConstraintSolver<Real> {
 public:
  explicit BlockGaussSeidelSolver(ConstraintSolverParameters<Real> parameters) : ConstraintSolver<Real>(parameters) {}
  ConstraintSolveReport solve(ConstraintProblem<Real>& problem) override;
  const char* name() const override { return "BlockGaussSeidelConstraintSolver"; }

 protected:
  bool warm_start_ = true;
};

// SOFA's UnbuiltGaussSeidelConstraintSolver: the same sweep with λ starting from zero every step
// (SOFA computes W λ through the corrections instead of W; with the corrections here the two agree).
template <class Real>
class UnbuiltGaussSeidelSolver final : public BlockGaussSeidelSolver<Real> {
 public:
  explicit UnbuiltGaussSeidelSolver(ConstraintSolverParameters<Real> parameters) : BlockGaussSeidelSolver<Real>(parameters) {
    this->warm_start_ = false;
  }
  const char* name() const override { return "UnbuiltGaussSeidelConstraintSolver"; }
  bool unbuilt() const override { return true; }
};

// SOFA's NNCGConstraintSolver (nonsmooth nonlinear conjugate gradient): Gauss–Seidel sweeps, each
// followed by a conjugate step along p with β = |Δλ_new|² / |Δλ_old|² (p reset when β > 1); also
// stops when |Δλ| falls below the tolerance. Warm-started as BlockGaussSeidel; no over-relaxation.
template <class Real>
class NNCGSolver final : public ConstraintSolver<Real> {
 public:
  explicit NNCGSolver(ConstraintSolverParameters<Real> parameters) : ConstraintSolver<Real>(parameters) {}
  ConstraintSolveReport solve(ConstraintProblem<Real>& problem) override;
  const char* name() const override { return "NNCGConstraintSolver"; }
};

// SOFA's PreconditionedConjugateResidual: conjugate residuals on the Jacobi-scaled W (every row
// treated as bilateral: no projection, no warm start), at most min(maxIterations, rows)
// iterations. Its stopping measure is SOFA's as written: Σ_blocks sqrt(Σ_rows r_i²) with r_i the
// residual's entry at the iteration index i, not at the row (kept, as it decides when SOFA stops).
template <class Real>
class PreconditionedConjugateResidualSolver final : public ConstraintSolver<Real> {
 public:
  explicit PreconditionedConjugateResidualSolver(ConstraintSolverParameters<Real> parameters) : ConstraintSolver<Real>(parameters) {}
  ConstraintSolveReport solve(ConstraintProblem<Real>& problem) override;
  const char* name() const override { return "PreconditionedConjugateResidual"; }
};

// SOFA's ImprovedJacobiConstraintSolver: every block resolved against the same violations of the
// previous iteration (Jacobi), λ starting from zero (or a resolution's warm start, against δ_free
// alone in the first iteration, as SOFA does). Options: the violations scaled by ρ = factor ·
// min(1, 1.8 / r), r SOFA's spectral measure of W (the largest squared eigenvalue modulus, as its
// code computes it), and a momentum step λ += β Δλ_previous with β = min(1, (i / maxIterations)^speed).
// Stops when the summed block errors fall below the tolerance, never after the first iteration.
template <class Real>
class ImprovedJacobiSolver final : public ConstraintSolver<Real> {
 public:
  struct Options {
    bool spectral_correction = false;   // useSpectralCorrection
    Real spectral_factor = 1;           // spectralCorrectionFactor
    bool conjugate_residue = false;     // useConjugateResidue
    Real conjugate_residue_speed = 10;  // conjugateResidueSpeedFactor
  };
  ImprovedJacobiSolver(ConstraintSolverParameters<Real> parameters, Options options);
  ConstraintSolveReport solve(ConstraintProblem<Real>& problem) override;
  const char* name() const override { return "ImprovedJacobiConstraintSolver"; }

 private:
  Options options_;
};

}  // namespace fastcorot
