// SOFA's LCPConstraintSolver: a projected Gauss–Seidel on the built W that reads every three rows as
// one frictional contact (normal, then two tangents; SOFA's nlcp_gaussseidel) when mu > 0, or every
// row as one frictionless contact (gaussSeidelLCP1) when mu = 0. It ignores the constraints'
// resolutions, as SOFA does: a bilateral constraint's rows are solved as contacts under it.
// Design and differences: docs/constraints.md.
#pragma once

#include "fastcorot/constraint/constraint_solvers.h"

namespace fastcorot {

template <class Real>
class LCPConstraintSolver final : public ConstraintSolver<Real> {
 public:
  struct Options {
    Real mu = Real(0.6);  // one friction coefficient for every contact (SOFA's default)
    Real min_w = 0;       // contacts whose W_nn is at most this carry no force (0: off)
    Real max_f = 0;       // contacts whose normal λ reaches this are dropped at convergence (0: off)
  };
  // Uses the parameters' maxIterations (SOFA's maxIt), tolerance and regularisation; SOFA's
  // tolerance is not scaled by the row count here but by the number of contacts plus one (mu > 0)
  // or not at all (mu = 0).
  LCPConstraintSolver(ConstraintSolverParameters<Real> parameters, Options options);
  ConstraintSolveReport solve(ConstraintProblem<Real>& problem) override;
  const char* name() const override { return "LCPConstraintSolver"; }
  bool stores_lambda() const override { return false; }

 private:
  ConstraintSolveReport solve_with_friction(ConstraintProblem<Real>& problem) const;
  ConstraintSolveReport solve_frictionless(ConstraintProblem<Real>& problem) const;

  Options options_;
};

}  // namespace fastcorot
