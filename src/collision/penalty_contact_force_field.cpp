#include "fastcorot/collision/penalty_contact_force_field.h"

#include "fastcorot/core/error.h"

#include <cmath>

namespace fastcorot {

template <class Real>
void PenaltyContactForceField<Real>::set_contacts(std::vector<PenaltyContact<Real>> contacts, std::span<const Vec3<Real>> x) {
  const Index n = mesh_->num_points();
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const auto& contact = contacts[c];
    for (const auto* side : {&contact.side1, &contact.side2}) {
      for (const auto& [block, j] : *side) {
        if (block < 0 || block >= n) throw make_error("PenalityContactForceField: contact ", c, " reads block ", block, " of ", n);
        if (!j.allFinite()) throw make_error("PenalityContactForceField: contact ", c, " has a non-finite Jacobian");
      }
    }
    if (!contact.y1.allFinite() || !contact.y2.allFinite() || !contact.normal.allFinite() || !std::isfinite(contact.distance) ||
        !(contact.stiffness >= 0) || !std::isfinite(contact.stiffness)) {
      throw make_error("PenalityContactForceField: contact ", c, " has a non-finite point, normal or distance, or a negative stiffness");
    }
  }
  contacts_ = std::move(contacts);
  x_t_.assign(x.begin(), x.end());
  active_.assign(contacts_.size(), 0);
  forces_.assign(contacts_.size(), Vec3<Real>::Zero());
}

template <class Real>
Vec3<Real> PenaltyContactForceField<Real>::apply_j(const std::vector<std::pair<Index, Mat3<Real>>>& side, std::span<const Vec3<Real>> dx) const {
  Vec3<Real> out = Vec3<Real>::Zero();
  for (const auto& [block, j] : side) out += j * dx[static_cast<std::size_t>(block)];
  return out;
}

template <class Real>
Vec3<Real> PenaltyContactForceField<Real>::point(const std::vector<std::pair<Index, Mat3<Real>>>& side, const Vec3<Real>& y_t,
                                                 std::span<const Vec3<Real>> x) const {
  Vec3<Real> y = y_t;
  for (const auto& [block, j] : side) {
    const auto b = static_cast<std::size_t>(block);
    y += j * (x[b] - x_t_[b]);
  }
  return y;
}

template <class Real>
void PenaltyContactForceField<Real>::add_jt(const std::vector<std::pair<Index, Mat3<Real>>>& side, const Vec3<Real>& f, std::span<Vec3<Real>> out) {
  for (const auto& [block, j] : side) out[static_cast<std::size_t>(block)] += j.transpose() * f;
}

template <class Real>
void PenaltyContactForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const auto& contact = contacts_[c];
    const Vec3<Real> y1 = point(contact.side1, contact.y1, x), y2 = point(contact.side2, contact.y2, x);
    const Real pen = contact.distance - (y2 - y1).dot(contact.normal);
    active_[c] = pen > 0;
    forces_[c] = active_[c] ? Vec3<Real>(contact.normal * (contact.stiffness * pen)) : Vec3<Real>::Zero();
    if (!active_[c]) continue;
    add_jt(contact.side1, -forces_[c], f);
    add_jt(contact.side2, forces_[c], f);
  }
}

template <class Real>
void PenaltyContactForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real) const {
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    if (!active_[c]) continue;
    const auto& contact = contacts_[c];
    const Vec3<Real> gap = apply_j(contact.side2, dx) - apply_j(contact.side1, dx);
    const Vec3<Real> change = contact.normal * (-k_factor * contact.stiffness * contact.normal.dot(gap));
    add_jt(contact.side1, -change, df);
    add_jt(contact.side2, change, df);
  }
}

template <class Real>
void PenaltyContactForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real) const {
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    if (!active_[c]) continue;
    const auto& contact = contacts_[c];
    const Mat3<Real> k = (-k_factor * contact.stiffness) * (contact.normal * contact.normal.transpose());
    // d f₂ / d y₂ = k, d f₂ / d y₁ = −k, and f₁ = −f₂: block (a, b) = s_a s_b J_aᵀ k J_b, s₁ = −1, s₂ = +1.
    const std::pair<const std::vector<std::pair<Index, Mat3<Real>>>*, Real> sides[2] = {{&contact.side1, Real(-1)},
                                                                                          {&contact.side2, Real(1)}};
    for (const auto& [rows, sign_r] : sides) {
      for (const auto& [cols, sign_c] : sides) {
        for (const auto& [br, jr] : *rows) {
          for (const auto& [bc, jc] : *cols) {
            sink.add_block(offset + 3 * br, offset + 3 * bc, (sign_r * sign_c) * (jr.transpose() * k * jc));
          }
        }
      }
    }
  }
}

template <class Real>
void PenaltyContactForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real) const {
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    if (!active_[c]) continue;
    const auto& contact = contacts_[c];
    const Mat3<Real> k = (-k_factor * contact.stiffness) * (contact.normal * contact.normal.transpose());
    // The diagonal blocks of the matrix add_stiffness assembles (a block both sides read sums them).
    for (const auto* rows : {&contact.side1, &contact.side2}) {
      for (const auto* cols : {&contact.side1, &contact.side2}) {
        const Real sign = rows == cols ? Real(1) : Real(-1);
        for (const auto& [br, jr] : *rows) {
          for (const auto& [bc, jc] : *cols) {
            if (br == bc) diagonal[static_cast<std::size_t>(br)] += sign * (jr.transpose() * k * jc);
          }
        }
      }
    }
  }
}

template <class Real>
Real PenaltyContactForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (const auto& contact : contacts_) {
    const Real pen = contact.distance - (point(contact.side2, contact.y2, x) - point(contact.side1, contact.y1, x)).dot(contact.normal);
    if (pen > 0) energy += Real(0.5) * contact.stiffness * pen * pen;
  }
  return energy;
}

template <class Real>
std::size_t PenaltyContactForceField<Real>::memory_bytes() const {
  std::size_t bytes = x_t_.size() * sizeof(Vec3<Real>);
  for (const auto& c : contacts_) bytes += sizeof(c) + (c.side1.size() + c.side2.size()) * sizeof(std::pair<Index, Mat3<Real>>);
  return bytes;
}

template class PenaltyContactForceField<double>;

}  // namespace fastcorot
