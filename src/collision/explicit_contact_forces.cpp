#include "fastcorot/collision/explicit_contact_forces.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

template <class Real>
void ExplicitContactForces<Real>::clear() {
  forces_.assign(static_cast<std::size_t>(mesh_->num_points()), Vec3<Real>::Zero());
}

template <class Real>
void ExplicitContactForces<Real>::add(Index block, const Vec3<Real>& force) {
  if (block < 0 || static_cast<std::size_t>(block) >= forces_.size()) {
    throw make_error("explicit contact force on block ", block, " of an object of ", forces_.size(), " blocks");
  }
  if (!force.allFinite()) throw make_error("explicit contact force on block ", block, " is not finite");
  forces_[static_cast<std::size_t>(block)] += force;
}

template <class Real>
void ExplicitContactForces<Real>::add_force(std::span<const Vec3<Real>>, std::span<Vec3<Real>> f) {
  for (std::size_t i = 0; i < forces_.size() && i < f.size(); ++i) f[i] += forces_[i];
}

template <class Real>
Real ExplicitContactForces<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (std::size_t i = 0; i < forces_.size() && i < x.size(); ++i) energy -= forces_[i].dot(x[i]);
  return energy;
}

template class ExplicitContactForces<double>;

}  // namespace fastcorot
