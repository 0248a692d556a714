#include "fastcorot/fem/corotational_force_field.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <utility>

namespace fastcorot {

namespace {

template <class Real>
void check_parameter_list(const std::vector<Real>& values, const char* name, Index num_tetrahedra) {
  if (values.size() != 1 && values.size() != static_cast<std::size_t>(num_tetrahedra)) {
    throw make_error(name, ": ", values.size(), " values given; expected 1 or one per tetrahedron (",
                     num_tetrahedra, ")");
  }
}

// SPEC.md: element t uses entry t if present, else entry 0.
template <class Real>
Real entry_for(const std::vector<Real>& values, std::size_t t) {
  return t < values.size() ? values[t] : values.front();
}

template <class Real>
LameParameters<Real> element_lame(const std::vector<Real>& young, const std::vector<Real>& poisson,
                                  std::size_t t) {
  try {
    return lame_parameters(entry_for(young, t), entry_for(poisson, t));
  } catch (const Error& error) {
    if (young.size() == 1 && poisson.size() == 1) throw;
    throw make_error(error.what(), " (tetrahedron ", t, ")");
  }
}

}  // namespace

template <class Real>
CorotationalForceField<Real>::CorotationalForceField(std::shared_ptr<TetMesh> mesh,
                                                     std::span<const Vec3<Real>> rest_positions,
                                                     Parameters parameters)
    : mesh_(std::move(mesh)),
      rest_positions_(rest_positions.begin(), rest_positions.end()),
      parameters_(std::move(parameters)) {
  if (!mesh_ || mesh_->num_tetrahedra() == 0) {
    throw make_error("FastTetrahedralCorotationalForceField: the topology has no tetrahedra");
  }
  const Index n = mesh_->num_tetrahedra();
  check_parameter_list(parameters_.young_modulus, "youngModulus", n);
  check_parameter_list(parameters_.poisson_ratio, "poissonRatio", n);
  if (!(parameters_.rayleigh_stiffness >= 0) || !std::isfinite(parameters_.rayleigh_stiffness)) {
    throw make_error("rayleighStiffness = ", parameters_.rayleigh_stiffness,
                     ": must be a finite value >= 0");
  }
  check_rest_volumes<Real>(*mesh_, rest_positions_);
  lame_.reserve(static_cast<std::size_t>(n));
  for (std::size_t t = 0; t < static_cast<std::size_t>(n); ++t) {
    lame_.push_back(element_lame(parameters_.young_modulus, parameters_.poisson_ratio, t));
  }
  set_method(parameters_.method);
}

template <class Real>
TetrahedronRest<Real> CorotationalForceField<Real>::compute_rest(Index t) const {
  const auto p = tetrahedron_points<Real>(mesh_->tetrahedron(t), rest_positions_);
  return tetrahedron_rest(p, lame_[static_cast<std::size_t>(t)], parameters_.method);
}

template <class Real>
void CorotationalForceField<Real>::set_method(RotationMethod method) {
  parameters_.method = method;
  const Index n = mesh_->num_tetrahedra();
  rest_.clear();
  rest_.reserve(static_cast<std::size_t>(n));
  for (Index t = 0; t < n; ++t) rest_.push_back(compute_rest(t));
  rotations_.assign(static_cast<std::size_t>(n), Mat3<Real>::Identity());
  rebuild_edge_stiffness();
}

template <class Real>
void CorotationalForceField<Real>::check_size(std::span<const Vec3<Real>> v, const char* what) const {
  if (v.size() != static_cast<std::size_t>(mesh_->num_points())) {
    throw make_error("FastTetrahedralCorotationalForceField: ", what, " holds ", v.size(),
                     " points; the topology has ", mesh_->num_points());
  }
}

template <class Real>
void CorotationalForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  check_size(x, "x");
  check_size(f, "f");
  const auto tetrahedra = mesh_->tetrahedra();
  for (std::size_t t = 0; t < tetrahedra.size(); ++t) {
    const auto p = tetrahedron_points<Real>(tetrahedra[t], rest_positions_);
    const auto xt = tetrahedron_points(tetrahedra[t], x);
    rotations_[t] = tetrahedron_rotation(rest_[t], xt, parameters_.method);
    const auto ft = tetrahedron_force(rest_[t], p, xt, rotations_[t]);
    for (int j = 0; j < 4; ++j) f[static_cast<std::size_t>(tetrahedra[t][j])] += ft[j];
  }
  rebuild_edge_stiffness();
}

template <class Real>
void CorotationalForceField<Real>::rebuild_edge_stiffness() {
  edge_stiffness_.assign(static_cast<std::size_t>(mesh_->num_edges()), Mat3<Real>::Zero());
  for (Index t = 0; t < mesh_->num_tetrahedra(); ++t) {
    const auto& rest = rest_[static_cast<std::size_t>(t)];
    const Mat3<Real>& r = rotations_[static_cast<std::size_t>(t)];
    const std::array<Vec3<Real>, 4> rotated = {r * rest.shape[0], r * rest.shape[1], r * rest.shape[2],
                                               r * rest.shape[3]};
    const auto& edges = mesh_->edges_of_tetrahedron(t);
    for (int e = 0; e < 6; ++e) {
      // The block couples local vertex l to k; it is stored from the mesh edge's first vertex.
      edge_stiffness_[static_cast<std::size_t>(edges[e])] +=
          rotated_edge_block(rest, rotated, e, !mesh_->edge_follows_mesh_edge(t, e));
    }
  }
}

template <class Real>
void CorotationalForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df,
                                              Real k_factor, Real b_factor) const {
  check_size(dx, "dx");
  check_size(df, "df");
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  const auto edges = mesh_->edges();
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto a = static_cast<std::size_t>(edges[e][0]);
    const auto b = static_cast<std::size_t>(edges[e][1]);
    const Vec3<Real> w = k * (dx[b] - dx[a]);
    df[b] += edge_stiffness_[e] * w;
    df[a] -= edge_stiffness_[e].transpose() * w;
  }
}

template <class Real>
void CorotationalForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset,
                                                 Real b_factor) const {
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  for (Index t = 0; t < mesh_->num_tetrahedra(); ++t) {
    const Mat3<Real>& r = rotations_[static_cast<std::size_t>(t)];
    const Tetrahedron& tet = mesh_->tetrahedron(t);
    for (int j = 0; j < 4; ++j) {
      const Mat3<Real> block = -k * (r * vertex_block(rest_[static_cast<std::size_t>(t)], j) * r.transpose());
      sink.add_block(offset + 3 * tet[j], offset + 3 * tet[j], block);
    }
  }
  const auto edges = mesh_->edges();
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Index a = edges[e][0];
    const Index b = edges[e][1];
    sink.add_block(offset + 3 * a, offset + 3 * b, -k * edge_stiffness_[e].transpose());
    sink.add_block(offset + 3 * b, offset + 3 * a, -k * edge_stiffness_[e]);
  }
}

template <class Real>
Eigen::SparseMatrix<Real> CorotationalForceField<Real>::stiffness_matrix(Real k_factor) const {
  TripletSink<Real> sink;
  add_stiffness(sink, k_factor);
  return sink.to_sparse(3 * mesh_->num_points());
}

template <class Real>
Real CorotationalForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  check_size(x, "x");
  Real energy = 0;
  const auto tetrahedra = mesh_->tetrahedra();
  for (std::size_t t = 0; t < tetrahedra.size(); ++t) {
    const auto p = tetrahedron_points<Real>(tetrahedra[t], rest_positions_);
    const auto xt = tetrahedron_points(tetrahedra[t], x);
    const Mat3<Real> r = tetrahedron_rotation(rest_[t], xt, parameters_.method);
    energy += tetrahedron_energy(rest_[t], p, xt, r);
  }
  return energy;
}

template <class Real>
std::vector<Real> CorotationalForceField<Real>::rest_volumes() const {
  std::vector<Real> volumes;
  volumes.reserve(rest_.size());
  for (const auto& rest : rest_) volumes.push_back(rest.volume);
  return volumes;
}

template <class Real>
void CorotationalForceField<Real>::add_tetrahedra(std::span<const Tetrahedron> tetrahedra) {
  const Index first = mesh_->num_tetrahedra();
  TetMesh grown = *mesh_;
  grown.add_tetrahedra(tetrahedra);
  // Validate the grown mesh before touching any state, so a failure leaves the field as it was.
  check_rest_volumes<Real>(grown, rest_positions_);
  const LameParameters<Real> lame0 =
      lame_parameters(parameters_.young_modulus.front(), parameters_.poisson_ratio.front());
  std::vector<TetrahedronRest<Real>> added;
  for (Index t = first; t < grown.num_tetrahedra(); ++t) {
    const auto p = tetrahedron_points<Real>(grown.tetrahedron(t), rest_positions_);
    added.push_back(tetrahedron_rest(p, lame0, parameters_.method));
  }
  *mesh_ = std::move(grown);
  for (auto& rest : added) {
    rest_.push_back(rest);
    lame_.push_back(lame0);
    rotations_.push_back(Mat3<Real>::Identity());
    if (parameters_.young_modulus.size() > 1) parameters_.young_modulus.push_back(parameters_.young_modulus.front());
    if (parameters_.poisson_ratio.size() > 1) parameters_.poisson_ratio.push_back(parameters_.poisson_ratio.front());
  }
  rebuild_edge_stiffness();
}

template <class Real>
void CorotationalForceField<Real>::remove_tetrahedra(std::span<const Index> indices) {
  mesh_->remove_tetrahedra(indices);  // validates the indices
  std::vector<bool> removed(rest_.size(), false);
  for (Index t : indices) removed[static_cast<std::size_t>(t)] = true;
  auto keep = [&](auto& values) {
    if (values.size() != removed.size()) return;
    std::size_t out = 0;
    for (std::size_t t = 0; t < removed.size(); ++t) {
      if (!removed[t]) values[out++] = values[t];
    }
    values.resize(out);
  };
  keep(rest_);
  keep(lame_);
  keep(rotations_);
  // A single value applies to every tetrahedron and stays; per-tetrahedron lists follow.
  if (parameters_.young_modulus.size() > 1) keep(parameters_.young_modulus);
  if (parameters_.poisson_ratio.size() > 1) keep(parameters_.poisson_ratio);
  rebuild_edge_stiffness();
}

template <class Real>
void CorotationalForceField<Real>::update_topology_information() {
  mesh_->update_topology_information();
  rebuild_edge_stiffness();
}

template class CorotationalForceField<float>;
template class CorotationalForceField<double>;

}  // namespace fastcorot
