#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/lame.h"
#include "fastcorot/core/parallel.h"
#include "fastcorot/core/rotation.h"
#include "fastcorot/fem/tetrahedron_element.h"
#include "material_checks.h"
#include "tetrahedron_fem_kernels.h"

#include <cmath>

namespace fastcorot {

TetrahedronFEMMethod parse_tetrahedron_fem_method(std::string_view name) {
  if (name == "small") return TetrahedronFEMMethod::small;
  if (name == "large") return TetrahedronFEMMethod::large;
  if (name == "polar") return TetrahedronFEMMethod::polar;
  if (name == "svd") return TetrahedronFEMMethod::svd;
  throw make_error("method = \"", name, "\": expected small, large, polar or svd");
}

std::string to_string(TetrahedronFEMMethod method) {
  switch (method) {
    case TetrahedronFEMMethod::small: return "small";
    case TetrahedronFEMMethod::large: return "large";
    case TetrahedronFEMMethod::polar: return "polar";
    case TetrahedronFEMMethod::svd: return "svd";
  }
  return "?";
}

namespace {

// SOFA's peudo_determinant_for_coef of the 2×3 matrix with rows (p_u q_u r_u) and (p_v q_v r_v),
// written in SOFA's order of operations.
template <class Real>
Real pseudo_determinant(const Vec3<Real>& p, const Vec3<Real>& q, const Vec3<Real>& r, int u, int v) {
  return q[u] * r[v] - q[v] * r[u] - p[u] * r[v] + p[v] * r[u] + p[u] * q[v] - p[v] * q[u];
}

// J's values (SOFA's computeStrainDisplacement) for the element (a, b, c, d): vertex i's gradient
// entries come from the other three vertices, starting after i, with alternating signs.
template <class Real>
std::array<Vec3<Real>, 4> strain_gradients(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                           const Vec3<Real>& d) {
  const auto entries = [](const Vec3<Real>& p, const Vec3<Real>& q, const Vec3<Real>& r, Real sign) {
    return Vec3<Real>(sign * pseudo_determinant(p, q, r, 1, 2), -sign * pseudo_determinant(p, q, r, 0, 2),
                      sign * pseudo_determinant(p, q, r, 0, 1));
  };
  return {entries(b, c, d, Real(-1)), entries(c, d, a, Real(1)), entries(d, a, b, Real(-1)),
          entries(a, b, c, Real(1))};
}

// SOFA's computeRotationLarge: rows x along (b - a), z normal to the plane of (b - a, c - a).
template <class Real>
Mat3<Real> large_frame(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c) {
  return qr_frame<Real>(b - a, c - a);
}

template <class Real>
Mat3<Real> edge_rows(const TetPoints<Real>& p) {
  Mat3<Real> rows;
  rows.row(0) = (p[1] - p[0]).transpose();
  rows.row(1) = (p[2] - p[0]).transpose();
  rows.row(2) = (p[3] - p[0]).transpose();
  return rows;
}

// F = J K J^T D for one element (SOFA's computeForce, in its order of operations): g are J's
// values per vertex, k K's three values, D the twelve displacements.
// SOFA's plasticity thresholds (TetrahedronFEMForceField's computeForce); max <= 0: off.
template <class Real>
struct Plasticity {
  Real max = 0, yield = 0, creep = 0;
};

template <class Real>
std::array<Vec3<Real>, 4> element_force(const std::array<Vec3<Real>, 4>& g, const Vec3<Real>& k,
                                        const std::array<Vec3<Real>, 4>& d, std::array<Real, 6>* plastic = nullptr,
                                        const Plasticity<Real>& plasticity = {}) {
  Real e[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    e[0] += g[i].x() * d[i].x();
    e[1] += g[i].y() * d[i].y();
    e[2] += g[i].z() * d[i].z();
    e[3] += g[i].y() * d[i].x() + g[i].x() * d[i].y();
    e[4] += g[i].z() * d[i].y() + g[i].y() * d[i].z();
    e[5] += g[i].z() * d[i].x() + g[i].x() * d[i].z();
  }
  if (plastic && plasticity.max > 0) {
    // The strain's elastic part grows the plastic one by creep beyond the yield, which is then
    // capped at max; the force is that of what remains.
    std::array<Real, 6>& p = *plastic;
    Real elastic[6], elastic_norm2 = 0;
    for (int c = 0; c < 6; ++c) {
      elastic[c] = e[c] - p[static_cast<std::size_t>(c)];
      elastic_norm2 += elastic[c] * elastic[c];
    }
    if (elastic_norm2 > plasticity.yield * plasticity.yield) {
      for (int c = 0; c < 6; ++c) p[static_cast<std::size_t>(c)] += plasticity.creep * elastic[c];
    }
    Real plastic_norm2 = 0;
    for (Real v : p) plastic_norm2 += v * v;
    if (plastic_norm2 > plasticity.max * plasticity.max) {
      for (Real& v : p) v *= plasticity.max / std::sqrt(plastic_norm2);
    }
    for (int c = 0; c < 6; ++c) e[c] -= p[static_cast<std::size_t>(c)];
  }
  const Real s[6] = {k[0] * e[0] + k[1] * e[1] + k[1] * e[2], k[1] * e[0] + k[0] * e[1] + k[1] * e[2],
                     k[1] * e[0] + k[1] * e[1] + k[0] * e[2], k[2] * e[3],
                     k[2] * e[4],                             k[2] * e[5]};
  std::array<Vec3<Real>, 4> f;
  for (int i = 0; i < 4; ++i) {
    f[i] = Vec3<Real>(g[i].x() * s[0] + g[i].y() * s[3] + g[i].z() * s[5],
                      g[i].y() * s[1] + g[i].x() * s[3] + g[i].z() * s[4],
                      g[i].z() * s[2] + g[i].y() * s[4] + g[i].x() * s[5]);
  }
  return f;
}

}  // namespace

template <class Real>
TetrahedronFEMForceField<Real>::TetrahedronFEMForceField(std::shared_ptr<TetMesh> mesh,
                                                         std::span<const Vec3<Real>> rest_positions,
                                                         Parameters parameters)
    : mesh_(std::move(mesh)),
      rest_positions_(rest_positions.begin(), rest_positions.end()),
      parameters_(std::move(parameters)) {
  if (!mesh_ || mesh_->num_tetrahedra() == 0) {
    throw make_error("TetrahedronFEMForceField: the topology has no tetrahedra");
  }
  const Index n = mesh_->num_tetrahedra();
  detail::check_material_lists(parameters_.young_modulus, parameters_.poisson_ratio, parameters_.rayleigh_stiffness, n);
  for (const Real value : {parameters_.plastic_max_threshold, parameters_.plastic_yield_threshold, parameters_.plastic_creep}) {
    if (!std::isfinite(value) || value < 0) {
      throw make_error("plasticMaxThreshold ", parameters_.plastic_max_threshold, ", plasticYieldThreshold ",
                       parameters_.plastic_yield_threshold, ", plasticCreep ", parameters_.plastic_creep,
                       ": each must be finite and >= 0");
    }
  }
  if (parameters_.update_stiffness_matrix && parameters_.method == TetrahedronFEMMethod::large) {
    throw make_error("updateStiffnessMatrix with method large is not supported (SOFA updates only some entries of J "
                     "there, leaving the others at the rest shape's); polar and svd are");
  }
  for (std::size_t i = 0; i < parameters_.local_stiffness_factor.size(); ++i) {
    const Real factor = parameters_.local_stiffness_factor[i];
    if (!(factor > 0) || !std::isfinite(factor)) {
      throw make_error("localStiffnessFactor[", i, "] = ", factor, ": must be a finite value > 0");
    }
  }
  if (parameters_.von_mises < 0 || parameters_.von_mises > 2) {
    throw make_error("computeVonMisesStress = ", parameters_.von_mises,
                     ": expected 0 (none), 1 (corotational strain) or 2 (Green strain)");
  }
  if (static_cast<Index>(rest_positions_.size()) != mesh_->num_points()) {
    throw make_error("TetrahedronFEMForceField: ", rest_positions_.size(), " rest positions for a mesh of ",
                     mesh_->num_points(), " points");
  }
  check_rest_volumes<Real>(*mesh_, rest_positions_);
  young_per_tetrahedron_ = parameters_.young_modulus.size() > 1;
  poisson_per_tetrahedron_ = parameters_.poisson_ratio.size() > 1;
  elements_.resize(static_cast<std::size_t>(n));
  for (Index t = 0; t < n; ++t) initialise_element(t);
  schedule();
  last_positions_ = rest_positions_;
  refresh_blocks();
  update_von_mises_stress(rest_positions_);  // SOFA's reinit computes it once
}

template <class Real>
Real TetrahedronFEMForceField<Real>::young_modulus_of(Index t) const {
  const auto& young = parameters_.young_modulus;
  const auto i = static_cast<std::size_t>(t);
  Real e = young_per_tetrahedron_ && i < young.size() ? young[i] : young.front();
  const auto& factors = parameters_.local_stiffness_factor;
  if (!factors.empty()) {
    // SOFA: factor[i * M / N] for N tetrahedra (with the count the field was built with).
    const std::size_t m = factors.size(), count = elements_.size();
    e *= factors[std::min(m - 1, i * m / count)];
  }
  return e;
}

template <class Real>
Real TetrahedronFEMForceField<Real>::poisson_ratio_of(Index t) const {
  const auto& poisson = parameters_.poisson_ratio;
  const auto i = static_cast<std::size_t>(t);
  return poisson_per_tetrahedron_ && i < poisson.size() ? poisson[i] : poisson.front();
}

template <class Real>
void TetrahedronFEMForceField<Real>::initialise_element(Index t) {
  Element& element = elements_[static_cast<std::size_t>(t)];
  element = Element{};
  const Real young = young_modulus_of(t), nu = poisson_ratio_of(t);
  try {
    lame_parameters(young, nu);  // the same checks (and messages) as every force field
  } catch (const Error& error) {
    if (!young_per_tetrahedron_ && !poisson_per_tetrahedron_ && parameters_.local_stiffness_factor.empty()) throw;
    throw make_error(error.what(), " (tetrahedron ", t, ")");
  }
  const TetPoints<Real> p = tetrahedron_points<Real>(mesh_->tetrahedron(t), rest_positions_);
  // SOFA's computeMaterialStiffness: the unit matrix entries scaled by E (1 - nu) / ((1 + nu)
  // (1 - 2 nu)), then divided by 36 |V|.
  const Real scale = (young * (1 - nu)) / ((1 + nu) * (1 - 2 * nu));
  const Real volume36 = std::abs(signed_volume(p)) * 36;
  element.material = Vec3<Real>((1 * scale) / volume36, ((nu / (1 - nu)) * scale) / volume36,
                                (((1 - 2 * nu) / (2 * (1 - nu))) * scale) / volume36);
  switch (parameters_.method) {
    case TetrahedronFEMMethod::small:
      element.gradient = strain_gradients(p[0], p[1], p[2], p[3]);
      for (int i = 0; i < 4; ++i) element.rotated_rest[static_cast<std::size_t>(i)] = p[static_cast<std::size_t>(i)];
      return;
    case TetrahedronFEMMethod::large: {
      const Mat3<Real> frame = large_frame(p[0], p[1], p[2]);
      element.initial_rotation = frame.transpose();
      std::array<Vec3<Real>, 4> r;
      for (int i = 0; i < 4; ++i) r[static_cast<std::size_t>(i)] = frame * p[static_cast<std::size_t>(i)];
      for (int i = 1; i < 4; ++i) r[static_cast<std::size_t>(i)] -= r[0];
      r[0].setZero();
      element.rotated_rest = r;
      break;
    }
    case TetrahedronFEMMethod::svd:
      element.initial_transformation = edge_rows(p).inverse();
      [[fallthrough]];
    case TetrahedronFEMMethod::polar: {
      const Mat3<Real> frame = polar_factor<Real>(edge_rows(p));
      element.initial_rotation = frame.transpose();
      for (int i = 0; i < 4; ++i) {
        element.rotated_rest[static_cast<std::size_t>(i)] = frame * p[static_cast<std::size_t>(i)];
      }
      break;
    }
  }
  element.rotation = element.initial_rotation;
  const auto& r = element.rotated_rest;
  element.gradient = strain_gradients(r[0], r[1], r[2], r[3]);
}

template <class Real>
void TetrahedronFEMForceField<Real>::schedule() {
  schedule_ = make_scatter_schedule<4>(mesh_->num_points(), mesh_->tetrahedra());
  batched_constants_.resize(schedule_.order.size());
  for (std::size_t p = 0; p < schedule_.order.size(); ++p) {
    const Element& element = elements_[static_cast<std::size_t>(schedule_.order[p])];
    BatchedConstants& c = batched_constants_[p];
    for (std::size_t i = 0; i < 4; ++i) {
      for (int k = 0; k < 3; ++k) {
        c.rest[i][k] = element.rotated_rest[i][k];
        c.gradient[i][k] = element.gradient[i][k];
      }
    }
    for (int k = 0; k < 3; ++k) c.material[k] = element.material[k];
  }
  lay_out_blocks();
}

template <class Real>
void TetrahedronFEMForceField<Real>::check_size(std::span<const Vec3<Real>> v, const char* what) const {
  if (static_cast<Index>(v.size()) != mesh_->num_points()) {
    throw make_error("TetrahedronFEMForceField: ", what, " has ", v.size(), " points; the mesh has ",
                     mesh_->num_points());
  }
}

template <class Real>
typename TetrahedronFEMForceField<Real>::StrainDisplacement TetrahedronFEMForceField<Real>::strain_displacement(
    Index t) const {
  const Element& element = this->element(t);
  StrainDisplacement j = StrainDisplacement::Zero();
  for (int i = 0; i < 4; ++i) {
    const Vec3<Real>& g = element.gradient[static_cast<std::size_t>(i)];
    j(3 * i, 0) = j(3 * i + 1, 3) = j(3 * i + 2, 5) = g.x();
    j(3 * i, 3) = j(3 * i + 1, 1) = j(3 * i + 2, 4) = g.y();
    j(3 * i, 5) = j(3 * i + 1, 4) = j(3 * i + 2, 2) = g.z();
  }
  return j;
}

template <class Real>
typename TetrahedronFEMForceField<Real>::Mat6 TetrahedronFEMForceField<Real>::material_matrix(Index t) const {
  const Vec3<Real>& k = this->element(t).material;
  Mat6 m = Mat6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = i == j ? k[0] : k[1];
    m(3 + i, 3 + i) = k[2];
  }
  return m;
}

template <class Real>
Mat3<Real> TetrahedronFEMForceField<Real>::frame(const Element& element, const TetPoints<Real>& p,
                                                 TetrahedronFEMMethod method) {
  switch (method) {
    case TetrahedronFEMMethod::small:
      return Mat3<Real>::Identity();
    case TetrahedronFEMMethod::large:
      return large_frame(p[0], p[1], p[2]);
    case TetrahedronFEMMethod::polar:
      return polar_factor<Real>(edge_rows(p));
    default: {
      const Mat3<Real> a = edge_rows(p);
      const Mat3<Real> deformation = a * element.initial_transformation;
      if (deformation.determinant() < Real(1e-6)) {
        // Inverted or too flat: the rotation of a stable SVD, composed with the rest frame.
        return stable_polar_factor<Real>(deformation) * element.initial_rotation.transpose();
      }
      return polar_factor<Real>(a);
    }
  }
}

template <class Real>
std::array<Vec3<Real>, 4> TetrahedronFEMForceField<Real>::displacement_in_frame(const Element& element,
                                                                                const TetPoints<Real>& p,
                                                                                TetrahedronFEMMethod method,
                                                                                const Mat3<Real>& frame) {
  const auto& rest = element.rotated_rest;
  std::array<Vec3<Real>, 4> d;
  if (method == TetrahedronFEMMethod::small) {
    // SOFA's accumulateForceSmall: displacements relative to the first vertex.
    d[0].setZero();
    for (std::size_t i = 1; i < 4; ++i) d[i] = rest[i] - rest[0] - p[i] + p[0];
    return d;
  }
  std::array<Vec3<Real>, 4> deformed;
  for (std::size_t i = 0; i < 4; ++i) deformed[i] = frame * p[i];
  if (method == TetrahedronFEMMethod::large) {
    // SOFA's accumulateForceLarge: the frame puts vertex 1 on the x axis and vertex 2 in the xy
    // plane, whose other coordinates it takes as exactly zero.
    deformed[1][0] -= deformed[0][0];
    deformed[2][0] -= deformed[0][0];
    deformed[2][1] -= deformed[0][1];
    deformed[3] -= deformed[0];
    d[0].setZero();
    d[1] = Vec3<Real>(rest[1][0] - deformed[1][0], 0, 0);
    d[2] = Vec3<Real>(rest[2][0] - deformed[2][0], rest[2][1] - deformed[2][1], 0);
    d[3] = rest[3] - deformed[3];
  } else {
    for (std::size_t i = 0; i < 4; ++i) d[i] = rest[i] - deformed[i];
  }
  return d;
}

template <class Real>
std::array<Vec3<Real>, 4> TetrahedronFEMForceField<Real>::displacement(const Element& element, const TetPoints<Real>& p,
                                                                       TetrahedronFEMMethod method, Mat3<Real>& frame) {
  frame = TetrahedronFEMForceField::frame(element, p, method);
  return displacement_in_frame(element, p, method, frame);
}

template <class Real>
template <class Body>
void TetrahedronFEMForceField<Real>::for_each_element(Index begin, Index end, std::span<const Vec3<Real>> x,
                                                      const Body& body) const {
  for_each_batch(begin, end, x, [&](Index first, Index count, const TetPoints<Real>* points, const Mat3<Real>* frames) {
    for (Index j = 0; j < count; ++j) body(schedule_.order[static_cast<std::size_t>(first + j)], points[j], frames[j]);
  });
}

template <class Real>
template <class Body>
void TetrahedronFEMForceField<Real>::for_each_batch(Index begin, Index end, std::span<const Vec3<Real>> x,
                                                    const Body& body) const {
  // The frames of eight elements first, then the rest of each. A frame is a chain of square roots
  // and divisions (or the polar iteration): the QR frames (large) and the polar factors (polar, and
  // svd's elements that are not inverted) go four at a time through qr_frames and polar_factors,
  // whose SIMD lanes run four chains side by side, bit for bit qr_frame's and polar_factor's. Each
  // element's arithmetic and the order of the elements are unchanged.
  constexpr Index kBatch = 8;
  const TetrahedronFEMMethod method = parameters_.method;
  const bool polar = method == TetrahedronFEMMethod::polar || method == TetrahedronFEMMethod::svd;
  std::array<TetPoints<Real>, kBatch> points;
  std::array<Mat3<Real>, kBatch> frames, edges, factors;
  std::array<Vec3<Real>, kBatch> edge_ab, edge_ac;
  std::array<std::size_t, kBatch> lane_of;
  for (Index first = begin; first < end; first += kBatch) {
    const Index count = std::min(kBatch, end - first);
    int lanes = 0;
    for (Index j = 0; j < count; ++j) {
      const auto slot = static_cast<std::size_t>(j);
      const Index t = schedule_.order[static_cast<std::size_t>(first + j)];
      const Element& element = elements_[static_cast<std::size_t>(t)];
      points[slot] = tetrahedron_points<Real>(mesh_->tetrahedron(t), x);
      if (method == TetrahedronFEMMethod::large) {
        edge_ab[slot] = points[slot][1] - points[slot][0];  // large_frame's edges
        edge_ac[slot] = points[slot][2] - points[slot][0];
        continue;
      }
      if (!polar) {
        frames[slot] = frame(element, points[slot], method);
        continue;
      }
      const Mat3<Real> a = edge_rows(points[slot]);
      if (method == TetrahedronFEMMethod::svd && (a * element.initial_transformation).determinant() < Real(1e-6)) {
        frames[slot] = frame(element, points[slot], method);  // inverted or flat: the stable SVD
        continue;
      }
      edges[static_cast<std::size_t>(lanes)] = a;
      lane_of[static_cast<std::size_t>(lanes++)] = slot;
    }
    if (method == TetrahedronFEMMethod::large) qr_frames(edge_ab.data(), edge_ac.data(), frames.data(), static_cast<int>(count));
    polar_factors(edges.data(), factors.data(), lanes);
    for (int k = 0; k < lanes; ++k) frames[lane_of[static_cast<std::size_t>(k)]] = factors[static_cast<std::size_t>(k)];
    body(first, count, points.data(), frames.data());
  }
}

template <class Real>
bool TetrahedronFEMForceField<Real>::batched() const {
  return parameters_.method != TetrahedronFEMMethod::small && !(parameters_.plastic_max_threshold > 0) &&
         !parameters_.update_stiffness_matrix;
}

template <class Real>
template <bool kLinearise>
void TetrahedronFEMForceField<Real>::accumulate_batch(Index first, Index count, const TetPoints<Real>* points,
                                                      const Mat3<Real>* frames, std::span<Vec3<Real>> f) {
  namespace kernels = tetrahedron_fem_kernels;
  constexpr int W = kernels::kLanes<Real>;
  static_assert(W >= 8, "for_each_batch's batches must fit the kernels' lanes");
  kernels::Batch<Real> b;
  for (int l = 0; l < W; ++l) {
    if (l >= count) {  // spare lanes: an element at rest with no stiffness (their results are unused)
      for (int i = 0; i < 4; ++i) {
        for (int c = 0; c < 3; ++c) b.p[i][c][l] = b.rest[i][c][l] = b.g[i][c][l] = 0;
      }
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) b.frame[r][c][l] = r == c ? 1 : 0;
        b.k[r][l] = 0;
      }
      continue;
    }
    const BatchedConstants& constants = batched_constants_[static_cast<std::size_t>(first + l)];
    for (std::size_t i = 0; i < 4; ++i) {
      for (int c = 0; c < 3; ++c) {
        b.p[i][c][l] = points[l][i][c];
        b.rest[i][c][l] = constants.rest[i][c];
        b.g[i][c][l] = constants.gradient[i][c];
      }
    }
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) b.frame[r][c][l] = frames[l](r, c);
      b.k[r][l] = constants.material[r];
    }
  }
  kernels::forces(b, parameters_.method == TetrahedronFEMMethod::large);
  for (Index l = 0; l < count; ++l) {
    const Index t = schedule_.order[static_cast<std::size_t>(first + l)];
    const Tetrahedron& tet = mesh_->tetrahedron(t);
    for (std::size_t i = 0; i < 4; ++i) {
      f[static_cast<std::size_t>(tet[i])] += Vec3<Real>(b.force[i][0][l], b.force[i][1][l], b.force[i][2][l]);
    }
    if constexpr (kLinearise) {
      elements_[static_cast<std::size_t>(t)].rotation = frames[l].transpose();
      ElementStiffness& stiffness = element_stiffness_[static_cast<std::size_t>(t)];
      for (std::size_t i = 0; i < 4; ++i) stiffness.w[i] = Vec3<Real>(b.w[i][0][l], b.w[i][1][l], b.w[i][2][l]);
      stiffness.k1 = b.k[1][l];
      stiffness.k2 = b.k[2][l];
    }
  }
}

template <class Real>
template <bool kLinearise>
void TetrahedronFEMForceField<Real>::accumulate_element(Index t, const TetPoints<Real>& p, const Mat3<Real>& frame,
                                                        std::span<Vec3<Real>> f) {
  // frame: SOFA's R_0_2, world to the element's current frame
  Element& element = elements_[static_cast<std::size_t>(t)];
  const Tetrahedron& tet = mesh_->tetrahedron(t);
  const auto d = displacement_in_frame(element, p, parameters_.method, frame);
  const Plasticity<Real> plasticity{parameters_.plastic_max_threshold, parameters_.plastic_yield_threshold,
                                    parameters_.plastic_creep};
  std::array<Vec3<Real>, 4> gradient = element.gradient;
  if (parameters_.update_stiffness_matrix && parameters_.method != TetrahedronFEMMethod::small) {
    // SOFA's updateStiffnessMatrix (polar, svd): J of the current positions in the element's frame.
    gradient = strain_gradients<Real>(frame * p[0], frame * p[1], frame * p[2], frame * p[3]);
    if constexpr (kLinearise) element.gradient = gradient;
  }
  const auto force = element_force(gradient, element.material, d, &element.plastic_strain, plasticity);
  if (parameters_.method == TetrahedronFEMMethod::small) {
    for (std::size_t i = 0; i < 4; ++i) f[static_cast<std::size_t>(tet[i])] += force[i];
    return;
  }
  const Mat3<Real> rotation = frame.transpose();
  if constexpr (kLinearise) element.rotation = rotation;
  for (std::size_t i = 0; i < 4; ++i) f[static_cast<std::size_t>(tet[i])] += rotation * force[i];
}

template <class Real>
void TetrahedronFEMForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  check_size(x, "x");
  check_size(f, "f");
  PhaseTimer timer(times_ ? &times_->add_force : nullptr);
  // Forces and each element's w in one pass over the schedule, then the blocks.
  accumulate<true>(x, f);
  assemble_blocks();
  last_positions_.assign(x.begin(), x.end());
  stale_ = false;
}

template <class Real>
void TetrahedronFEMForceField<Real>::add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  check_size(x, "x");
  check_size(f, "f");
  accumulate<false>(x, f);
}

template <class Real>
template <bool kLinearise>
void TetrahedronFEMForceField<Real>::accumulate(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  run_schedule(schedule_, threads_, [&](Index begin, Index end) {
    if (batched()) {
      for_each_batch(begin, end, x, [&](Index first, Index count, const TetPoints<Real>* p, const Mat3<Real>* frames) {
        accumulate_batch<kLinearise>(first, count, p, frames, f);
      });
      return;
    }
    for_each_element(begin, end, x, [&](Index t, const TetPoints<Real>& p, const Mat3<Real>& frame) {
      accumulate_element<kLinearise>(t, p, frame, f);
      if constexpr (kLinearise) store_element_stiffness(t);
    });
  });
}

template <class Real>
Real TetrahedronFEMForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  check_size(x, "x");
  // 1/2 D . J K J^T D per element, D as add_force forms it at x: SOFA's getPotentialEnergy for
  // small; for the others the same in the element's frame at x (SOFA returns 0 there).
  Real energy = 0;
  for (Index t = 0; t < mesh_->num_tetrahedra(); ++t) {
    const Element& element = elements_[static_cast<std::size_t>(t)];
    Mat3<Real> frame;
    const auto d = displacement(element, tetrahedron_points<Real>(mesh_->tetrahedron(t), x), parameters_.method, frame);
    const auto force = element_force(element.gradient, element.material, d);
    for (std::size_t i = 0; i < 4; ++i) energy += Real(0.5) * d[i].dot(force[i]);
  }
  return energy;
}

template <class Real>
std::vector<Mat3<Real>> TetrahedronFEMForceField<Real>::rotations() const {
  ensure_linearisation();
  std::vector<Mat3<Real>> out(elements_.size());
  for (std::size_t t = 0; t < elements_.size(); ++t) {
    out[t] = elements_[t].rotation * elements_[t].initial_rotation.transpose();
  }
  return out;
}

template <class Real>
void TetrahedronFEMForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const {
  check_rest_volumes<Real>(tetrahedra, rest_positions_, mesh_->num_tetrahedra());
}

template <class Real>
void TetrahedronFEMForceField<Real>::apply(const TopologyChange& change) {
  apply_moves(elements_, change.tetrahedron_moves);
  elements_.resize(static_cast<std::size_t>(mesh_->num_tetrahedra()));
  // New tetrahedra take entry 0 of per-tetrahedron lists (as FastTetrahedralCorotational's do):
  // their indices have no entry of their own.
  for (Index t = change.first_added_tetrahedron; t < change.first_added_tetrahedron + change.num_added_tetrahedra;
       ++t) {
    const bool young = young_per_tetrahedron_, poisson = poisson_per_tetrahedron_;
    young_per_tetrahedron_ = poisson_per_tetrahedron_ = false;
    initialise_element(t);
    young_per_tetrahedron_ = young;
    poisson_per_tetrahedron_ = poisson;
  }
  if (young_per_tetrahedron_ || poisson_per_tetrahedron_) {
    apply_moves(parameters_.young_modulus, young_per_tetrahedron_ ? change.tetrahedron_moves
                                                                 : std::span<const IndexMove>{});
    apply_moves(parameters_.poisson_ratio, poisson_per_tetrahedron_ ? change.tetrahedron_moves
                                                                   : std::span<const IndexMove>{});
    if (young_per_tetrahedron_) parameters_.young_modulus.resize(elements_.size(), parameters_.young_modulus.front());
    if (poisson_per_tetrahedron_) parameters_.poisson_ratio.resize(elements_.size(), parameters_.poisson_ratio.front());
  }
  // The schedule is made anew (its cost is that of the mesh, not of the change).
  schedule();
  stale_ = true;
  shape_derivatives_.clear();  // remade for the new tetrahedra
  if (computes_von_mises_stress()) update_von_mises_stress(last_positions_);
}

template <class Real>
std::vector<double> TetrahedronFEMForceField<Real>::model_values() const {
  std::vector<double> values(parameters_.young_modulus.begin(), parameters_.young_modulus.end());
  values.insert(values.end(), parameters_.poisson_ratio.begin(), parameters_.poisson_ratio.end());
  values.insert(values.end(), parameters_.local_stiffness_factor.begin(), parameters_.local_stiffness_factor.end());
  values.push_back(static_cast<double>(parameters_.method));
  values.push_back(static_cast<double>(parameters_.rayleigh_stiffness));
  if (parameters_.update_stiffness_matrix) values.push_back(1);
  if (parameters_.plastic_max_threshold > 0) {
    values.insert(values.end(), {static_cast<double>(parameters_.plastic_max_threshold),
                                 static_cast<double>(parameters_.plastic_yield_threshold),
                                 static_cast<double>(parameters_.plastic_creep)});
  }
  return values;
}

template <class Real>
std::size_t TetrahedronFEMForceField<Real>::memory_bytes() const {
  return elements_.capacity() * sizeof(Element) + (point_blocks_.capacity() + row_blocks_.capacity()) * sizeof(PaddedBlock) +
         edge_incidence_begin_.capacity() * sizeof(Index) + edge_incidences_.capacity() * sizeof(EdgeIncidence) +
         element_stiffness_.capacity() * sizeof(ElementStiffness) +
         edge_entries_.capacity() * sizeof(std::array<Index, 2>) + batched_constants_.capacity() * sizeof(BatchedConstants) +
         last_positions_.capacity() * sizeof(Vec3<Real>) + schedule_.order.capacity() * sizeof(Index) +
         (von_mises_element_.capacity() + von_mises_node_.capacity()) * sizeof(Real) +
         shape_derivatives_.capacity() * sizeof(Eigen::Matrix<Real, 3, 4>) +
         (row_begin_.capacity() + row_neighbour_.capacity()) * sizeof(Index);
}

template class TetrahedronFEMForceField<float>;
template class TetrahedronFEMForceField<double>;

}  // namespace fastcorot
