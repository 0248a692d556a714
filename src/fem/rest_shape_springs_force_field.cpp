#include "fastcorot/fem/rest_shape_springs_force_field.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <utility>

namespace fastcorot {

template <class Real>
RestShapeSpringsForceField<Real>::RestShapeSpringsForceField(std::shared_ptr<const TetMesh> mesh, Parameters parameters)
    : mesh_(std::move(mesh)), p_(std::move(parameters)) {
  const std::string name = "RestShapeSpringsForceField";
  if (!mesh_) throw make_error(name, ": no mesh");
  const Index n = mesh_->num_points();
  for (Index i : p_.points) {
    if (i < 0 || i >= n) throw make_error(name, ": points: index ", i, " out of range [0, ", n, ")");
  }
  if (p_.anchors.size() != p_.points.size()) {
    throw make_error(name, ": ", p_.anchors.size(), " rest positions for ", p_.points.size(), " points");
  }
  for (std::size_t i = 0; i < p_.anchors.size(); ++i) {
    if (!p_.anchors[i].allFinite()) throw make_error(name, ": rest position ", i, " is not finite");
  }
  if (p_.stiffness.empty()) throw make_error(name, ": stiffness is empty");
  for (Real k : p_.stiffness) {
    if (!(k >= 0) || !std::isfinite(k)) throw make_error(name, ": stiffness = ", k, ": must be finite and >= 0");
  }
  if (!(p_.rayleigh_stiffness >= 0) || !std::isfinite(p_.rayleigh_stiffness)) {
    throw make_error(name, ": rayleighStiffness = ", p_.rayleigh_stiffness, ": must be finite and >= 0");
  }
  if (!p_.rigids) return;
  if (p_.rigid_of_point.size() != p_.points.size() || p_.rest_orientations.size() != p_.points.size()) {
    throw make_error(name, ": one rigid and one rest orientation per point are needed");
  }
  if (p_.angular_stiffness.empty()) throw make_error(name, ": angularStiffness is empty");
  for (Real k : p_.angular_stiffness) {
    if (!(k >= 0) || !std::isfinite(k)) throw make_error(name, ": angularStiffness = ", k, ": must be finite and >= 0");
  }
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    const Index k = p_.rigid_of_point[i];
    if (k < 0 || k >= static_cast<Index>(p_.rigids->size()) || p_.rigids->block[static_cast<std::size_t>(k)] != p_.points[i]) {
      throw make_error(name, ": point ", p_.points[i], " is not the linear block of rigid ", k);
    }
  }
}

template <class Real>
Vec3<Real> RestShapeSpringsForceField<Real>::rotation_offset(std::span<const Vec3<Real>> x, std::size_t i) const {
  const Eigen::Quaternion<Real> q = p_.rigids->coord(x, static_cast<std::size_t>(p_.rigid_of_point[i])).orientation;
  Eigen::Quaternion<Real> dq = quaternion_product(q, quaternion_inverse(p_.rest_orientations[i]));
  normalize_as_sofa(dq);
  if (dq.w() < 0) dq.coeffs() *= Real(-1);
  Vec3<Real> axis = Vec3<Real>::Zero();
  Real angle = 0;
  if (dq.w() < 1) quaternion_to_axis(dq, axis, angle);
  for (int a = 0; a < 3; ++a) {
    if (!p_.active_rotations[static_cast<std::size_t>(a)]) axis[a] = 0;
  }
  return axis * angle;
}

template <class Real>
Mat3<Real> RestShapeSpringsForceField<Real>::angular_block(std::size_t i) const {
  Mat3<Real> m = Mat3<Real>::Zero();
  for (int a = 0; a < 3; ++a) {
    if (p_.active_rotations[static_cast<std::size_t>(a)]) m(a, a) = angular_stiffness(i);
  }
  return m;
}

template <class Real>
Mat3<Real> RestShapeSpringsForceField<Real>::block(std::size_t i) const {
  Mat3<Real> m = Mat3<Real>::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    if (p_.active_directions[static_cast<std::size_t>(axis)]) m(axis, axis) = stiffness(i);
  }
  return m;
}

template <class Real>
void RestShapeSpringsForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  PhaseTimer timer(times_ ? &times_->add_force : nullptr);
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    const auto point = static_cast<std::size_t>(p_.points[i]);
    Vec3<Real> d = x[point] - p_.anchors[i];
    for (int axis = 0; axis < 3; ++axis) {
      if (!p_.active_directions[static_cast<std::size_t>(axis)]) d[axis] = 0;
    }
    f[point] -= d * stiffness(i);
    if (p_.rigids) f[point + 1] -= rotation_offset(x, i) * angular_stiffness(i);
  }
}

template <class Real>
void RestShapeSpringsForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                                                  Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    const auto point = static_cast<std::size_t>(p_.points[i]);
    Vec3<Real> d = dx[point];
    for (int axis = 0; axis < 3; ++axis) {
      if (!p_.active_directions[static_cast<std::size_t>(axis)]) d[axis] = 0;
    }
    df[point] -= d * stiffness(i) * k;
    if (p_.rigids) df[point + 1] -= angular_block(i) * dx[point + 1] * k;
  }
}

template <class Real>
void RestShapeSpringsForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    const Index at = offset + 3 * p_.points[i];
    sink.add_block(at, at, -(block(i) * k));
    if (p_.rigids) sink.add_block(at + 3, at + 3, -(angular_block(i) * k));
  }
}

template <class Real>
void RestShapeSpringsForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    const auto point = static_cast<std::size_t>(p_.points[i]);
    diagonal[point] -= block(i) * k;
    if (p_.rigids) diagonal[point + 1] -= angular_block(i) * k;
  }
}

template <class Real>
Real RestShapeSpringsForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    Vec3<Real> d = x[static_cast<std::size_t>(p_.points[i])] - p_.anchors[i];
    for (int axis = 0; axis < 3; ++axis) {
      if (!p_.active_directions[static_cast<std::size_t>(axis)]) d[axis] = 0;
    }
    energy += stiffness(i) * d.squaredNorm() / 2;
    if (p_.rigids) energy += angular_stiffness(i) * rotation_offset(x, i).squaredNorm() / 2;
  }
  return energy;
}

template <class Real>
std::vector<Mat3<Real>> RestShapeSpringsForceField<Real>::rotations() const {
  return std::vector<Mat3<Real>>(static_cast<std::size_t>(mesh_->num_tetrahedra()), Mat3<Real>::Identity());
}

template <class Real>
void RestShapeSpringsForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron>) const {
  throw make_error("RestShapeSpringsForceField: its points are chosen at init: topological changes are not supported");
}

template <class Real>
void RestShapeSpringsForceField<Real>::apply(const TopologyChange&) {
  throw make_error("RestShapeSpringsForceField: its points are chosen at init: topological changes are not supported");
}

template <class Real>
std::vector<double> RestShapeSpringsForceField<Real>::model_values() const {
  std::vector<double> values{static_cast<double>(p_.rayleigh_stiffness)};
  for (bool active : p_.active_directions) values.push_back(active ? 1.0 : 0.0);
  for (Real k : p_.stiffness) values.push_back(static_cast<double>(k));
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    values.push_back(static_cast<double>(p_.points[i]));
    for (int axis = 0; axis < 3; ++axis) values.push_back(static_cast<double>(p_.anchors[i][axis]));
  }
  for (Real k : p_.angular_stiffness) values.push_back(static_cast<double>(k));
  for (const auto& q : p_.rest_orientations) {
    for (int c = 0; c < 4; ++c) values.push_back(static_cast<double>(q.coeffs()[c]));
  }
  return values;
}

template <class Real>
std::size_t RestShapeSpringsForceField<Real>::memory_bytes() const {
  return p_.points.size() * (sizeof(Index) + sizeof(Vec3<Real>)) + p_.stiffness.size() * sizeof(Real);
}

template <class Real>
bool RestShapeSpringsForceField<Real>::follow_rest(std::span<const Vec3<Real>> rest_position) {
  if (!p_.anchors_follow_rest) return false;
  for (std::size_t i = 0; i < p_.points.size(); ++i) {
    if (p_.rigids) {
      const RigidCoord<Real> rest = p_.rigids->rest_coord(rest_position, static_cast<std::size_t>(p_.rigid_of_point[i]));
      p_.anchors[i] = rest.center;
      p_.rest_orientations[i] = rest.orientation;
    } else {
      p_.anchors[i] = rest_position[static_cast<std::size_t>(p_.points[i])];
    }
  }
  return true;
}

template class RestShapeSpringsForceField<double>;
template class RestShapeSpringsForceField<float>;

}  // namespace fastcorot
