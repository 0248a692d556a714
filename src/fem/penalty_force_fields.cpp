#include "fastcorot/fem/penalty_force_fields.h"

#include "fastcorot/core/error.h"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace fastcorot {

template <class Real>
PenaltyForceField<Real>::PenaltyForceField(std::shared_ptr<const TetMesh> mesh, Real stiffness, Real damping,
                                           Real rayleigh_stiffness)
    : stiffness_(stiffness), damping_(damping), mesh_(std::move(mesh)), rayleigh_stiffness_(rayleigh_stiffness) {
  if (!mesh_) throw make_error("penalty force field: no mesh");
  const auto check = [](Real value, const char* name) {
    if (!(value >= 0) || !std::isfinite(value)) throw make_error(name, " = ", value, ": must be finite and >= 0");
  };
  check(stiffness_, "stiffness");
  check(damping_, "damping");
  check(rayleigh_stiffness_, "rayleighStiffness");
}

template <class Real>
void PenaltyForceField<Real>::forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record) {
  PhaseTimer timer(times_ ? &times_->add_force : nullptr);
  if (record) contacts_.clear();
  const bool moving = velocity_.size() == x.size();
  for (std::size_t i = 0; i < x.size(); ++i) {
    Vec3<Real> force, normal;
    Real depth = 0;
    if (!contact(x[i], moving ? velocity_[i] : Vec3<Real>::Zero(), force, normal, depth)) continue;
    f[i] += force;
    if (record) contacts_.push_back({static_cast<Index>(i), normal});
  }
}

template <class Real>
void PenaltyForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                                         Real b_factor) const {
  const Real factor = -stiffness_ * (k_factor + b_factor * rayleigh_stiffness_);
  for (const Contact& c : contacts_) {
    const auto i = static_cast<std::size_t>(c.point);
    df[i] += c.normal * (factor * dx[i].dot(c.normal));
  }
}

template <class Real>
void PenaltyForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real b_factor) const {
  const Real factor = -stiffness_ * (k_factor + b_factor * rayleigh_stiffness_);
  for (const Contact& c : contacts_) sink.add_block(offset + 3 * c.point, offset + 3 * c.point, factor * c.normal * c.normal.transpose());
}

template <class Real>
void PenaltyForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor) const {
  const Real factor = -stiffness_ * (k_factor + b_factor * rayleigh_stiffness_);
  for (const Contact& c : contacts_) diagonal[static_cast<std::size_t>(c.point)] += factor * c.normal * c.normal.transpose();
}

template <class Real>
Real PenaltyForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (const auto& p : x) {
    Vec3<Real> force, normal;
    Real depth = 0;
    if (contact(p, Vec3<Real>::Zero(), force, normal, depth)) energy += stiffness_ * depth * depth / 2;
  }
  return energy;
}

template <class Real>
std::vector<Mat3<Real>> PenaltyForceField<Real>::rotations() const {
  return std::vector<Mat3<Real>>(static_cast<std::size_t>(mesh_->num_tetrahedra()), Mat3<Real>::Identity());
}

template <class Real>
PlaneForceField<Real>::PlaneForceField(std::shared_ptr<const TetMesh> mesh, const Parameters& parameters)
    : PenaltyForceField<Real>(std::move(mesh), parameters.stiffness, parameters.damping, parameters.rayleigh_stiffness),
      p_(parameters) {
  if (!p_.normal.allFinite() || !std::isfinite(p_.d)) throw make_error("PlaneForceField: normal and d must be finite");
  if (!(p_.max_force >= 0) || !std::isfinite(p_.max_force)) throw make_error("PlaneForceField: maxForce = ", p_.max_force, ": must be finite and >= 0");
}

template <class Real>
bool PlaneForceField<Real>::contact(const Vec3<Real>& x, const Vec3<Real>& v, Vec3<Real>& force, Vec3<Real>& normal,
                                    Real& depth) const {
  const Real d = x.dot(p_.normal) - p_.d;
  if (!(p_.bilateral || d < 0)) return false;
  force = p_.normal * (-this->stiffness_ * d) - v * (-this->damping_ * d);
  const Real limit = p_.max_force * p_.max_force, amplitude = force.squaredNorm();
  if (limit > 0 && amplitude > limit) force *= std::sqrt(limit / amplitude);
  normal = p_.normal;
  depth = d;
  return true;
}

template <class Real>
std::vector<double> PlaneForceField<Real>::model_values() const {
  return {static_cast<double>(p_.normal.x()), static_cast<double>(p_.normal.y()), static_cast<double>(p_.normal.z()),
          static_cast<double>(p_.d), static_cast<double>(p_.stiffness), static_cast<double>(p_.damping),
          static_cast<double>(p_.max_force), p_.bilateral ? 1.0 : 0.0, static_cast<double>(p_.rayleigh_stiffness)};
}

template <class Real>
ConicalForceField<Real>::ConicalForceField(std::shared_ptr<const TetMesh> mesh, const Parameters& parameters)
    : PenaltyForceField<Real>(std::move(mesh), parameters.stiffness, parameters.damping, parameters.rayleigh_stiffness),
      p_(parameters) {
  if (!p_.center.allFinite() || !p_.height.allFinite() || !std::isfinite(p_.angle)) {
    throw make_error("ConicalForceField: coneCenter, coneHeight and coneAngle must be finite");
  }
  if (p_.height.norm() == 0) throw make_error("ConicalForceField: coneHeight is zero: the cone has no axis");
}

template <class Real>
bool ConicalForceField<Real>::inside(const Vec3<Real>& x) const {
  const Vec3<Real> cp = x - p_.center;
  const Real h = p_.height.norm(), distance = cp.norm();
  if (distance > h) return false;
  return !(std::acos(cp.dot(p_.height) / (h * distance)) * 180 / std::numbers::pi_v<Real> > p_.angle);
}

template <class Real>
bool ConicalForceField<Real>::contact(const Vec3<Real>& x, const Vec3<Real>& v, Vec3<Real>& force, Vec3<Real>& normal,
                                      Real& depth) const {
  if (inside(x)) return false;
  const Vec3<Real> cp = x - p_.center;
  const Vec3<Real> axis = p_.height.normalized();
  const Real length = cp.norm();
  if (length > p_.height.norm()) {
    // Beyond the sphere through the base: pulled back towards the apex.
    const Real d = length - p_.height.norm();
    force = cp * (-this->stiffness_ * d / length) - v * (-this->damping_ * d);
    normal = cp / length;
    depth = d;
    return true;
  }
  Vec3<Real> direction;
  Real d = 0;
  if (cp.dot(axis) > 0) {
    // Beside the cone: to the nearest point of its surface in the plane of the axis and the point.
    const Real alpha = std::acos(cp.dot(axis) / length) - p_.angle * std::numbers::pi_v<Real> / 180;
    const Vec3<Real> t = axis.cross(cp).normalized();
    const Vec3<Real> surface = (Eigen::AngleAxis<Real>(-alpha, t) * cp).normalized();
    const Vec3<Real> to_surface = surface * surface.dot(cp) - cp;
    d = to_surface.norm();
    direction = to_surface / d;
  } else {
    // Above the apex: back to it.
    d = length;
    direction = -cp / length;
  }
  force = direction * (this->stiffness_ * d) + direction * (this->damping_ * -direction.dot(v));
  normal = direction;
  depth = d;
  return true;
}

template <class Real>
std::vector<double> ConicalForceField<Real>::model_values() const {
  return {static_cast<double>(p_.center.x()), static_cast<double>(p_.center.y()), static_cast<double>(p_.center.z()),
          static_cast<double>(p_.height.x()), static_cast<double>(p_.height.y()), static_cast<double>(p_.height.z()),
          static_cast<double>(p_.angle),      static_cast<double>(p_.stiffness),  static_cast<double>(p_.damping),
          static_cast<double>(p_.rayleigh_stiffness)};
}

template class PenaltyForceField<double>;
template class PenaltyForceField<float>;
template class PlaneForceField<double>;
template class PlaneForceField<float>;
template class ConicalForceField<double>;
template class ConicalForceField<float>;

}  // namespace fastcorot
