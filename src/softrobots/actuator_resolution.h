// The two resolutions SoftRobots' actuators share on their one row (internal to src/softrobots): a
// commanded motion (CableConstraint's displacement, SurfacePressureConstraint's volumeGrowth) or a
// commanded impulse (force, pressure), with SoftRobots' bounds.
#pragma once

#include "fastcorot/constraint/constraint_problem.h"

#include <functional>

namespace fastcorot::softrobots_detail {

template <class Real>
class ActuatorResolution final : public ConstraintResolution<Real> {
 public:
  enum class Command {
    motion,   // λ -= (d - c) / W_aa, then clamped to [low, high] (bounds of λ)
    impulse,  // λ = c unless W_aa c + d leaves [low, high] (bounds of the motion): then λ moves to the bound
    // SurfacePressureConstraint's pressure: as impulse but, as SoftRobots writes it, the lower bound's
    // correction is overwritten by λ = c (only the upper bound acts)
    impulse_upper_bound_only,
  };
  // `stored` receives λ after the solve.
  ActuatorResolution(Command command, Real value, Real low, Real high, std::function<void(Real)> stored)
      : ConstraintResolution<Real>(1), command_(command), value_(value), low_(low), high_(high), stored_(std::move(stored)) {}

  void init(int line, const DenseMatrix<Real>& w, Real*) override { w_ = w(line, line); }

  void resolve(int line, const DenseMatrix<Real>&, const Real* d, Real* f, const Real*) override {
    Real& lambda = f[line];
    if (command_ == Command::motion) {
      lambda -= (d[line] - value_) / w_;
      if (lambda < low_) lambda = low_;
      if (lambda > high_) lambda = high_;
      return;
    }
    const Real motion = w_ * value_ + d[line];
    if (command_ == Command::impulse) {
      if (motion < low_) {
        lambda -= (d[line] - low_) / w_;
      } else if (motion > high_) {
        lambda -= (d[line] - high_) / w_;
      } else {
        lambda = value_;
      }
      return;
    }
    Real bounded = motion;  // SoftRobots' order, the bounded motion carried from one test to the next
    if (bounded < low_) {
      bounded = low_;
      lambda -= (d[line] - bounded) / w_;
    }
    if (bounded > high_) {
      bounded = high_;
      lambda -= (d[line] - bounded) / w_;
    } else {
      lambda = value_;
    }
  }

  void store(int line, const Real* f) override { stored_(f[line]); }

 private:
  Command command_;
  Real value_, low_, high_, w_ = 1;
  std::function<void(Real)> stored_;
};

}  // namespace fastcorot::softrobots_detail
