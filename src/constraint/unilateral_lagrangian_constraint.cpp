#include "fastcorot/constraint/unilateral_lagrangian_constraint.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/simulation.h"

#include <cmath>

namespace fastcorot {

template <class Real>
void UnilateralFrictionResolution<Real>::init(int line, const DenseMatrix<Real>& w, Real*) {
  w_nn_ = w(line, line);
  w_nt_ = w(line, line + 1);
  w_ns_ = w(line, line + 2);
  w_tt_ = w(line + 1, line + 1);
  w_ss_ = w(line + 2, line + 2);
}

template <class Real>
void UnilateralFrictionResolution<Real>::resolve(int line, const DenseMatrix<Real>&, const Real* d, Real* f, const Real*) {
  const Real normal_before = f[line];
  f[line] -= d[line] / w_nn_;
  if (f[line] < 0) {
    f[line] = f[line + 1] = f[line + 2] = 0;
    return;
  }
  // The tangent violations see the normal impulse's change through W's coupling terms.
  const Real change = f[line] - normal_before;
  const Real d_t = d[line + 1] + w_nt_ * change;
  const Real d_s = d[line + 2] + w_ns_ * change;
  f[line + 1] -= 2 * d_t / (w_tt_ + w_ss_);
  f[line + 2] -= 2 * d_s / (w_tt_ + w_ss_);
  const Real tangent = std::sqrt(f[line + 1] * f[line + 1] + f[line + 2] * f[line + 2]);
  const Real bound = mu_ * f[line];
  if (tangent > bound) {
    const Real factor = bound / tangent;
    f[line + 1] *= factor;
    f[line + 2] *= factor;
  }
}

template <class Real>
void AugmentedLagrangianFrictionResolution<Real>::resolve(int line, const DenseMatrix<Real>&, const Real* d, Real* f, const Real*) {
  f[line] -= d[line] * epsilon_;
  if (f[line] < 0) {
    f[line] = f[line + 1] = f[line + 2] = 0;
    return;
  }
  const Real t0 = f[line + 1] - d[line + 1] * epsilon_;
  const Real t1 = f[line + 2] - d[line + 2] * epsilon_;
  if (std::sqrt(t0 * t0 + t1 * t1) - mu_ * std::abs(f[line]) < 0) {
    f[line + 1] = t0;
    f[line + 2] = t1;
    return;
  }
  const Real slide = std::sqrt(d[line + 1] * d[line + 1] + d[line + 2] * d[line + 2]);
  f[line + 1] -= mu_ * d[line] * epsilon_ * d[line + 1] / slide;
  f[line + 2] -= mu_ * d[line] * epsilon_ * d[line + 2] / slide;
}

template <class Real>
UnilateralLagrangianConstraint<Real>::UnilateralLagrangianConstraint(std::string where, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)), parameters_(parameters) {
  if (!(parameters_.mu >= 0) || !std::isfinite(parameters_.mu)) throw make_error("mu = ", parameters_.mu, " must be finite and ≥ 0");
  if (!(parameters_.tolerance >= 0) || !std::isfinite(parameters_.tolerance)) {
    throw make_error("tol = ", parameters_.tolerance, " must be finite and ≥ 0");
  }
  if (!(parameters_.epsilon >= 0) || !std::isfinite(parameters_.epsilon)) {
    throw make_error("epsilon = ", parameters_.epsilon, " must be finite and ≥ 0");
  }
}

template <class Real>
void UnilateralLagrangianConstraint<Real>::tangents(const Vec3<Real>& n, Vec3<Real>& t, Vec3<Real>& s) {
  t = Vec3<Real>(n.z(), n.x(), n.y());
  s = n.cross(t);
  s = s / s.norm();
  t = (-n).cross(s);
}

template <class Real>
ContactSideMotion<Real> free_motion(const ContactSide<Real>& side, std::span<const SimulatedObject<Real>> objects, Real dt) {
  ContactSideMotion<Real> motion;
  if (!side.still) {
    const auto& velocity = objects[side.object].system.state.velocity;
    for (const auto& [block, m] : side.blocks) motion.free_velocity += m * velocity[static_cast<std::size_t>(block)];
  }
  motion.free_position = side.position + dt * motion.free_velocity;
  return motion;
}

template <class Real>
void UnilateralLagrangianConstraint<Real>::prepare(std::span<const SimulatedObject<Real>> objects, Real dt) {
  motion_.resize(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    motion_[k] = {free_motion(contacts_[k].first, objects, dt), free_motion(contacts_[k].second, objects, dt)};
  }
}

template <class Real>
void UnilateralLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  const int per_contact = rows_per_contact();
  this->rows_ = per_contact * static_cast<int>(contacts_.size());
  this->first_row_ = rows.add_rows(this->rows_);
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const auto& c = contacts_[k];
    Vec3<Real> axes[3] = {c.normal, Vec3<Real>::Zero(), Vec3<Real>::Zero()};
    if (per_contact == 3) tangents(c.normal, axes[1], axes[2]);
    for (int a = 0; a < per_contact; ++a) {
      const int row = this->first_row_ + per_contact * static_cast<int>(k) + a;
      if (!c.first.still) rows.add_blocks(row, c.first.object, c.first.blocks, -axes[a]);
      if (!c.second.still) rows.add_blocks(row, c.second.object, c.second.blocks, axes[a]);
    }
  }
}

template <class Real>
void UnilateralLagrangianConstraint<Real>::violation(ConstraintOrder order, Real dt, Real* dfree) const {
  const int per_contact = rows_per_contact();
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const auto& c = contacts_[k];
    const Vec3<Real>& q = c.first.position;
    const Vec3<Real>& p = c.second.position;
    Vec3<Real> t = Vec3<Real>::Zero(), s = Vec3<Real>::Zero();
    if (per_contact == 3) tangents(c.normal, t, s);
    Real* out = dfree + this->first_row_ + per_contact * static_cast<int>(k);
    if (order == ConstraintOrder::velocity) {
      const Vec3<Real> relative = motion_[k][1].free_velocity - motion_[k][0].free_velocity;
      const Real inverse_dt = Real(1) / dt;
      out[0] = (relative + (p - q) * inverse_dt).dot(c.normal) - c.distance * inverse_dt;
      if (per_contact == 3) {
        out[1] = relative.dot(t);
        out[2] = relative.dot(s);
      }
      continue;
    }
    const Vec3<Real>& q_free = motion_[k][0].free_position;
    const Vec3<Real>& p_free = motion_[k][1].free_position;
    const Vec3<Real> p_move = p_free - p, q_move = q_free - q;
    const Real scale = p_move.norm() + q_move.norm();
    const Real gap_free = (p_free - q_free).dot(c.normal) - c.distance;
    const Real gap = (p - q).dot(c.normal) - c.distance;
    out[0] = gap_free;
    if (per_contact != 3) continue;
    // The tangential motion, counted from where the gap closes during the step when it does.
    Vec3<Real> p_slide = p_move, q_slide = q_move;
    if (std::abs(gap) < Real(1e-5) * scale && std::abs(gap_free) < Real(1e-5) * scale) {
      // both gaps about zero: the whole motion
    } else if (std::abs(gap - gap_free) > Real(0.001) * gap) {
      const Real crossing = gap / (gap - gap_free);
      if (crossing > 0 && crossing < 1) {
        p_slide = p_free - (p * (1 - crossing) + p_free * crossing);
        q_slide = q_free - (q * (1 - crossing) + q_free * crossing);
      } else if (!(gap_free < 0)) {
        p_slide = q_slide = Vec3<Real>::Zero();
      }
    }
    out[1] = p_slide.dot(t) - q_slide.dot(t);
    out[2] = p_slide.dot(s) - q_slide.dot(s);
  }
}

template <class Real>
void UnilateralLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    if (rows_per_contact() == 3 && parameters_.augmented) {
      problem.add_block(
          std::make_unique<AugmentedLagrangianFrictionResolution<Real>>(parameters_.mu, parameters_.epsilon, parameters_.tolerance));
    } else if (rows_per_contact() == 3) {
      problem.add_block(std::make_unique<UnilateralFrictionResolution<Real>>(parameters_.mu, parameters_.tolerance));
    } else {
      problem.add_block(std::make_unique<UnilateralResolution<Real>>());
    }
  }
}

template class UnilateralFrictionResolution<double>;
template class AugmentedLagrangianFrictionResolution<double>;
template class UnilateralLagrangianConstraint<double>;
template ContactSideMotion<double> free_motion(const ContactSide<double>&, std::span<const SimulatedObject<double>>, double);

}  // namespace fastcorot
