// SOFA's UnilateralLagrangianConstraint<Vec3> (Sofa/Component/Constraint/Lagrangian/Model:
// BaseContactLagrangianConstraint.inl, UnilateralLagrangianConstraint.{inl,cpp}), the constraint
// that SOFA's FrictionContactConstraint response creates for one pair of collision models each
// step: per contact a normal row that may only push and, with friction (mu > 0), two tangent rows
// held inside Coulomb's disk. The collision layer fills its contacts at the step's start
// (ContactPipeline); the loop prepares, builds and solves it as any other constraint.
//
// A contact joins point Q on the first model (the detection's point[0]) and point P on the second
// (point[1]), n the unit normal from Q to P and d the contact distance. Each point is a weighted sum
// of collision points, themselves the object's points or mapped from them (SOFA's contact mapper
// over the collision model's mapping): `blocks` are its rows of J on the object's blocks, so that
// the point moves by Σ J_b v_b. Rows, in SOFA's frame t = (n_z, n_x, n_y), s = |n × t|⁻¹ n × t,
// t ← -n × s: n (and t, s) on P, their opposites on Q.
// Violations (position order): δ_n = (P_f - Q_f)·n - d with P_f = P + h Σ J_b v_free,b (SOFA's
// linearised free positions of mapped states); δ_t, δ_s the tangential displacement, measured from
// where the gap crosses zero during the step when it does (SOFA's getPositionViolation).
// Velocity order: δ_n = (v_P - v_Q)·n + ((P - Q)·n - d)/h, δ_t = (v_P - v_Q)·t.
// Resolutions: UnilateralResolution without friction, UnilateralFrictionResolution with it.
// Design: docs/collision.md.
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

// One side of a contact: a point of a simulated object (or a still one, with no blocks).
template <class Real>
struct ContactSide {
  std::size_t object = 0;
  bool still = false;
  Vec3<Real> position;                              // at the step's start
  std::vector<std::pair<Index, Mat3<Real>>> blocks;  // its rows of J on the object's blocks
};

// Where a contact side goes in the free motion: its free velocity J v_free and its free position
// x + h J v_free (SOFA's linearised free positions of mapped states); zero motion for a still side.
template <class Real>
struct ContactSideMotion {
  Vec3<Real> free_position = Vec3<Real>::Zero();
  Vec3<Real> free_velocity = Vec3<Real>::Zero();
};
template <class Real>
ContactSideMotion<Real> free_motion(const ContactSide<Real>& side, std::span<const SimulatedObject<Real>> objects, Real dt);

template <class Real>
struct UnilateralContact {
  ContactSide<Real> first, second;  // Q (the first model's point), P (the second's)
  Vec3<Real> normal;                // unit, from Q to P
  Real distance = 0;                // kept between P and Q along n
};

// SOFA's UnilateralConstraintResolutionWithFriction: the normal impulse first (λ_n -= d_n / W_nn,
// all three zero when it would pull), then the tangent impulses by one shared diagonal step
// (2 / (W_tt + W_ss)) after their violations took the normal change in, scaled back into the disk
// |λ_t| ≤ mu λ_n. No warm start (SOFA passes none).
template <class Real>
class UnilateralFrictionResolution final : public ConstraintResolution<Real> {
 public:
  UnilateralFrictionResolution(Real mu, Real tolerance) : ConstraintResolution<Real>(3, tolerance), mu_(mu) {}
  void init(int line, const DenseMatrix<Real>& w, Real* f) override;
  void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real* dfree) override;

 private:
  Real mu_;
  Real w_nn_ = 0, w_nt_ = 0, w_ns_ = 0, w_tt_ = 0, w_ss_ = 0;
};

// SOFA's AugmentedLagrangianResolutionWithFriction (AugmentedLagrangianConstraint.cpp): the normal
// impulse moved by −ε d_n (all three zero when it would pull), the tangent ones by −ε d_t; kept when
// inside the disk |λ_t| < mu |λ_n|, else moved instead by −mu ε d_n d_t / |d_t| from where they
// were. W is not used (SOFA reads it and leaves it).
template <class Real>
class AugmentedLagrangianFrictionResolution final : public ConstraintResolution<Real> {
 public:
  AugmentedLagrangianFrictionResolution(Real mu, Real epsilon, Real tolerance)
      : ConstraintResolution<Real>(3, tolerance), mu_(mu), epsilon_(epsilon) {}
  void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real* dfree) override;

 private:
  Real mu_, epsilon_;
};

template <class Real>
class UnilateralLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  struct Parameters {
    Real mu = Real(0.8);  // FrictionContactConstraint's mu: tangent rows when > 0
    Real tolerance = 0;   // its tol: the friction blocks' own tolerance (0: the solver's)
    // SOFA's AugmentedLagrangianResponseConstraint (AugmentedLagrangianConstraint): the same rows,
    // solved by AugmentedLagrangianFrictionResolution with penalty factor `epsilon` when mu > 0
    // (without friction its resolution is UnilateralResolution's).
    bool augmented = false;
    Real epsilon = 0;
  };
  // Throws fastcorot::Error for a negative or non-finite mu, tolerance or epsilon.
  UnilateralLagrangianConstraint(std::string where, Parameters parameters);

  // This step's contacts (the collision stage sets them before the free motion).
  void set_contacts(std::vector<UnilateralContact<Real>> contacts) { contacts_ = std::move(contacts); }
  const std::vector<UnilateralContact<Real>>& contacts() const { return contacts_; }
  const Parameters& parameters() const { return parameters_; }

  std::vector<ConstraintPoints<Real>*> point_sets() override { return {}; }
  void prepare(std::span<const SimulatedObject<Real>> objects, Real dt) override;
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  void draw(ConstraintDrawer<Real>& drawer) const override;  // constraint_drawing.cpp

  // Rows per contact: 3 with friction, else 1.
  int rows_per_contact() const { return parameters_.mu > 0 ? 3 : 1; }
  // The tangent directions SOFA builds from a normal.
  static void tangents(const Vec3<Real>& n, Vec3<Real>& t, Vec3<Real>& s);

 private:
  Parameters parameters_;
  std::vector<UnilateralContact<Real>> contacts_;
  std::vector<std::array<ContactSideMotion<Real>, 2>> motion_;  // Q's, P's
};

}  // namespace fastcorot
