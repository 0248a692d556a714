#include "fastcorot/fem/element_fem_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/lame.h"
#include "fastcorot/core/parallel.h"
#include "fastcorot/core/rotation.h"
#include "fastcorot/fem/finite_element.h"

#include <cmath>

namespace fastcorot {

namespace {

template <class Real, int N>
std::array<Vec3<Real>, N> corners(std::span<const Vec3<Real>> x, const std::array<Index, N>& element) {
  std::array<Vec3<Real>, N> c;
  for (int j = 0; j < N; ++j) c[static_cast<std::size_t>(j)] = x[static_cast<std::size_t>(element[static_cast<std::size_t>(j)])];
  return c;
}

// SOFA's computeCentroid: the corners summed in order, divided by N.
template <class Real, int N>
Vec3<Real> centroid(const std::array<Vec3<Real>, N>& c) {
  Vec3<Real> sum = Vec3<Real>::Zero();
  for (const auto& p : c) sum += p;
  return sum / static_cast<Real>(N);
}

template <class Real>
Real element_value(const std::vector<Real>& values, std::size_t element) {
  return values.size() > element ? values[element] : values.front();
}

const char* element_name(int nodes) { return nodes == 4 ? "tetrahedron" : "hexahedron"; }

}  // namespace

ElementRotationMethod parse_element_rotation_method(std::string_view name, int nodes_per_element) {
  const std::string_view own = nodes_per_element == 4 ? "triangle" : "hexahedron";
  if (name == "stable_polar") return ElementRotationMethod::stable_polar;
  if (name == "polar") return ElementRotationMethod::polar;
  if (name == "identity") return ElementRotationMethod::identity;
  if (name == own) return nodes_per_element == 4 ? ElementRotationMethod::triangle : ElementRotationMethod::hexahedron;
  throw make_error("rotationMethod \"", name, "\": expected stable_polar, polar, identity or ", own);
}

std::string to_string(ElementRotationMethod method) {
  switch (method) {
    case ElementRotationMethod::none: return "none";
    case ElementRotationMethod::identity: return "identity";
    case ElementRotationMethod::triangle: return "triangle";
    case ElementRotationMethod::hexahedron: return "hexahedron";
    case ElementRotationMethod::polar: return "polar";
    case ElementRotationMethod::stable_polar: return "stable_polar";
  }
  return "none";
}

template <class Real, int N>
Mat3<Real> element_frame(const std::array<Vec3<Real>, N>& n) {
  if constexpr (N == 4) {
    return qr_frame<Real>(n[1] - n[0], n[2] - n[0]);
  } else {
    const Vec3<Real> x_axis = (n[1] - n[0] + n[2] - n[3] + n[5] - n[4] + n[6] - n[7]) * Real(0.25);
    const Vec3<Real> y_axis = (n[3] - n[0] + n[2] - n[1] + n[7] - n[4] + n[6] - n[5]) * Real(0.25);
    return qr_frame<Real>(x_axis, y_axis);
  }
}

template <class Real, int N>
ElementFEMForceField<Real, N>::ElementFEMForceField(std::shared_ptr<TetMesh> drawn, std::vector<Element> elements,
                                                    std::span<const Vec3<Real>> rest, Parameters parameters)
    : drawn_(std::move(drawn)), elements_(std::move(elements)), rest_(rest.begin(), rest.end()),
      parameters_(std::move(parameters)) {
  const auto count = elements_.size();
  const auto n = static_cast<Index>(rest_.size());
  const auto check_list = [&](const std::vector<Real>& values, const char* name) {
    if (values.size() != 1 && values.size() != count) {
      throw make_error(name, ": ", values.size(), " values given; expected 1 or one per ", element_name(N), " (", count, ")");
    }
  };
  check_list(parameters_.young_modulus, "youngModulus");
  check_list(parameters_.poisson_ratio, "poissonRatio");
  if (!(parameters_.rayleigh_stiffness >= 0) || !std::isfinite(parameters_.rayleigh_stiffness)) {
    throw make_error("rayleighStiffness = ", parameters_.rayleigh_stiffness, ": must be a finite value >= 0");
  }
  if (parameters_.method == ElementRotationMethod::triangle && N != 4) throw make_error("rotationMethod triangle is for tetrahedra");
  if (parameters_.method == ElementRotationMethod::hexahedron && N != 8) throw make_error("rotationMethod hexahedron is for hexahedra");
  stiffness_.resize(count);
  rest_frame_.assign(count, Mat3<Real>::Identity());
  rotation_.assign(count, Mat3<Real>::Identity());
  element_terms_.assign(count, ElementVector::Zero());
  for (std::size_t e = 0; e < count; ++e) {
    for (Index p : elements_[e]) {
      if (p < 0 || p >= n) throw make_error(element_name(N), " ", e, ": point ", p, " outside [0, ", n, ")");
    }
    try {
      const Real young = element_value(parameters_.young_modulus, e), nu = element_value(parameters_.poisson_ratio, e);
      const LameParameters<Real> lame = lame_parameters(young, nu);
      const auto c = corners<Real, N>(rest_, elements_[e]);
      stiffness_[e] = fastcorot::element_stiffness<Real, N>(c, lame.mu, lame.lambda);
      if (parameters_.method == ElementRotationMethod::triangle || parameters_.method == ElementRotationMethod::hexahedron) {
        rest_frame_[e] = element_frame<Real, N>(c);
        if (!rest_frame_[e].allFinite()) throw make_error("its rest frame is undefined (corners coincide)");
      }
    } catch (const Error& error) {
      throw make_error(element_name(N), " ", e, ": ", error.what());
    }
  }
}

template <class Real, int N>
std::string ElementFEMForceField<Real, N>::component() const {
  return parameters_.method == ElementRotationMethod::none ? "LinearSmallStrainFEMForceField" : "CorotationalFEMForceField";
}

template <class Real, int N>
Mat3<Real> ElementFEMForceField<Real, N>::element_rotation(std::span<const Vec3<Real>> x, std::size_t e) const {
  const auto c = corners<Real, N>(x, elements_[e]);
  switch (parameters_.method) {
    case ElementRotationMethod::none:
    case ElementRotationMethod::identity:
      return Mat3<Real>::Identity();
    case ElementRotationMethod::triangle:
    case ElementRotationMethod::hexahedron:
      return element_frame<Real, N>(c).transpose() * rest_frame_[e];
    case ElementRotationMethod::polar:
    case ElementRotationMethod::stable_polar: {
      const auto c0 = corners<Real, N>(rest_, elements_[e]);
      const Vec3<Real> t = centroid<Real, N>(c), t0 = centroid<Real, N>(c0);
      Mat3<Real> H = Mat3<Real>::Zero();
      for (int j = 0; j < N; ++j) H += (c[static_cast<std::size_t>(j)] - t) * (c0[static_cast<std::size_t>(j)] - t0).transpose();
      return parameters_.method == ElementRotationMethod::polar ? polar_factor<Real>(H) : stable_polar_factor<Real>(H);
    }
  }
  return Mat3<Real>::Identity();
}

template <class Real, int N>
auto ElementFEMForceField<Real, N>::element_force(std::span<const Vec3<Real>> x, std::size_t e, const Mat3<Real>& R) const
    -> ElementVector {
  const auto c = corners<Real, N>(x, elements_[e]);
  const auto c0 = corners<Real, N>(rest_, elements_[e]);
  ElementVector d;
  if (parameters_.method == ElementRotationMethod::none) {
    for (int j = 0; j < N; ++j) d.template segment<3>(3 * j) = c[static_cast<std::size_t>(j)] - c0[static_cast<std::size_t>(j)];
    return stiffness_[e] * d;
  }
  const Vec3<Real> t = centroid<Real, N>(c), t0 = centroid<Real, N>(c0);
  for (int j = 0; j < N; ++j) {
    d.template segment<3>(3 * j) = R.transpose() * (c[static_cast<std::size_t>(j)] - t) - (c0[static_cast<std::size_t>(j)] - t0);
  }
  ElementVector f = stiffness_[e] * d;
  for (int j = 0; j < N; ++j) f.template segment<3>(3 * j) = R * f.template segment<3>(3 * j);
  return f;
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record) {
  parallel_ranges(threads_, elements_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t e = begin; e < end; ++e) {
      const Mat3<Real> R = element_rotation(x, e);
      if (record) rotation_[e] = R;
      element_terms_[e] = element_force(x, e, R);
    }
  });
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    for (int j = 0; j < N; ++j) {
      f[static_cast<std::size_t>(elements_[e][static_cast<std::size_t>(j)])] -= element_terms_[e].template segment<3>(3 * j);
    }
  }
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  forces(x, f, true);
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  forces(x, f, false);
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                                               Real b_factor) const {
  const bool rotated = parameters_.method != ElementRotationMethod::none;
  parallel_ranges(threads_, elements_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t e = begin; e < end; ++e) {
      const Mat3<Real>& R = rotation_[e];
      ElementVector local;
      for (int j = 0; j < N; ++j) {
        const Vec3<Real>& v = dx[static_cast<std::size_t>(elements_[e][static_cast<std::size_t>(j)])];
        local.template segment<3>(3 * j) = rotated ? Vec3<Real>(R.transpose() * v) : v;
      }
      ElementVector term = stiffness_[e] * local;
      if (rotated) {
        for (int j = 0; j < N; ++j) term.template segment<3>(3 * j) = R * term.template segment<3>(3 * j);
      }
      element_terms_[e] = term;
    }
  });
  const Real k = factor(k_factor, b_factor);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    for (int j = 0; j < N; ++j) {
      df[static_cast<std::size_t>(elements_[e][static_cast<std::size_t>(j)])] -= k * element_terms_[e].template segment<3>(3 * j);
    }
  }
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Mat3<Real>& R = rotation_[e];
    for (int a = 0; a < N; ++a) {
      for (int b = 0; b < N; ++b) {
        const Mat3<Real> block = stiffness_[e].template block<3, 3>(3 * a, 3 * b);
        const Mat3<Real> world = parameters_.method == ElementRotationMethod::none ? block : Mat3<Real>(R * block * R.transpose());
        sink.add_block(offset + 3 * elements_[e][static_cast<std::size_t>(a)], offset + 3 * elements_[e][static_cast<std::size_t>(b)],
                       -k * world);
      }
    }
  }
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor) const {
  const Real k = factor(k_factor, b_factor);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Mat3<Real>& R = rotation_[e];
    for (int a = 0; a < N; ++a) {
      const Mat3<Real> block = stiffness_[e].template block<3, 3>(3 * a, 3 * a);
      const Mat3<Real> world = parameters_.method == ElementRotationMethod::none ? block : Mat3<Real>(R * block * R.transpose());
      diagonal[static_cast<std::size_t>(elements_[e][static_cast<std::size_t>(a)])] -= k * world;
    }
  }
}

template <class Real, int N>
Real ElementFEMForceField<Real, N>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Mat3<Real> R = element_rotation(x, e);
    const auto c = corners<Real, N>(x, elements_[e]);
    const auto c0 = corners<Real, N>(rest_, elements_[e]);
    ElementVector d;
    const Vec3<Real> t = centroid<Real, N>(c), t0 = centroid<Real, N>(c0);
    for (int j = 0; j < N; ++j) {
      d.template segment<3>(3 * j) = R.transpose() * (c[static_cast<std::size_t>(j)] - t) - (c0[static_cast<std::size_t>(j)] - t0);
    }
    energy += Real(0.5) * d.dot(stiffness_[e] * d);
  }
  return energy;
}

template <class Real, int N>
std::vector<Mat3<Real>> ElementFEMForceField<Real, N>::rotations() const {
  if constexpr (N == 4) return rotation_;
  std::vector<Mat3<Real>> out;
  out.reserve(6 * rotation_.size());
  for (const Mat3<Real>& R : rotation_) {
    for (int t = 0; t < 6; ++t) out.push_back(R);
  }
  return out;
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::check_new_tetrahedra(std::span<const Tetrahedron>) const {
  throw make_error(component(), ": its elements cannot change (cutting and added tetrahedra are for "
                   "FastTetrahedralCorotationalForceField and TetrahedronFEMForceField)");
}

template <class Real, int N>
void ElementFEMForceField<Real, N>::apply(const TopologyChange&) {
  throw make_error(component(), ": its elements cannot change (topological changes are not supported)");
}

template <class Real, int N>
std::vector<double> ElementFEMForceField<Real, N>::model_values() const {
  std::vector<double> values{static_cast<double>(N), static_cast<double>(parameters_.method),
                             static_cast<double>(parameters_.rayleigh_stiffness)};
  for (Real v : parameters_.young_modulus) values.push_back(static_cast<double>(v));
  for (Real v : parameters_.poisson_ratio) values.push_back(static_cast<double>(v));
  return values;
}

template <class Real, int N>
std::size_t ElementFEMForceField<Real, N>::memory_bytes() const {
  return elements_.size() * (sizeof(ElementStiffness) + 2 * sizeof(Mat3<Real>) + sizeof(ElementVector) + sizeof(Element));
}

template class ElementFEMForceField<float, 4>;
template class ElementFEMForceField<float, 8>;
template class ElementFEMForceField<double, 4>;
template class ElementFEMForceField<double, 8>;
template Mat3<float> element_frame<float, 4>(const std::array<Vec3<float>, 4>&);
template Mat3<float> element_frame<float, 8>(const std::array<Vec3<float>, 8>&);
template Mat3<double> element_frame<double, 4>(const std::array<Vec3<double>, 4>&);
template Mat3<double> element_frame<double, 8>(const std::array<Vec3<double>, 8>&);

}  // namespace fastcorot
