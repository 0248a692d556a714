#include "fastcorot/sim/mechanical_system.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace fastcorot {

namespace {

// The couplings as an operator C (each of its 3×3 blocks a multiple of the identity): the rows of
// the points they touch, each a list of (column point, weight); untouched points' rows are the
// identity's. The couplings compose in order: C = C_k ... C_1.
template <class Real>
using CouplingRows = std::map<Index, std::vector<std::pair<Index, Real>>>;

template <class Real>
CouplingRows<Real> coupling_rows(const std::vector<PointCoupling<Real>>& couplings) {
  CouplingRows<Real> rows;
  auto row = [&rows](Index i) -> std::vector<std::pair<Index, Real>>& {
    auto [at, inserted] = rows.try_emplace(i);
    if (inserted) at->second.emplace_back(i, Real(1));
    return at->second;
  };
  auto combine = [](const std::vector<std::pair<Index, Real>>& a, Real wa, const std::vector<std::pair<Index, Real>>& b,
                    Real wb) {
    std::map<Index, Real> sum;
    for (const auto& [j, w] : a) sum[j] += wa * w;
    for (const auto& [j, w] : b) sum[j] += wb * w;
    std::vector<std::pair<Index, Real>> out;
    for (const auto& [j, w] : sum) {
      if (w != 0) out.emplace_back(j, w);
    }
    return out;
  };
  for (const auto& c : couplings) {
    if (!c.two_way) {
      row(c.second).clear();
      continue;
    }
    const auto a = row(c.first), b = row(c.second);
    row(c.first) = combine(a, 1 - c.response, b, c.response);
    row(c.second) = combine(a, c.response, b, 1 - c.response);
  }
  return rows;
}

}  // namespace

template <class Real>
void MechanicalSystem<Real>::finalize() {
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  const Index n = size();
  for (Index i : fixed) {
    if (i < 0 || i >= n) throw make_error("fixed point index ", i, " out of range [0, ", n, ")");
  }
  for (Index i : zero_velocity) {
    if (i < 0 || i >= n) throw make_error("zero-velocity point index ", i, " out of range [0, ", n, ")");
  }
  if (rigids) rigids->check(n);
  for (const auto& p : projections) {
    if (p.point < 0 || p.point >= n) throw make_error("projected point index ", p.point, " out of range [0, ", n, ")");
    if (!p.projector.allFinite()) throw make_error("projected point ", p.point, ": the projection is not finite");
  }
  for (const auto& c : couplings) {
    if (c.first < 0 || c.first >= n || c.second < 0 || c.second >= n) {
      throw make_error("coupled points ", c.first, " and ", c.second, ": out of range [0, ", n, ")");
    }
    if (!std::isfinite(c.response) || !std::isfinite(c.position) || !std::isfinite(c.velocity)) {
      throw make_error("coupled points ", c.first, " and ", c.second, ": a factor is not finite");
    }
  }
  for (const auto& m : motions) {
    if (m.point < 0 || m.point >= n) throw make_error("moved point index ", m.point, " out of range [0, ", n, ")");
    if (!m.start.allFinite() || !m.end.allFinite() || !std::isfinite(m.begin_time) || !std::isfinite(m.end_time)) {
      throw make_error("moved point ", m.point, ": its motion is not finite");
    }
  }
  for (const auto& p : placements) {
    if (p.point < 0 || p.point >= n) throw make_error("projected point index ", p.point, " out of range [0, ", n, ")");
    if (!p.projector.allFinite() || !p.origin.allFinite() || !p.velocity_projector.allFinite()) {
      throw make_error("projected point ", p.point, ": the projection is not finite");
    }
  }
  // One entry per point: a stable sort keeps each point's projectors in the order given.
  std::stable_sort(projections.begin(), projections.end(),
                   [](const PointProjection<Real>& a, const PointProjection<Real>& b) { return a.point < b.point; });
  std::vector<PointProjection<Real>> combined;
  for (const auto& p : projections) {
    if (!combined.empty() && combined.back().point == p.point) {
      combined.back().projector = (p.projector * combined.back().projector).eval();
    } else {
      combined.push_back(p);
    }
  }
  projections = std::move(combined);
  for (const auto& constant : constant_forces) {
    if (constant.forces.size() != constant.indices.size()) {
      throw make_error("constant force: ", constant.forces.size(), " forces for ", constant.indices.size(),
                       " indices");
    }
    for (Index i : constant.indices) {
      if (i < 0 || i >= n) throw make_error("constant force index ", i, " out of range [0, ", n, ")");
    }
  }
  if (mass.size() != 0 && mass.size() != n) {
    throw make_error("the mass has ", mass.size(), " entries; the state has ", n, " points");
  }
  if (state.velocity.empty()) state.velocity.assign(static_cast<std::size_t>(n), Vec3<Real>::Zero());
  if (state.rest_position.empty()) state.rest_position = state.position;
  if (state.velocity.size() != state.position.size() || state.rest_position.size() != state.position.size()) {
    throw make_error("the state has ", n, " positions, ", state.velocity.size(), " velocities and ",
                     state.rest_position.size(), " rest positions");
  }
  set_threads(threads_);
  set_phase_times(times_);
}

template <class Real>
void MechanicalSystem<Real>::set_threads(int threads) {
  threads_ = std::max(threads, 1);
  for (auto& field : force_fields) field->set_threads(threads_);
}

template <class Real>
void MechanicalSystem<Real>::set_phase_times(PhaseTimes* times) {
  times_ = times;
  for (auto& field : force_fields) field->set_phase_times(times);
}

template <class Real>
void MechanicalSystem<Real>::compute_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f,
                                           std::span<const Vec3<Real>> v) {
  {
    const PhaseTimer timer(timer_slot(&PhaseTimes::mass_constraints));
    set_zero(f);
  }
  const std::span<const Vec3<Real>> velocity = v.empty() ? std::span<const Vec3<Real>>(state.velocity) : v;
  for (auto& field : force_fields) {
    field->set_velocity(velocity);
    field->add_force(x, f);  // times itself (add_force)
    field->set_velocity({});
  }
  const PhaseTimer timer(timer_slot(&PhaseTimes::mass_constraints));
  if (mass.size() != 0) mass.add_gravity(gravity, f);
  for (const auto& constant : constant_forces) {
    for (std::size_t i = 0; i < constant.indices.size(); ++i) {
      f[static_cast<std::size_t>(constant.indices[i])] += constant.forces[i];
    }
  }
  if (exchange) exchange->sum_shared(f);
}

template <class Real>
void MechanicalSystem<Real>::multiply(const MatrixFactors<Real>& factors, std::span<const Vec3<Real>> dx,
                                      std::span<Vec3<Real>> out) const {
  multiply_own_part(factors, dx, out);
  if (exchange) exchange->sum_shared(out);
  project(out);
}

template <class Real>
void MechanicalSystem<Real>::multiply_own_part(const MatrixFactors<Real>& factors, std::span<const Vec3<Real>> dx,
                                               std::span<Vec3<Real>> out) const {
  const PhaseTimer timer(timer_slot(&PhaseTimes::matrix_vector));
  if (factors.m != 0 && mass.size() != 0) {
    mass.multiply(dx, out, factors.m, threads_);
  } else {
    set_zero(out);
  }
  for (const auto& field : force_fields) field->add_dforce(dx, out, factors.k, factors.b);
}

template <class Real>
const Eigen::SparseMatrix<Real>& MechanicalSystem<Real>::assemble(const MatrixFactors<Real>& factors) const {
  TripletSink<Real>& sink = sink_;
  sink.triplets.clear();
  if (mass.size() != 0) mass.add_to_matrix(sink, factors.m);
  for (const auto& field : force_fields) field->add_stiffness(sink, factors.k, 0, factors.b);
  std::vector<bool> is_fixed(static_cast<std::size_t>(size()), false);
  std::vector<Index> held = fixed;
  held.insert(held.end(), isolated.begin(), isolated.end());
  held.insert(held.end(), moving.begin(), moving.end());
  for (Index i : held) is_fixed[static_cast<std::size_t>(i)] = true;
  auto& triplets = sink.triplets;
  if (!held.empty()) {
    triplets.erase(std::remove_if(triplets.begin(), triplets.end(),
                                  [&](const Eigen::Triplet<Real>& t) {
                                    return is_fixed[static_cast<std::size_t>(t.row() / 3)] ||
                                           is_fixed[static_cast<std::size_t>(t.col() / 3)];
                                  }),
                   triplets.end());
  }
  for (Index i : held) {
    for (Index c = 0; c < 3; ++c) triplets.emplace_back(3 * i + c, 3 * i + c, Real(1));
  }
  const Eigen::SparseMatrix<Real>& matrix = assembly_.to_sparse(triplets, 3 * size());
  if (projections.empty() && couplings.empty()) return matrix;
  // P A P + (I - P) with P the operator project() applies: the couplings C, then the per-point
  // projectors, then zero rows at fixed points (for a projector onto coordinate axes, SOFA's
  // clearing of the rows and columns of the fixed directions).
  const CouplingRows<Real> rows = coupling_rows(couplings);
  std::vector<const Mat3<Real>*> projector(static_cast<std::size_t>(size()), nullptr);
  for (const auto& p : projections) projector[static_cast<std::size_t>(p.point)] = &p.projector;
  std::vector<Eigen::Triplet<Real>> p_triplets, complement;
  const std::vector<std::pair<Index, Real>> unit_row = {{0, Real(1)}};
  for (Index i = 0; i < size(); ++i) {
    const auto at = rows.find(i);
    const Mat3<Real> local = is_fixed[static_cast<std::size_t>(i)] ? Mat3<Real>::Zero()
                             : projector[static_cast<std::size_t>(i)] ? *projector[static_cast<std::size_t>(i)]
                                                                       : Mat3<Real>::Identity();
    Mat3<Real> diagonal = Mat3<Real>::Zero();
    if (at == rows.end()) {
      diagonal = local;
      for (Index r = 0; r < 3; ++r) {
        for (Index c = 0; c < 3; ++c) {
          if (local(r, c) != 0) p_triplets.emplace_back(3 * i + r, 3 * i + c, local(r, c));
        }
      }
    } else {
      for (const auto& [j, w] : at->second) {
        const Mat3<Real> block = local * w;
        if (j == i) diagonal = block;
        for (Index r = 0; r < 3; ++r) {
          for (Index c = 0; c < 3; ++c) {
            if (block(r, c) != 0) p_triplets.emplace_back(3 * i + r, 3 * j + c, block(r, c));
          }
        }
      }
    }
    const Mat3<Real> rest = Mat3<Real>::Identity() - diagonal;
    for (Index r = 0; r < 3; ++r) {
      for (Index c = 0; c < 3; ++c) {
        if (rest(r, c) != 0) complement.emplace_back(3 * i + r, 3 * i + c, rest(r, c));
      }
    }
  }
  Eigen::SparseMatrix<Real> p_matrix(3 * size(), 3 * size()), rest_matrix(3 * size(), 3 * size());
  p_matrix.setFromTriplets(p_triplets.begin(), p_triplets.end());
  rest_matrix.setFromTriplets(complement.begin(), complement.end());
  // Off the diagonal, (I - P) is -P's off-diagonal blocks.
  Eigen::SparseMatrix<Real> off = p_matrix;
  off.prune([](Index r, Index c, const Real&) { return r / 3 != c / 3; });
  projected_ = p_matrix * matrix * p_matrix;
  projected_ += rest_matrix;
  projected_ -= off;
  projected_.makeCompressed();
  return projected_;
}

template <class Real>
void MechanicalSystem<Real>::diagonal_blocks(const MatrixFactors<Real>& factors, std::span<Mat3<Real>> blocks) const {
  if (blocks.size() != static_cast<std::size_t>(size())) {
    throw make_error("diagonal blocks: ", blocks.size(), " blocks for a system of ", size(), " points");
  }
  for (auto& block : blocks) block.setZero();
  if (mass.size() != 0) mass.add_diagonal_blocks(blocks, factors.m);
  for (const auto& field : force_fields) field->add_diagonal_blocks(blocks, factors.k, factors.b);
  // Block i of P A P + (I - P) for P = Ppoints C (project()'s operator without the fixed points,
  // whose blocks are the identity): sum_j P_ij A_jj P_ji + I - P_ii, with A's blocks between
  // different points left out (exact when the only points P joins share no element).
  std::vector<const Mat3<Real>*> projector(blocks.size(), nullptr);
  for (const auto& p : projections) projector[static_cast<std::size_t>(p.point)] = &p.projector;
  auto local = [&projector](Index i) -> Mat3<Real> {
    const Mat3<Real>* p = projector[static_cast<std::size_t>(i)];
    return p ? *p : Mat3<Real>::Identity();
  };
  const CouplingRows<Real> rows = coupling_rows(couplings);
  auto weight = [&rows](Index i, Index j) {
    const auto at = rows.find(i);
    if (at == rows.end()) return Real(i == j ? 1 : 0);
    for (const auto& [k, w] : at->second) {
      if (k == j) return w;
    }
    return Real(0);
  };
  const std::vector<Mat3<Real>> original(blocks.begin(), blocks.end());
  for (const auto& [i, row] : rows) {
    const Mat3<Real> pi = local(i);
    Mat3<Real> block = Mat3<Real>::Identity() - weight(i, i) * pi;
    for (const auto& [j, w] : row) block += w * weight(j, i) * (pi * original[static_cast<std::size_t>(j)] * local(j));
    blocks[static_cast<std::size_t>(i)] = block;
  }
  for (const auto& p : projections) {
    if (rows.count(p.point)) continue;
    Mat3<Real>& block = blocks[static_cast<std::size_t>(p.point)];
    block = (p.projector * block * p.projector + (Mat3<Real>::Identity() - p.projector)).eval();
  }
  for (const auto* held : {&fixed, &isolated, &moving}) {
    for (Index i : *held) blocks[static_cast<std::size_t>(i)].setIdentity();
  }
}

template <class Real>
void MechanicalSystem<Real>::project(std::span<Vec3<Real>> v) const {
  for (const auto& c : couplings) {
    Vec3<Real>& second = v[static_cast<std::size_t>(c.second)];
    if (!c.two_way) {
      second.setZero();
      continue;
    }
    Vec3<Real>& first = v[static_cast<std::size_t>(c.first)];
    const Vec3<Real> correction = (second - first) * c.response;
    first += correction;
    second -= correction;
  }
  for (const auto& p : projections) {
    Vec3<Real>& entry = v[static_cast<std::size_t>(p.point)];
    entry = (p.projector * entry).eval();
  }
  for (const auto* held : {&fixed, &isolated, &moving}) {
    for (Index i : *held) v[static_cast<std::size_t>(i)].setZero();
  }
}

template <class Real>
void MechanicalSystem<Real>::begin_step(double time) {
  if (linear_movements.empty()) return;
  moving.clear();
  for (const auto& movement : linear_movements) movement.held(time, moving);
}

template <class Real>
void MechanicalSystem<Real>::apply_placements(double time) {
  for (const auto& c : couplings) {
    const auto first = static_cast<std::size_t>(c.first), second = static_cast<std::size_t>(c.second);
    state.position[second] -= ((state.position[second] - state.position[first]) * c.position).eval();
    const Vec3<Real> correction = (state.velocity[second] - state.velocity[first]) * c.velocity;
    state.velocity[first] += correction;
    state.velocity[second] -= correction;
  }
  for (const auto& p : placements) {
    Vec3<Real>& x = state.position[static_cast<std::size_t>(p.point)];
    x = (p.origin + p.projector * (x - p.origin)).eval();
    Vec3<Real>& v = state.velocity[static_cast<std::size_t>(p.point)];
    v = (p.velocity_projector * v).eval();
  }
  for (const auto& m : motions) {
    const auto i = static_cast<std::size_t>(m.point);
    const double total = m.end_time - m.begin_time;
    if (time > m.begin_time && time <= m.end_time && total > 0) {
      state.position[i] = ((m.end - m.start) * static_cast<Real>(time) +
                           (m.start * static_cast<Real>(m.end_time) - m.end * static_cast<Real>(m.begin_time))) /
                          static_cast<Real>(total);
    } else if (time > m.end_time) {
      state.position[i] = m.end;
    }
    state.velocity[i].setZero();
  }
  for (auto& movement : linear_movements) movement.apply(time, state, rigids.get());
}

template <class Real>
TopologyChange MechanicalSystem<Real>::remove_tetrahedra(TetMesh& mesh, std::span<const Index> indices) {
  const TopologyChange change = mesh.remove_tetrahedra(indices);
  follow(mesh, change);
  return change;
}

template <class Real>
TopologyChange MechanicalSystem<Real>::add_tetrahedra(TetMesh& mesh, std::span<const Tetrahedron> tetrahedra) {
  for (const auto& field : force_fields) {
    if (&field->mesh() == &mesh) field->check_new_tetrahedra(tetrahedra);
  }
  check_rest_volumes<Real>(tetrahedra, state.rest_position, mesh.num_tetrahedra());
  const TopologyChange change = mesh.add_tetrahedra(tetrahedra);
  follow(mesh, change);
  return change;
}

template <class Real>
void MechanicalSystem<Real>::follow(const TetMesh& mesh, const TopologyChange& change) {
  for (auto& field : force_fields) {
    if (&field->mesh() == &mesh) field->apply(change);
  }
  if (mass.follows(mesh)) mass.apply(change, state.rest_position);
  // A point without tetrahedra in any force field and without mass is held still; one that gets a
  // tetrahedron back moves again.
  const auto connected = [&](Index v) {
    for (const auto& field : force_fields) {
      if (!field->mesh().tetrahedra_around_vertex(v).empty()) return true;
    }
    return false;
  };
  for (Index v : change.isolated_points) {
    const bool massless = mass.size() == 0 || mass.vertex_masses()[static_cast<std::size_t>(v)] == 0;
    if (!massless || connected(v)) continue;
    const auto at = std::lower_bound(isolated.begin(), isolated.end(), v);
    if (at == isolated.end() || *at != v) isolated.insert(at, v);
    state.velocity[static_cast<std::size_t>(v)].setZero();
  }
  for (Index v : change.reconnected_points) {
    const auto at = std::lower_bound(isolated.begin(), isolated.end(), v);
    if (at != isolated.end() && *at == v) isolated.erase(at);
  }
}

template <class Real>
Real MechanicalSystem<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (const auto& field : force_fields) energy += field->potential_energy(x);
  if (mass.size() != 0) energy += mass.gravity_energy(gravity, x);
  for (const auto& constant : constant_forces) {
    for (std::size_t i = 0; i < constant.indices.size(); ++i) {
      energy -= constant.forces[i].dot(x[static_cast<std::size_t>(constant.indices[i])]);
    }
  }
  return exchange ? exchange->sum(energy) : energy;
}

template <class Real>
Real MechanicalSystem<Real>::kinetic_energy() const {
  const Real energy = mass.size() == 0 ? Real(0) : mass.kinetic_energy(state.velocity);
  return exchange ? exchange->sum(energy) : energy;
}

template class MechanicalSystem<float>;
template class MechanicalSystem<double>;

}  // namespace fastcorot
