#include "fastcorot/fem/constant_force_field.h"

#include "fastcorot/core/error.h"

#include <utility>

namespace fastcorot {

template <class Real>
ConstantForceField<Real>::ConstantForceField(std::shared_ptr<const TetMesh> mesh, std::vector<Index> points,
                                             std::vector<Vec3<Real>> forces)
    : mesh_(std::move(mesh)), points_(std::move(points)), forces_(std::move(forces)) {
  if (!mesh_) throw make_error("ConstantForceField: no mesh");
  if (forces_.size() != points_.size()) {
    throw make_error("ConstantForceField: ", forces_.size(), " forces for ", points_.size(), " points");
  }
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (points_[i] < 0 || points_[i] >= mesh_->num_points()) {
      throw make_error("ConstantForceField: index ", points_[i], " out of range [0, ", mesh_->num_points(), ")");
    }
    if (!forces_[i].allFinite()) throw make_error("ConstantForceField: force ", i, " is not finite");
  }
}

template <class Real>
void ConstantForceField<Real>::add_force(std::span<const Vec3<Real>>, std::span<Vec3<Real>> f) {
  for (std::size_t i = 0; i < points_.size(); ++i) f[static_cast<std::size_t>(points_[i])] += forces_[i];
}

template <class Real>
Real ConstantForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (std::size_t i = 0; i < points_.size(); ++i) energy -= forces_[i].dot(x[static_cast<std::size_t>(points_[i])]);
  return energy;
}

template <class Real>
std::vector<double> ConstantForceField<Real>::model_values() const {
  std::vector<double> values;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    values.push_back(static_cast<double>(points_[i]));
    for (int c = 0; c < 3; ++c) values.push_back(static_cast<double>(forces_[i][c]));
  }
  return values;
}

template class ConstantForceField<double>;

}  // namespace fastcorot
