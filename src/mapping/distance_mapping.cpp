#include "fastcorot/mapping/distance_mapping.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fastcorot {

template <class Real>
typename DistanceMapping<Real>::Direction DistanceMapping<Real>::direction(const Vec3<Real>& a, const Vec3<Real>& b) {
  Direction d{b - a, Real(0)};
  const Real length = d.u.norm();
  // SOFA compares with the machine epsilon of its scalar type (double).
  if (static_cast<double>(length) > std::numeric_limits<double>::epsilon()) {
    d.inverse_length = Real(1) / length;
    d.u *= d.inverse_length;
  } else {
    d.u.setConstant(Real(1) / std::sqrt(Real(3)));
  }
  return d;
}

template <class Real>
DistanceMapping<Real>::DistanceMapping(std::vector<Edge> edges, std::span<const Vec3<Real>> rest, std::vector<Real> rest_lengths)
    : edges_(std::move(edges)), rest_lengths_(std::move(rest_lengths)), directions_(edges_.size(), Vec3<Real>::Zero()) {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    for (Index p : edges_[i]) {
      if (p < 0 || static_cast<std::size_t>(p) >= rest.size()) {
        throw make_error("DistanceMapping: edge ", i, " joins point ", p, ", outside the ", rest.size(), " points of its input");
      }
    }
  }
  if (rest_lengths_.empty()) {
    rest_lengths_.reserve(edges_.size());
    for (const Edge& e : edges_) {
      rest_lengths_.push_back((rest[static_cast<std::size_t>(e[0])] - rest[static_cast<std::size_t>(e[1])]).norm());
    }
  } else if (rest_lengths_.size() != edges_.size()) {
    throw make_error("DistanceMapping: ", rest_lengths_.size(), " rest lengths for ", edges_.size(), " edges");
  }
}

template <class Real>
Index DistanceMapping<Real>::parent_extent() const {
  Index extent = 0;
  for (const Edge& e : edges_) extent = std::max({extent, e[0] + 1, e[1] + 1});
  return extent;
}

template <class Real>
void DistanceMapping<Real>::apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Vec3<Real>& a = x[static_cast<std::size_t>(edges_[i][0])];
    const Vec3<Real>& b = x[static_cast<std::size_t>(edges_[i][1])];
    y[i] = Vec3<Real>((b - a).norm() - rest_lengths_[i], 0, 0);
    directions_[i] = direction(a, b).u;
  }
}

template <class Real>
void DistanceMapping<Real>::positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Vec3<Real>& a = x[static_cast<std::size_t>(edges_[i][0])];
    const Vec3<Real>& b = x[static_cast<std::size_t>(edges_[i][1])];
    y[i] = Vec3<Real>((b - a).norm() - rest_lengths_[i], 0, 0);
  }
}

template <class Real>
void DistanceMapping<Real>::velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const auto a = static_cast<std::size_t>(edges_[i][0]), b = static_cast<std::size_t>(edges_[i][1]);
    y[i] = Vec3<Real>(direction(x[a], x[b]).u.dot(v[b] - v[a]), 0, 0);
  }
}

template <class Real>
void DistanceMapping<Real>::apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const auto a = static_cast<std::size_t>(edges_[i][0]), b = static_cast<std::size_t>(edges_[i][1]);
    dy[i] = Vec3<Real>(directions_[i].dot(dx[b] - dx[a]), 0, 0);
  }
}

template <class Real>
void DistanceMapping<Real>::apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Vec3<Real> along = f[i][0] * directions_[i];
    parent[static_cast<std::size_t>(edges_[i][0])] -= along;
    parent[static_cast<std::size_t>(edges_[i][1])] += along;
  }
}

template <class Real>
void DistanceMapping<Real>::row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  out.clear();
  Mat3<Real> minus = Mat3<Real>::Zero(), plus = Mat3<Real>::Zero();
  minus.row(0) = -directions_[i].transpose();
  plus.row(0) = directions_[i].transpose();
  // In increasing parent order, as SOFA inserts J's entries.
  if (edges_[i][0] <= edges_[i][1]) {
    out.emplace_back(edges_[i][0], minus);
    out.emplace_back(edges_[i][1], plus);
  } else {
    out.emplace_back(edges_[i][1], plus);
    out.emplace_back(edges_[i][0], minus);
  }
}

template <class Real>
std::vector<double> DistanceMapping<Real>::model_values() const {
  std::vector<double> values{static_cast<double>(edges_.size())};
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    values.push_back(static_cast<double>(edges_[i][0]));
    values.push_back(static_cast<double>(edges_[i][1]));
    values.push_back(static_cast<double>(rest_lengths_[i]));
  }
  return values;
}

template <class Real>
DistanceGeometricStiffness<Real>::DistanceGeometricStiffness(std::shared_ptr<const TetMesh> mesh, std::vector<Edge> edges,
                                                             std::shared_ptr<const std::vector<Vec3<Real>>> child_force,
                                                             GeometricStiffnessMethod method)
    : mesh_(std::move(mesh)), edges_(std::move(edges)), child_force_(std::move(child_force)), method_(method),
      blocks_(edges_.size(), Mat3<Real>::Zero()) {
  if (method_ == GeometricStiffnessMethod::none) throw make_error("DistanceGeometricStiffness: method none adds nothing");
  if (!child_force_) throw make_error("DistanceGeometricStiffness: no child forces to read");
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    for (Index p : edges_[i]) {
      if (p < 0 || p >= mesh_->num_points()) {
        throw make_error("DistanceMapping: edge ", i, " joins point ", p, ", outside the ", mesh_->num_points(), " points");
      }
    }
  }
}

template <class Real>
void DistanceGeometricStiffness<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>>) {
  const auto& force = *child_force_;
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Real f = i < force.size() ? force[i][0] : Real(0);
    if (f >= 0 && method_ == GeometricStiffnessMethod::stabilized) {
      blocks_[i].setZero();
      continue;
    }
    const auto d = DistanceMapping<Real>::direction(x[static_cast<std::size_t>(edges_[i][0])], x[static_cast<std::size_t>(edges_[i][1])]);
    blocks_[i] = (Mat3<Real>::Identity() - d.u * d.u.transpose()) * (f * d.inverse_length);
  }
}

template <class Real>
void DistanceGeometricStiffness<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real) const {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const auto a = static_cast<std::size_t>(edges_[i][0]), b = static_cast<std::size_t>(edges_[i][1]);
    const Vec3<Real> change = k_factor * (blocks_[i] * (dx[b] - dx[a]));
    df[a] -= change;
    df[b] += change;
  }
}

template <class Real>
void DistanceGeometricStiffness<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real) const {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Mat3<Real> k = k_factor * blocks_[i];
    const Index a = offset + 3 * edges_[i][0], b = offset + 3 * edges_[i][1];
    sink.add_block(a, a, k);
    sink.add_block(a, b, -k);
    sink.add_block(b, a, -k);
    sink.add_block(b, b, k);
  }
}

template <class Real>
void DistanceGeometricStiffness<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real) const {
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    diagonal[static_cast<std::size_t>(edges_[i][0])] += k_factor * blocks_[i];
    diagonal[static_cast<std::size_t>(edges_[i][1])] += k_factor * blocks_[i];
  }
}

template <class Real>
std::vector<double> DistanceGeometricStiffness<Real>::model_values() const {
  std::vector<double> values{static_cast<double>(method_), static_cast<double>(edges_.size())};
  for (const Edge& e : edges_) values.insert(values.end(), {static_cast<double>(e[0]), static_cast<double>(e[1])});
  return values;
}

template class DistanceMapping<float>;
template class DistanceMapping<double>;
template class DistanceGeometricStiffness<float>;
template class DistanceGeometricStiffness<double>;

}  // namespace fastcorot
