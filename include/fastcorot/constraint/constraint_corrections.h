// Constraint corrections (SOFA's Sofa/Component/Constraint/Lagrangian/Correction): how an object
// answers constraint impulses. Each adds its compliance to W (W += factor H A⁻¹ Hᵀ on its columns
// of H) and, once λ is known, corrects the object's free motion by dx = A⁻¹ Hᵀλ:
// x = x_free + (position factor) dx, v = v_free + (velocity factor) dx. Design: docs/constraints.md.
#pragma once

#include "fastcorot/constraint/constraint_problem.h"
#include "fastcorot/constraint/lagrangian_constraints.h"
#include "fastcorot/sim/simulation.h"

#include <Eigen/SparseCore>

#include <span>
#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
class ConstraintCorrection {
 public:
  ConstraintCorrection(std::string where, std::size_t object) : where_(std::move(where)), object_(object) {}
  virtual ~ConstraintCorrection() = default;
  const std::string& where() const { return where_; }
  std::size_t object() const { return object_; }
  // W += its compliance in constraint space; `ht` is Hᵀ on the object's blocks, projected.
  virtual void add_compliance(SimulatedObject<Real>& object, const Eigen::SparseMatrix<Real>& ht, ConstraintOrder order,
                              Real dt, DenseMatrix<Real>& w) = 0;
  // Corrects the object (holding its free motion) for the impulses Hᵀλ on its blocks.
  virtual void correct(SimulatedObject<Real>& object, std::span<const Vec3<Real>> impulse, ConstraintOrder order, Real dt) = 0;
  // Whether the problem goes to an unbuilt solver (SOFA's UnbuiltGaussSeidelConstraintSolver, which
  // reads each correction's block-diagonal compliance and displacements instead of W; a correction
  // whose unbuilt path differs from its W gives that compliance then).
  void set_unbuilt(bool unbuilt) { unbuilt_ = unbuilt; }

 protected:
  bool unbuilt_ = false;

 private:
  std::string where_;
  std::size_t object_;
};

// SOFA's LinearSolverConstraintCorrection (and GenericConstraintCorrection, which gathers H through
// the mappings as the rows here always are): A is the matrix of the object's last free-motion step,
// solved by its own linear solver. With a direct solver, W's block is Zᵀ D⁻¹ Z with Z = L⁻¹ P Hᵀ
// by sparse triangular solves on its factorisation; with an iterative one, one solve per row.
// `compliance_factor` is GenericConstraintCorrection's complianceFactor (1 otherwise);
// `regularization` is added to the diagonal of its rows.
template <class Real>
class LinearSolverConstraintCorrection final : public ConstraintCorrection<Real> {
 public:
  LinearSolverConstraintCorrection(std::string where, std::size_t object, Real regularization = 0, Real compliance_factor = 1);
  void add_compliance(SimulatedObject<Real>& object, const Eigen::SparseMatrix<Real>& ht, ConstraintOrder order, Real dt,
                      DenseMatrix<Real>& w) override;
  void correct(SimulatedObject<Real>& object, std::span<const Vec3<Real>> impulse, ConstraintOrder order, Real dt) override;

 private:
  IntegrationFactors<Real> factors(const SimulatedObject<Real>& object, Real dt) const;

  Real regularization_;
  Real compliance_factor_;
  std::vector<Vec3<Real>> dx_;
};

// SOFA's UncoupledConstraintCorrection on a range of an object's state (one MechanicalObject): a
// fixed compliance per point, no coupling between points. Points: c I₃ (`compliance` per point, or
// `defaultCompliance`); rigid bodies: c₀ I₃ on the centre and a symmetric 3×3 on the rotation
// (SOFA's 7 numbers: c₀, then the rotation's upper triangle). W_ij += factor Σ_points n_i·C n_j
// with factor h (1 in velocity order), or 1 when not `use_ode_factors` and for an unbuilt solver
// (SOFA's getBlockDiagonalCompliance and setConstraintDForce leave the ODE factor out, so its
// unbuilt Gauss–Seidel sees W / h in position order; kept); correction dx = C Hᵀλ,
// x += h dx and v += dx, or (not use_ode_factors) x += position_factor dx and
// v += velocity_factor / dt dx.
template <class Real>
class UncoupledConstraintCorrection final : public ConstraintCorrection<Real> {
 public:
  struct Parameters {
    Index offset = 0;                 // the range of the object's blocks it covers
    std::vector<Mat3<Real>> compliance;  // one 3×3 per block of the range
    bool use_ode_factors = true;
    Real position_factor = 1;
    Real velocity_factor = 1;
  };
  UncoupledConstraintCorrection(std::string where, std::size_t object, Parameters parameters);
  void add_compliance(SimulatedObject<Real>& object, const Eigen::SparseMatrix<Real>& ht, ConstraintOrder order, Real dt,
                      DenseMatrix<Real>& w) override;
  void correct(SimulatedObject<Real>& object, std::span<const Vec3<Real>> impulse, ConstraintOrder order, Real dt) override;
  const Parameters& parameters() const { return parameters_; }

 private:
  Parameters parameters_;
};

}  // namespace fastcorot
