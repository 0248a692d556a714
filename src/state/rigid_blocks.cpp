#include "fastcorot/state/rigid_blocks.h"

#include <algorithm>

#include "fastcorot/core/error.h"

namespace fastcorot {

template <class Real>
RigidCoord<Real> RigidBlocks<Real>::coord(std::span<const Vec3<Real>> x, std::size_t k) const {
  const auto b = static_cast<std::size_t>(block[k]);
  RigidCoord<Real> c;
  c.center = x[b];
  c.orientation = orientation[k];
  const Vec3<Real>& theta = x[b + 1];
  if (theta[0] != 0 || theta[1] != 0 || theta[2] != 0) integrate(c, Vec3<Real>::Zero(), theta);
  return c;
}

template <class Real>
std::vector<RigidCoord<Real>> RigidBlocks<Real>::coords(std::span<const Vec3<Real>> x) const {
  std::vector<RigidCoord<Real>> out(size());
  for (std::size_t k = 0; k < size(); ++k) out[k] = coord(x, k);
  return out;
}

template <class Real>
RigidCoord<Real> RigidBlocks<Real>::rest_coord(std::span<const Vec3<Real>> rest, std::size_t k) const {
  RigidCoord<Real> c;
  c.center = rest[static_cast<std::size_t>(block[k])];
  c.orientation = rest_orientation[k];
  return c;
}

template <class Real>
void RigidBlocks<Real>::rebase(std::span<Vec3<Real>> x) {
  for (std::size_t k = 0; k < size(); ++k) {
    Vec3<Real>& theta = x[static_cast<std::size_t>(block[k]) + 1];
    if (theta[0] == 0 && theta[1] == 0 && theta[2] == 0) continue;
    RigidCoord<Real> c;
    c.orientation = orientation[k];
    integrate(c, Vec3<Real>::Zero(), theta);
    orientation[k] = c.orientation;
    theta.setZero();
  }
  for (auto& [follower, first] : followers) {
    std::copy_n(orientation.begin() + static_cast<std::ptrdiff_t>(first), follower->size(), follower->orientation.begin());
  }
}

template <class Real>
void RigidBlocks<Real>::check(Index points) const {
  if (orientation.size() != block.size() || rest_orientation.size() != block.size()) {
    throw make_error("rigid bodies: ", block.size(), " blocks but ", orientation.size(), " orientations and ",
                     rest_orientation.size(), " rest orientations");
  }
  for (std::size_t k = 0; k < block.size(); ++k) {
    if (block[k] < 0 || block[k] + 1 >= points) {
      throw make_error("rigid ", k, ": blocks ", block[k], " and ", block[k] + 1, " outside the state's ", points);
    }
  }
}

template struct RigidBlocks<float>;
template struct RigidBlocks<double>;

}  // namespace fastcorot
