#include "fastcorot/fem/hexahedron_fem_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/rotation.h"
#include "material_checks.h"

#include <cmath>

namespace fastcorot {

namespace {

// SOFA's _coef: the sign of each corner's local coordinate (x1, x2, x3) in [-1, 1]^3.
constexpr int kCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                               {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

// The six tetrahedra of SOFA's Hexahedron::volume.
constexpr int kTetrahedra[6][4] = {{0, 5, 1, 6}, {0, 1, 3, 6}, {1, 3, 6, 2}, {6, 3, 0, 7}, {6, 7, 0, 5}, {7, 5, 4, 0}};

template <class Real>
Real element_value(const std::vector<Real>& values, std::size_t element) {
  return values.size() > element ? values[element] : values.front();
}

// The mean x edge and mean y edge of the corners, summed in SOFA's order.
template <class Real>
std::pair<Vec3<Real>, Vec3<Real>> mean_edges(const std::array<Vec3<Real>, 8>& n) {
  const Vec3<Real> horizontal = (n[1] - n[0] + n[2] - n[3] + n[5] - n[4] + n[6] - n[7]) * Real(0.25);
  const Vec3<Real> vertical = (n[3] - n[0] + n[2] - n[1] + n[7] - n[4] + n[6] - n[5]) * Real(0.25);
  return {horizontal, vertical};
}

template <class Real>
std::array<Vec3<Real>, 8> corners(std::span<const Vec3<Real>> x, const Hexahedron& h) {
  std::array<Vec3<Real>, 8> n;
  for (int w = 0; w < 8; ++w) n[static_cast<std::size_t>(w)] = x[static_cast<std::size_t>(h[static_cast<std::size_t>(w)])];
  return n;
}

}  // namespace

HexahedronFEMMethod parse_hexahedron_fem_method(std::string_view name) {
  if (name == "large") return HexahedronFEMMethod::large;
  if (name == "polar") return HexahedronFEMMethod::polar;
  if (name == "small") return HexahedronFEMMethod::small;
  throw make_error("method \"", name, "\": expected large, polar or small");
}

template <class Real>
Real hexahedron_volume(std::span<const Vec3<Real>> points, const Hexahedron& h) {
  Real volume = 0;
  for (const auto& t : kTetrahedra) {
    const Vec3<Real>& a = points[static_cast<std::size_t>(h[static_cast<std::size_t>(t[0])])];
    const Vec3<Real> b = points[static_cast<std::size_t>(h[static_cast<std::size_t>(t[1])])] - a;
    const Vec3<Real> c = points[static_cast<std::size_t>(h[static_cast<std::size_t>(t[2])])] - a;
    const Vec3<Real> d = points[static_cast<std::size_t>(h[static_cast<std::size_t>(t[3])])] - a;
    volume += std::abs(b.cross(c).dot(d)) / Real(6);
  }
  return volume;
}

std::vector<Tetrahedron> hexahedra_tetrahedra(std::span<const Hexahedron> hexahedra) {
  std::vector<Tetrahedron> tetrahedra;
  tetrahedra.reserve(6 * hexahedra.size());
  for (const Hexahedron& h : hexahedra) {
    for (const auto& t : kTetrahedra) {
      tetrahedra.push_back({h[static_cast<std::size_t>(t[0])], h[static_cast<std::size_t>(t[1])],
                            h[static_cast<std::size_t>(t[2])], h[static_cast<std::size_t>(t[3])]});
    }
  }
  return tetrahedra;
}

template <class Real>
Eigen::Matrix<Real, 24, 24> hexahedron_element_stiffness(const std::array<Vec3<Real>, 8>& n, Real u, Real v, Real w) {
  Eigen::Matrix<Real, 24, 24> K = Eigen::Matrix<Real, 24, 24>::Zero();
  Mat3<Real> J, J_1;
  Real det_j = 1;
  const Vec3<Real> lx = n[1] - n[0], ly = n[3] - n[0], lz = n[4] - n[0];
  // A parallelepiped has one Jacobian; SOFA's test, with its tolerances.
  const bool parallel = (n[3] + lx - n[2]).norm() < lx.norm() * Real(0.001) &&
                        (n[0] + lz - n[4]).norm() < lz.norm() * Real(0.001) &&
                        (n[1] + lz - n[5]).norm() < lz.norm() * Real(0.001) &&
                        (n[2] + lz - n[6]).norm() < lz.norm() * Real(0.001) &&
                        (n[3] + lz - n[7]).norm() < lz.norm() * Real(0.001);
  const auto invert = [&] {
    det_j = J.determinant();
    if (!(det_j > 0) || !std::isfinite(det_j)) {
      throw make_error("a flat or inverted hexahedron (det J = ", det_j, "): its corners must be in SOFA's order, "
                       "the bottom face counter-clockwise seen from the top face");
    }
    J_1 = J.inverse();
  };
  if (parallel) {
    for (int c = 0; c < 3; ++c) {
      J(c, 0) = lx[c] / 2;
      J(c, 1) = ly[c] / 2;
      J(c, 2) = lz[c] / 2;
    }
    invert();
  }
  const double inv_sqrt3 = 1.0 / std::sqrt(3.0);
  for (int gx1 = -1; gx1 <= 1; gx1 += 2) {
    for (int gx2 = -1; gx2 <= 1; gx2 += 2) {
      for (int gx3 = -1; gx3 <= 1; gx3 += 2) {
        const double x1 = gx1 * inv_sqrt3, x2 = gx2 * inv_sqrt3, x3 = gx3 * inv_sqrt3;
        if (!parallel) {
          for (int c = 0; c < 3; ++c) {
            J(c, 0) = static_cast<Real>((n[1][c] - n[0][c]) * (1 - x2) * (1 - x3) / 8 + (n[2][c] - n[3][c]) * (1 + x2) * (1 - x3) / 8 +
                                        (n[5][c] - n[4][c]) * (1 - x2) * (1 + x3) / 8 + (n[6][c] - n[7][c]) * (1 + x2) * (1 + x3) / 8);
            J(c, 1) = static_cast<Real>((n[3][c] - n[0][c]) * (1 - x1) * (1 - x3) / 8 + (n[2][c] - n[1][c]) * (1 + x1) * (1 - x3) / 8 +
                                        (n[7][c] - n[4][c]) * (1 - x1) * (1 + x3) / 8 + (n[6][c] - n[5][c]) * (1 + x1) * (1 + x3) / 8);
            J(c, 2) = static_cast<Real>((n[4][c] - n[0][c]) * (1 - x1) * (1 - x2) / 8 + (n[5][c] - n[1][c]) * (1 + x1) * (1 - x2) / 8 +
                                        (n[6][c] - n[2][c]) * (1 + x1) * (1 + x2) / 8 + (n[7][c] - n[3][c]) * (1 - x1) * (1 + x2) / 8);
          }
          invert();
        }
        Real qx[8], qy[8], qz[8];
        for (int i = 0; i < 8; ++i) {
          const int* s = kCorner[i];
          const Real d1 = static_cast<Real>(s[0] * (1 + s[1] * x2) * (1 + s[2] * x3) / 8.0);
          const Real d2 = static_cast<Real>((1 + s[0] * x1) * s[1] * (1 + s[2] * x3) / 8.0);
          const Real d3 = static_cast<Real>((1 + s[0] * x1) * (1 + s[1] * x2) * s[2] / 8.0);
          qx[i] = d1 * J_1(0, 0) + d2 * J_1(1, 0) + d3 * J_1(2, 0);
          qy[i] = d1 * J_1(0, 1) + d2 * J_1(1, 1) + d3 * J_1(2, 1);
          qz[i] = d1 * J_1(0, 2) + d2 * J_1(1, 2) + d3 * J_1(2, 2);
        }
        for (int i = 0; i < 8; ++i) {
          // C B_i (6×3), then B_j^T C B_i, as SOFA writes out the non-zero products.
          Eigen::Matrix<Real, 6, 3> mb;
          mb << u * qx[i], v * qy[i], v * qz[i],  //
              v * qx[i], u * qy[i], v * qz[i],    //
              v * qx[i], v * qy[i], u * qz[i],    //
              w * qy[i], w * qx[i], Real(0),      //
              Real(0), w * qz[i], w * qy[i],      //
              w * qz[i], Real(0), w * qx[i];
          for (int j = i; j < 8; ++j) {
            Mat3<Real> k;
            k(0, 0) = qx[j] * mb(0, 0) + qy[j] * mb(3, 0) + qz[j] * mb(5, 0);
            k(0, 1) = qx[j] * mb(0, 1) + qy[j] * mb(3, 1);
            k(0, 2) = qx[j] * mb(0, 2) + qz[j] * mb(5, 2);
            k(1, 0) = qy[j] * mb(1, 0) + qx[j] * mb(3, 0);
            k(1, 1) = qy[j] * mb(1, 1) + qx[j] * mb(3, 1) + qz[j] * mb(4, 1);
            k(1, 2) = qy[j] * mb(1, 2) + qz[j] * mb(4, 2);
            k(2, 0) = qz[j] * mb(2, 0) + qx[j] * mb(5, 0);
            k(2, 1) = qz[j] * mb(2, 1) + qy[j] * mb(4, 1);
            k(2, 2) = qz[j] * mb(2, 2) + qy[j] * mb(4, 2) + qx[j] * mb(5, 2);
            k *= det_j;
            for (int m = 0; m < 3; ++m) {
              for (int l = 0; l < 3; ++l) K(i * 3 + m, j * 3 + l) += k(l, m);
            }
          }
        }
      }
    }
  }
  for (int i = 0; i < 24; ++i) {
    for (int j = i + 1; j < 24; ++j) K(j, i) = K(i, j);
  }
  return K;
}

template <class Real>
HexahedronFEMForceField<Real>::HexahedronFEMForceField(Index num_points, std::vector<Hexahedron> hexahedra,
                                                       std::span<const Vec3<Real>> rest, Parameters parameters)
    : hexahedra_(std::move(hexahedra)), parameters_(std::move(parameters)) {
  const auto count = static_cast<Index>(hexahedra_.size());
  if (count == 0) throw make_error("no hexahedra");
  if (static_cast<Index>(rest.size()) != num_points) {
    throw make_error(rest.size(), " rest positions for ", num_points, " points");
  }
  detail::check_material_lists(parameters_.young_modulus, parameters_.poisson_ratio, parameters_.rayleigh_stiffness, count);
  for (Index e = 0; e < count; ++e) {
    const Hexahedron& h = hexahedra_[static_cast<std::size_t>(e)];
    for (int a = 0; a < 8; ++a) {
      if (h[static_cast<std::size_t>(a)] < 0 || h[static_cast<std::size_t>(a)] >= num_points) {
        throw make_error("hexahedron ", e, ": point ", h[static_cast<std::size_t>(a)], " is outside [0, ", num_points, ")");
      }
      for (int b = 0; b < a; ++b) {
        if (h[static_cast<std::size_t>(a)] == h[static_cast<std::size_t>(b)]) {
          throw make_error("hexahedron ", e, ": point ", h[static_cast<std::size_t>(a)], " repeats");
        }
      }
    }
  }
  drawn_ = std::make_shared<TetMesh>(num_points, hexahedra_tetrahedra(hexahedra_));
  stiffness_.resize(hexahedra_.size());
  rest_in_frame_.resize(hexahedra_.size());
  rotation_.resize(hexahedra_.size());
  for (Index e = 0; e < count; ++e) {
    const auto i = static_cast<std::size_t>(e);
    const Real young = element_value(parameters_.young_modulus, i), nu = element_value(parameters_.poisson_ratio, i);
    if (!(young > 0) || !std::isfinite(young)) throw make_error("hexahedron ", e, ": youngModulus = ", young, ": must be > 0");
    if (!(nu > -1 && nu < Real(0.5))) throw make_error("hexahedron ", e, ": poissonRatio = ", nu, ": must be in (-1, 0.5)");
    // SOFA's computeMaterialStiffness: the unit-diagonal matrix scaled by E (1 - nu) / ((1 + nu)(1 - 2 nu)).
    const Real scale = (young * (1 - nu)) / ((1 + nu) * (1 - 2 * nu));
    const Real u = Real(1) * scale, v = (nu / (1 - nu)) * scale, w = ((1 - 2 * nu) / (2 * (1 - nu))) * scale;
    const std::array<Vec3<Real>, 8> nodes = corners(rest, hexahedra_[i]);
    rotation_[i] = element_rotation(rest, hexahedra_[i]);
    for (int k = 0; k < 8; ++k) rest_in_frame_[i][static_cast<std::size_t>(k)] = rotation_[i] * nodes[static_cast<std::size_t>(k)];
    try {
      stiffness_[i] = hexahedron_element_stiffness<Real>(rest_in_frame_[i], u, v, w);
    } catch (const Error& error) {
      throw make_error("hexahedron ", e, ": ", error.what());
    }
  }
}

template <class Real>
std::string HexahedronFEMForceField<Real>::method_name() const {
  switch (parameters_.method) {
    case HexahedronFEMMethod::small:
      return "small";
    case HexahedronFEMMethod::polar:
      return "polar";
    case HexahedronFEMMethod::large:
      break;
  }
  return "large";
}

template <class Real>
Mat3<Real> HexahedronFEMForceField<Real>::element_rotation(std::span<const Vec3<Real>> x, const Hexahedron& h) const {
  const std::array<Vec3<Real>, 8> n = corners(x, h);
  switch (parameters_.method) {
    case HexahedronFEMMethod::small:
      return Mat3<Real>::Identity();
    case HexahedronFEMMethod::large: {
      const auto [horizontal, vertical] = mean_edges(n);
      return qr_frame<Real>(horizontal, vertical);
    }
    case HexahedronFEMMethod::polar: {
      const auto [horizontal, vertical] = mean_edges(n);
      const Vec3<Real> depth = (n[4] - n[0] + n[5] - n[1] + n[7] - n[3] + n[6] - n[2]) * Real(0.25);
      return polar_frame<Real>(horizontal, vertical, depth);
    }
  }
  return Mat3<Real>::Identity();
}

template <class Real>
Mat3<Real> HexahedronFEMForceField<Real>::current_rotation(std::span<const Vec3<Real>> x, std::size_t e) const {
  return parameters_.method == HexahedronFEMMethod::small ? rotation_[e] : element_rotation(x, hexahedra_[e]);
}

template <class Real>
Eigen::Matrix<Real, 24, 1> HexahedronFEMForceField<Real>::displacement(std::span<const Vec3<Real>> x, std::size_t e,
                                                                      const Mat3<Real>& R) const {
  Eigen::Matrix<Real, 24, 1> D;
  for (int k = 0; k < 8; ++k) {
    const Vec3<Real> deformed = R * x[static_cast<std::size_t>(hexahedra_[e][static_cast<std::size_t>(k)])];
    D.template segment<3>(3 * k) = rest_in_frame_[e][static_cast<std::size_t>(k)] - deformed;
  }
  return D;
}

template <class Real>
void HexahedronFEMForceField<Real>::forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record) {
  for (std::size_t e = 0; e < hexahedra_.size(); ++e) {
    const Hexahedron& h = hexahedra_[e];
    const Mat3<Real> R = current_rotation(x, e);
    const Eigen::Matrix<Real, 24, 1> F = stiffness_[e] * displacement(x, e, R);
    for (int k = 0; k < 8; ++k) {
      f[static_cast<std::size_t>(h[static_cast<std::size_t>(k)])] += R.transpose() * F.template segment<3>(3 * k);
    }
    if (record) rotation_[e] = R;
  }
}

template <class Real>
void HexahedronFEMForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  forces(x, f, true);
}

template <class Real>
void HexahedronFEMForceField<Real>::add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  forces(x, f, false);
}

template <class Real>
void HexahedronFEMForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                                               Real b_factor) const {
  const Real kf = factor(k_factor, b_factor);
  for (std::size_t e = 0; e < hexahedra_.size(); ++e) {
    const Hexahedron& h = hexahedra_[e];
    const Mat3<Real>& R = rotation_[e];
    Eigen::Matrix<Real, 24, 1> X;
    for (int k = 0; k < 8; ++k) X.template segment<3>(3 * k) = R * dx[static_cast<std::size_t>(h[static_cast<std::size_t>(k)])];
    const Eigen::Matrix<Real, 24, 1> F = stiffness_[e] * X;
    for (int k = 0; k < 8; ++k) {
      df[static_cast<std::size_t>(h[static_cast<std::size_t>(k)])] -= (R.transpose() * F.template segment<3>(3 * k)) * kf;
    }
  }
}

template <class Real>
void HexahedronFEMForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset, Real b_factor) const {
  const Real kf = factor(k_factor, b_factor);
  for (std::size_t e = 0; e < hexahedra_.size(); ++e) {
    const Hexahedron& h = hexahedra_[e];
    const Mat3<Real>& R = rotation_[e];
    for (int a = 0; a < 8; ++a) {
      for (int b = 0; b < 8; ++b) {
        const Mat3<Real> block = R.transpose() * stiffness_[e].template block<3, 3>(3 * a, 3 * b) * R;
        sink.add_block(offset + 3 * h[static_cast<std::size_t>(a)], offset + 3 * h[static_cast<std::size_t>(b)], block * (-kf));
      }
    }
  }
}

template <class Real>
void HexahedronFEMForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor) const {
  const Real kf = factor(k_factor, b_factor);
  for (std::size_t e = 0; e < hexahedra_.size(); ++e) {
    const Hexahedron& h = hexahedra_[e];
    const Mat3<Real>& R = rotation_[e];
    for (int a = 0; a < 8; ++a) {
      const Mat3<Real> block = R.transpose() * stiffness_[e].template block<3, 3>(3 * a, 3 * a) * R;
      diagonal[static_cast<std::size_t>(h[static_cast<std::size_t>(a)])] += block * (-kf);
    }
  }
}

template <class Real>
Real HexahedronFEMForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  Real energy = 0;
  for (std::size_t e = 0; e < hexahedra_.size(); ++e) {
    const Eigen::Matrix<Real, 24, 1> D = displacement(x, e, current_rotation(x, e));
    energy += D.dot(stiffness_[e] * D);
  }
  return energy / 2;
}

template <class Real>
std::vector<Mat3<Real>> HexahedronFEMForceField<Real>::rotations() const {
  std::vector<Mat3<Real>> out;
  out.reserve(6 * rotation_.size());
  for (const Mat3<Real>& R : rotation_) {
    for (int t = 0; t < 6; ++t) out.push_back(R.transpose());
  }
  return out;
}

template <class Real>
void HexahedronFEMForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron>) const {
  throw make_error("HexahedronFEMForceField: its hexahedra cannot change (cutting and added tetrahedra are for "
                   "tetrahedral force fields)");
}

template <class Real>
void HexahedronFEMForceField<Real>::apply(const TopologyChange&) {
  throw make_error("HexahedronFEMForceField: its hexahedra cannot change (cutting is for tetrahedral force fields)");
}

template <class Real>
std::vector<double> HexahedronFEMForceField<Real>::model_values() const {
  std::vector<double> values{static_cast<double>(parameters_.method), static_cast<double>(parameters_.rayleigh_stiffness)};
  for (Real v : parameters_.young_modulus) values.push_back(static_cast<double>(v));
  for (Real v : parameters_.poisson_ratio) values.push_back(static_cast<double>(v));
  return values;
}

template <class Real>
std::size_t HexahedronFEMForceField<Real>::memory_bytes() const {
  return hexahedra_.size() * (sizeof(ElementStiffness) + sizeof(Mat3<Real>) + 8 * sizeof(Vec3<Real>) + sizeof(Hexahedron));
}

template class HexahedronFEMForceField<float>;
template class HexahedronFEMForceField<double>;
template float hexahedron_volume(std::span<const Vec3<float>>, const Hexahedron&);
template double hexahedron_volume(std::span<const Vec3<double>>, const Hexahedron&);
template Eigen::Matrix<float, 24, 24> hexahedron_element_stiffness(const std::array<Vec3<float>, 8>&, float, float, float);
template Eigen::Matrix<double, 24, 24> hexahedron_element_stiffness(const std::array<Vec3<double>, 8>&, double, double, double);

}  // namespace fastcorot
