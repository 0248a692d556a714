#include "fastcorot/collision/stick_contact_force_field.h"

#include "fastcorot/core/error.h"

#include <cmath>

namespace fastcorot {

template <class Real>
void StickContactForceField<Real>::set_springs(std::vector<StickSpring<Real>> springs, std::span<const Vec3<Real>> x) {
  const Index n = mesh_->num_points();
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const auto& spring = springs[s];
    for (const auto* side : {&spring.side1, &spring.side2}) {
      for (const auto& [block, j] : *side) {
        if (block < 0 || block >= n) throw make_error("StickContactForceField: spring ", s, " reads block ", block, " of ", n);
        if (!j.allFinite()) throw make_error("StickContactForceField: spring ", s, " has a non-finite Jacobian");
      }
    }
    if (!spring.y1.allFinite() || !spring.y2.allFinite() || !spring.rest.allFinite() || !spring.relative_velocity.allFinite() ||
        !(spring.stiffness >= 0) || !std::isfinite(spring.stiffness) || !(spring.damping >= 0) || !std::isfinite(spring.damping)) {
      throw make_error("StickContactForceField: spring ", s, " has a non-finite point, rest vector or velocity, or a negative stiffness or damping");
    }
  }
  springs_ = std::move(springs);
  x_t_.assign(x.begin(), x.end());
}

template <class Real>
void StickContactForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  for (const auto& s : springs_) {
    const Vec3<Real> y1 = contact_point<Real>(s.side1, s.y1, x, x_t_), y2 = contact_point<Real>(s.side2, s.y2, x, x_t_);
    const Vec3<Real> force = (y2 - y1 - s.rest) * s.stiffness + s.relative_velocity * s.damping;
    contact_add_jt<Real>(s.side1, force, f);
    contact_add_jt<Real>(s.side2, -force, f);
  }
}

template <class Real>
void StickContactForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real) const {
  for (const auto& s : springs_) {
    const Vec3<Real> change = (contact_apply_j<Real>(s.side2, dx) - contact_apply_j<Real>(s.side1, dx)) * (k_factor * s.stiffness);
    contact_add_jt<Real>(s.side1, change, df);
    contact_add_jt<Real>(s.side2, -change, df);
  }
}

template <class Real>
void StickContactForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real) const {
  // d f₁ / d y₂ = ks I, d f₁ / d y₁ = −ks I, and f₂ = −f₁.
  for (const auto& s : springs_) {
    contact_add_stiffness<Real>(sink, s.side1, s.side2, Mat3<Real>::Identity() * (-k_factor * s.stiffness), offset);
  }
}

template <class Real>
void StickContactForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real) const {
  for (const auto& s : springs_) contact_add_diagonal<Real>(diagonal, s.side1, s.side2, Mat3<Real>::Identity() * (-k_factor * s.stiffness));
}

template <class Real>
Real StickContactForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (const auto& s : springs_) {
    const Vec3<Real> stretch = contact_point<Real>(s.side2, s.y2, x, x_t_) - contact_point<Real>(s.side1, s.y1, x, x_t_) - s.rest;
    energy += Real(0.5) * s.stiffness * stretch.squaredNorm();
  }
  return energy;
}

template <class Real>
std::size_t StickContactForceField<Real>::memory_bytes() const {
  std::size_t bytes = x_t_.size() * sizeof(Vec3<Real>);
  for (const auto& s : springs_) bytes += sizeof(s) + (s.side1.size() + s.side2.size()) * sizeof(std::pair<Index, Mat3<Real>>);
  return bytes;
}

template class StickContactForceField<double>;

}  // namespace fastcorot
