#include "fastcorot/fem/spring_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/tetrahedron_faces.h"

#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace fastcorot {

template <class Real>
std::vector<Spring<Real>> mesh_springs(const SpringTopology& topology, std::span<const Vec3<Real>> rest,
                                       const MeshSpringParameters<Real>& p) {
  const auto n = static_cast<Index>(rest.size());
  std::vector<Spring<Real>> springs;
  std::set<std::pair<Index, Index>> made;
  const auto add = [&](Index a, Index b, Real stiffness, Real damping) {
    if (a < 0 || a >= n || b < 0 || b >= n) {
      throw make_error("MeshSpringForceField: an element joins points ", a, " and ", b, ", outside the ", n, " points");
    }
    if (!made.insert({std::min(a, b), std::max(a, b)}).second) return;
    const Real length = (rest[static_cast<std::size_t>(b)] - rest[static_cast<std::size_t>(a)]).norm();
    const bool scaled = length > std::numeric_limits<Real>::epsilon();
    springs.push_back({a, b, scaled ? stiffness / length : stiffness, scaled ? damping / length : damping, length,
                       p.no_compression});
  };
  const auto add_all_pairs = [&](const auto& elements, Real stiffness, Real damping) {
    if (stiffness == 0 && damping == 0) return;
    for (const auto& e : elements) {
      for (std::size_t k = 0; k < e.size(); ++k) {
        for (std::size_t j = k + 1; j < e.size(); ++j) add(e[k], e[j], stiffness, damping);
      }
    }
  };
  add_all_pairs(topology.lines, p.lines_stiffness, p.lines_damping);
  add_all_pairs(topology.triangles, p.triangles_stiffness, p.triangles_damping);
  add_all_pairs(topology.quads, p.quads_stiffness, p.quads_damping);
  add_all_pairs(topology.tetrahedra, p.tetrahedra_stiffness, p.tetrahedra_damping);
  add_all_pairs(topology.hexahedra, p.cubes_stiffness, p.cubes_damping);
  return springs;
}

template <class Real>
std::vector<Spring<Real>> mesh_springs(const TetMesh& mesh, std::span<const Vec3<Real>> rest,
                                       const MeshSpringParameters<Real>& p) {
  if (rest.size() != static_cast<std::size_t>(mesh.num_points())) {
    throw make_error("MeshSpringForceField: ", rest.size(), " rest positions for a mesh of ", mesh.num_points(), " points");
  }
  SpringTopology topology;
  topology.lines.assign(mesh.edges().begin(), mesh.edges().end());
  topology.tetrahedra.assign(mesh.tetrahedra().begin(), mesh.tetrahedra().end());
  if (p.triangles_stiffness != 0 || p.triangles_damping != 0) topology.triangles = tetrahedron_set_triangles(topology.tetrahedra);
  return mesh_springs(topology, rest, p);
}

template <class Real>
SpringForceField<Real>::SpringForceField(std::shared_ptr<const TetMesh> mesh, std::vector<Spring<Real>> springs,
                                         Real rayleigh_stiffness, std::string component)
    : mesh_(std::move(mesh)), springs_(std::move(springs)), rayleigh_stiffness_(rayleigh_stiffness),
      component_(std::move(component)) {
  if (!mesh_) throw make_error(component_, ": no mesh");
  if (!(rayleigh_stiffness_ >= 0) || !std::isfinite(rayleigh_stiffness_)) {
    throw make_error(component_, ": rayleighStiffness = ", rayleigh_stiffness_, ": must be finite and >= 0");
  }
  const Index n = mesh_->num_points();
  for (std::size_t s = 0; s < springs_.size(); ++s) {
    const Spring<Real>& spring = springs_[s];
    if (spring.a < 0 || spring.a >= n || spring.b < 0 || spring.b >= n) {
      throw make_error(component_, ": spring ", s, " (", spring.a, ", ", spring.b, "): index out of range [0, ", n, ")");
    }
    if (spring.a == spring.b) throw make_error(component_, ": spring ", s, " joins point ", spring.a, " to itself");
    for (Real value : {spring.stiffness, spring.damping, spring.rest_length}) {
      if (!(value >= 0) || !std::isfinite(value)) {
        throw make_error(component_, ": spring ", s, " (", spring.a, ", ", spring.b, "): stiffness ", spring.stiffness,
                         ", damping ", spring.damping, ", rest length ", spring.rest_length, ": each must be finite and >= 0");
      }
    }
  }
  tangent_.assign(springs_.size(), Mat3<Real>::Zero());
  assembled_ = springs_.size();
}

template <class Real>
void SpringForceField<Real>::set_assembled_springs(std::size_t count) {
  if (count > springs_.size()) {
    throw make_error(component_, ": ", count, " assembled springs of ", springs_.size());
  }
  assembled_ = count;
}

template <class Real>
void SpringForceField<Real>::forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record) {
  PhaseTimer timer(times_ ? &times_->add_force : nullptr);
  const bool moving = velocity_.size() == x.size();
  for (std::size_t s = 0; s < springs_.size(); ++s) {
    const Spring<Real>& spring = springs_[s];
    const auto a = static_cast<std::size_t>(spring.a), b = static_cast<std::size_t>(spring.b);
    Vec3<Real> u = x[b] - x[a];
    const Real d = u.norm();
    if (!spring.enabled || !(d > Real(1e-9)) || (spring.elongation_only && !(d > spring.rest_length))) {
      if (record) tangent_[s].setZero();
      continue;
    }
    const Real inverse = Real(1) / d;
    u *= inverse;
    const Real speed = moving ? u.dot(velocity_[b] - velocity_[a]) : Real(0);
    const Real intensity = spring.stiffness * (d - spring.rest_length) + spring.damping * speed;
    f[a] += u * intensity;
    f[b] -= u * intensity;
    if (record) {
      const Real tangential = intensity * inverse;
      tangent_[s] = (spring.stiffness - tangential) * u * u.transpose();
      tangent_[s].diagonal().array() += tangential;
    }
  }
}

template <class Real>
void SpringForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  forces(x, f, true);
}

template <class Real>
void SpringForceField<Real>::add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  forces(x, f, false);
}

template <class Real>
void SpringForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                                        Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t s = 0; s < springs_.size(); ++s) {
    const auto a = static_cast<std::size_t>(springs_[s].a), b = static_cast<std::size_t>(springs_[s].b);
    const Vec3<Real> change = tangent_[s] * (dx[b] - dx[a]) * k;
    df[a] += change;
    df[b] -= change;
  }
}

template <class Real>
void SpringForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t s = 0; s < assembled_; ++s) {
    const Index a = offset + 3 * springs_[s].a, b = offset + 3 * springs_[s].b;
    const Mat3<Real> block = tangent_[s] * k;
    sink.add_block(a, a, -block);
    sink.add_block(a, b, block);
    sink.add_block(b, a, block);
    sink.add_block(b, b, -block);
  }
}

template <class Real>
void SpringForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t s = 0; s < assembled_; ++s) {
    diagonal[static_cast<std::size_t>(springs_[s].a)] -= tangent_[s] * k;
    diagonal[static_cast<std::size_t>(springs_[s].b)] -= tangent_[s] * k;
  }
}

template <class Real>
Real SpringForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (const Spring<Real>& spring : springs_) {
    const Real d = (x[static_cast<std::size_t>(spring.b)] - x[static_cast<std::size_t>(spring.a)]).norm();
    if (!spring.enabled || !(d > Real(1e-9)) || (spring.elongation_only && !(d > spring.rest_length))) continue;
    energy += spring.stiffness * (d - spring.rest_length) * (d - spring.rest_length) / 2;
  }
  return energy;
}

template <class Real>
std::vector<Mat3<Real>> SpringForceField<Real>::rotations() const {
  return std::vector<Mat3<Real>>(static_cast<std::size_t>(mesh_->num_tetrahedra()), Mat3<Real>::Identity());
}

template <class Real>
void SpringForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron>) const {
  throw make_error(component_, ": its springs are made once, at init: topological changes of its mesh are not supported");
}

template <class Real>
void SpringForceField<Real>::apply(const TopologyChange&) {
  throw make_error(component_, ": its springs are made once, at init: topological changes of its mesh are not supported");
}

template <class Real>
std::vector<double> SpringForceField<Real>::model_values() const {
  std::vector<double> values{static_cast<double>(rayleigh_stiffness_)};
  for (const Spring<Real>& s : springs_) {
    values.insert(values.end(), {static_cast<double>(s.a), static_cast<double>(s.b), static_cast<double>(s.stiffness),
                                 static_cast<double>(s.damping), static_cast<double>(s.rest_length),
                                 !s.enabled ? -1.0 : (s.elongation_only ? 1.0 : 0.0)});  // -1: disabled
  }
  return values;
}

template <class Real>
std::size_t SpringForceField<Real>::memory_bytes() const {
  return springs_.size() * (sizeof(Spring<Real>) + sizeof(Mat3<Real>));
}

template std::vector<Spring<double>> mesh_springs(const TetMesh&, std::span<const Vec3<double>>, const MeshSpringParameters<double>&);
template std::vector<Spring<double>> mesh_springs(const SpringTopology&, std::span<const Vec3<double>>, const MeshSpringParameters<double>&);
template std::vector<Spring<float>> mesh_springs(const TetMesh&, std::span<const Vec3<float>>, const MeshSpringParameters<float>&);
template std::vector<Spring<float>> mesh_springs(const SpringTopology&, std::span<const Vec3<float>>, const MeshSpringParameters<float>&);
template class SpringForceField<double>;
template class SpringForceField<float>;

}  // namespace fastcorot
