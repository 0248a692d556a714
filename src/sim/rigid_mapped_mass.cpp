#include "fastcorot/sim/rigid_mapped_mass.h"

#include "fastcorot/core/error.h"
#include "fastcorot/state/rigid3.h"

namespace fastcorot {

template <class Real>
Mass<Real> RigidMappedMass<Real>::at(std::span<const Vec3<Real>> x, Index points) const {
  const auto n = static_cast<std::size_t>(points);
  std::vector<Mat3<Real>> blocks(n, Mat3<Real>::Zero());
  std::vector<Mat3<Real>> gravity(n, Mat3<Real>::Zero());
  if (own.size() != 0) {
    if (own.size() != points) throw make_error("rigid mass: ", own.size(), " blocks for ", points, " points");
    const auto own_blocks = own.blocks();
    const auto own_weights = own.gravity_masses();
    for (std::size_t i = 0; i < n; ++i) {
      blocks[i] = own_blocks[i];
      gravity[i] = own_weights[i] * Mat3<Real>::Identity();
    }
  }
  std::vector<Mat3<Real>> coupling(n, Mat3<Real>::Zero());  // at each rigid's linear block
  for (const Carried& part : carried) {
    const std::vector<RigidCoord<Real>> coords = part.points.frames->coords(x);
    for (std::size_t i = 0; i < part.points.size(); ++i) {
      const auto k = static_cast<std::size_t>(part.points.rigid[i]);
      const auto b = static_cast<std::size_t>(part.points.frames->block[k]);
      const Vec3<Real> r = coords[k].rotate(part.points.local[i]);
      const Mat3<Real> s = cross_matrix(r);
      const Real m = part.masses[i];
      blocks[b].diagonal().array() += m;
      blocks[b + 1] += m * (r.squaredNorm() * Mat3<Real>::Identity() - r * r.transpose());
      coupling[b] -= m * s;
      gravity[b].diagonal().array() += part.weights[i];
      gravity[b + 1] += part.weights[i] * s;
    }
  }
  Mass<Real> mass = Mass<Real>::block_diagonal(std::move(blocks));
  std::vector<typename Mass<Real>::Coupling> couplings;
  for (std::size_t b = 0; b < n; ++b) {
    if (!coupling[b].isZero(Real(0))) couplings.push_back({static_cast<Index>(b), static_cast<Index>(b + 1), coupling[b]});
  }
  mass.set_couplings(std::move(couplings));
  mass.set_gravity_blocks(std::move(gravity));
  return mass;
}

template struct RigidMappedMass<float>;
template struct RigidMappedMass<double>;

}  // namespace fastcorot
