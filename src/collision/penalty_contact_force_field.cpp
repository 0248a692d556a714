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
  normal_begin_.assign(1, 0);
  normal_block_.clear();
  normal_row_.clear();
  for (const auto& contact : contacts_) {
    for (const auto& [block, j] : contact.side1) {
      normal_block_.push_back(block);
      normal_row_.push_back(-(j.transpose() * contact.normal));
    }
    for (const auto& [block, j] : contact.side2) {
      normal_block_.push_back(block);
      normal_row_.push_back(j.transpose() * contact.normal);
    }
    normal_begin_.push_back(static_cast<Index>(normal_block_.size()));
  }
  x_t_.assign(x.begin(), x.end());
  active_.assign(contacts_.size(), 0);
  forces_.assign(contacts_.size(), Vec3<Real>::Zero());
}

template <class Real>
Vec3<Real> PenaltyContactForceField<Real>::point(const ContactBlocks<Real>& side, const Vec3<Real>& y_t, std::span<const Vec3<Real>> x) const {
  return contact_point<Real>(side, y_t, x, x_t_);
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
    contact_add_jt<Real>(contact.side1, -forces_[c], f);
    contact_add_jt<Real>(contact.side2, forces_[c], f);
  }
}

template <class Real>
void PenaltyContactForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real) const {
  // df₂ = −k_factor k n (n · (J₂ dx − J₁ dx)) on side 2 through J₂ᵀ, its opposite on side 1.
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    if (!active_[c]) continue;
    const auto begin = static_cast<std::size_t>(normal_begin_[c]), end = static_cast<std::size_t>(normal_begin_[c + 1]);
    Real along = 0;
    for (std::size_t e = begin; e < end; ++e) along += normal_row_[e].dot(dx[static_cast<std::size_t>(normal_block_[e])]);
    const Real change = -k_factor * contacts_[c].stiffness * along;
    for (std::size_t e = begin; e < end; ++e) df[static_cast<std::size_t>(normal_block_[e])] += normal_row_[e] * change;
  }
}

template <class Real>
void PenaltyContactForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real) const {
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    if (!active_[c]) continue;
    const auto& contact = contacts_[c];
    const Mat3<Real> k = (-k_factor * contact.stiffness) * (contact.normal * contact.normal.transpose());
    // d f₂ / d y₂ = k, d f₂ / d y₁ = −k, and f₁ = −f₂.
    contact_add_stiffness<Real>(sink, contact.side1, contact.side2, k, offset);
  }
}

template <class Real>
void PenaltyContactForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real) const {
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    if (!active_[c]) continue;
    const auto& contact = contacts_[c];
    const Mat3<Real> k = (-k_factor * contact.stiffness) * (contact.normal * contact.normal.transpose());
    contact_add_diagonal<Real>(diagonal, contact.side1, contact.side2, k);
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
  std::size_t bytes = (x_t_.size() + normal_row_.size()) * sizeof(Vec3<Real>) + (normal_begin_.size() + normal_block_.size()) * sizeof(Index);
  for (const auto& c : contacts_) bytes += sizeof(c) + (c.side1.size() + c.side2.size()) * sizeof(std::pair<Index, Mat3<Real>>);
  return bytes;
}

template class PenaltyContactForceField<double>;

}  // namespace fastcorot
