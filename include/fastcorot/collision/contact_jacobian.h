// A contact's two sides as the force fields of contacts see them: each side a point y that moves
// with the object as y = y_t + J (x − x_t), J given by its row blocks on the object's blocks (an
// empty J: a still obstacle's point). What PenaltyContactForceField and StickContactForceField
// share: the point at x, J dx, Jᵀ f, and the blocks of s_a s_b J_aᵀ k J_b (s₁ = −1, s₂ = +1) that a
// force depending on y₂ − y₁ through k puts in the system matrix.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/fem/matrix_sink.h"

#include <span>
#include <utility>
#include <vector>

namespace fastcorot {

template <class Real>
using ContactBlocks = std::vector<std::pair<Index, Mat3<Real>>>;

// y_t + J (x − x_t).
template <class Real>
Vec3<Real> contact_point(const ContactBlocks<Real>& side, const Vec3<Real>& y_t, std::span<const Vec3<Real>> x,
                         std::span<const Vec3<Real>> x_t) {
  Vec3<Real> y = y_t;
  for (const auto& [block, j] : side) {
    const auto b = static_cast<std::size_t>(block);
    y += j * (x[b] - x_t[b]);
  }
  return y;
}

// J dx.
template <class Real>
Vec3<Real> contact_apply_j(const ContactBlocks<Real>& side, std::span<const Vec3<Real>> dx) {
  Vec3<Real> out = Vec3<Real>::Zero();
  for (const auto& [block, j] : side) out += j * dx[static_cast<std::size_t>(block)];
  return out;
}

// out += Jᵀ f.
template <class Real>
void contact_add_jt(const ContactBlocks<Real>& side, const Vec3<Real>& f, std::span<Vec3<Real>> out) {
  for (const auto& [block, j] : side) out[static_cast<std::size_t>(block)] += j.transpose() * f;
}

// Blocks (a, b) of s_a s_b J_aᵀ k J_b over both sides into `sink` (3 × block + offset).
template <class Real>
void contact_add_stiffness(MatrixSink<Real>& sink, const ContactBlocks<Real>& side1, const ContactBlocks<Real>& side2, const Mat3<Real>& k,
                           Index offset) {
  const std::pair<const ContactBlocks<Real>*, Real> sides[2] = {{&side1, Real(-1)}, {&side2, Real(1)}};
  for (const auto& [rows, sign_r] : sides) {
    for (const auto& [cols, sign_c] : sides) {
      for (const auto& [br, jr] : *rows) {
        for (const auto& [bc, jc] : *cols) sink.add_block(offset + 3 * br, offset + 3 * bc, (sign_r * sign_c) * (jr.transpose() * k * jc));
      }
    }
  }
}

// The diagonal blocks of what contact_add_stiffness assembles (a block both sides read sums them).
template <class Real>
void contact_add_diagonal(std::span<Mat3<Real>> diagonal, const ContactBlocks<Real>& side1, const ContactBlocks<Real>& side2,
                          const Mat3<Real>& k) {
  for (const auto* rows : {&side1, &side2}) {
    for (const auto* cols : {&side1, &side2}) {
      const Real sign = rows == cols ? Real(1) : Real(-1);
      for (const auto& [br, jr] : *rows) {
        for (const auto& [bc, jc] : *cols) {
          if (br == bc) diagonal[static_cast<std::size_t>(br)] += sign * (jr.transpose() * k * jc);
        }
      }
    }
  }
}

}  // namespace fastcorot
