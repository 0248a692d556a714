#include "fastcorot/sim/hexahedron_fem_mass.h"

#include "fastcorot/core/error.h"

#include <Eigen/SparseCore>

#include <cmath>

namespace fastcorot {

namespace {

// The signs of each corner of SOFA's hexahedron (its _coef table): corners 0-3 at z = -1 (counter-
// clockwise from (-1, -1)), 4-7 above them at z = +1.
constexpr int kCornerSigns[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

// |n1 - n0| |n3 - n0| |n4 - n0|: SOFA's element volume for masses (exact for a box).
template <class Real>
Real box_volume(const Vec3<Real>& n0, const Vec3<Real>& n1, const Vec3<Real>& n3, const Vec3<Real>& n4) {
  return (n1 - n0).norm() * (n3 - n0).norm() * (n4 - n0).norm();
}

}  // namespace

template <class Real>
Real hexahedron_mass_integral(int sx, int sy, int sz) {
  // The terms in SOFA's order (the sum's rounding is SOFA's).
  const auto x2 = static_cast<Real>(sx * sx), y2 = static_cast<Real>(sy * sy), z2 = static_cast<Real>(sz * sz);
  const Real xy2 = x2 * y2;
  return x2 * z2 / Real(72) + y2 * z2 / Real(72) + xy2 * z2 / Real(216) + z2 / Real(24) + Real(1) / Real(8) +
         xy2 / Real(72) + x2 / Real(24) + y2 / Real(24);
}

template <class Real>
Mass<Real> hexahedron_fem_mass(const HexahedronFEMForceField<Real>& field, std::span<const Vec3<Real>> rest, Real density,
                               bool lumped) {
  if (!(density > 0) || !std::isfinite(density)) {
    throw make_error("HexahedronFEMForceFieldAndMass: density = ", density, ": must be finite and > 0");
  }
  const auto n = static_cast<std::size_t>(field.mesh().num_points());
  if (rest.size() != n) throw make_error("HexahedronFEMForceFieldAndMass: ", rest.size(), " rest positions for ", n, " points");
  const auto hexahedra = field.hexahedra();
  std::vector<Real> weights(n, Real(0)), row_sums(n, Real(0));
  std::vector<Eigen::Triplet<Real>> entries;
  if (!lumped) entries.reserve(64 * hexahedra.size());
  for (std::size_t e = 0; e < hexahedra.size(); ++e) {
    const Hexahedron& h = hexahedra[e];
    const auto corner = [&](int k) { return rest[static_cast<std::size_t>(h[static_cast<std::size_t>(k)])]; };
    const Real weight = box_volume(corner(0), corner(1), corner(3), corner(4)) * density / Real(8);
    const auto& frame = field.rest_in_frame(static_cast<Index>(e));
    const Real volume = box_volume(frame[0], frame[1], frame[3], frame[4]);
    for (int i = 0; i < 8; ++i) {
      const Index a = h[static_cast<std::size_t>(i)];
      weights[static_cast<std::size_t>(a)] += weight;
      const Real m = volume * (hexahedron_mass_integral<Real>(kCornerSigns[i][0], kCornerSigns[i][1], kCornerSigns[i][2]) * density);
      // Row i holds m at every corner j >= i; the rows j < i take theirs by symmetry (m of corner j).
      for (int j = 0; j < 8; ++j) {
        const Index b = h[static_cast<std::size_t>(j)];
        if (j < i) continue;
        if (lumped) {
          row_sums[static_cast<std::size_t>(a)] += m;
          if (j != i) row_sums[static_cast<std::size_t>(b)] += m;
        } else {
          entries.emplace_back(a, b, m);
          if (j != i) entries.emplace_back(b, a, m);
        }
      }
    }
  }
  Mass<Real> mass;
  if (lumped) {
    mass = Mass<Real>::lumped(std::move(row_sums));
  } else {
    Eigen::SparseMatrix<Real> matrix(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    matrix.setFromTriplets(entries.begin(), entries.end());
    mass = Mass<Real>::consistent(std::move(matrix));
  }
  mass.set_gravity_masses(std::move(weights));
  return mass;
}

template float hexahedron_mass_integral<float>(int, int, int);
template double hexahedron_mass_integral<double>(int, int, int);
template Mass<double> hexahedron_fem_mass(const HexahedronFEMForceField<double>&, std::span<const Vec3<double>>, double, bool);
template Mass<float> hexahedron_fem_mass(const HexahedronFEMForceField<float>&, std::span<const Vec3<float>>, float, bool);

}  // namespace fastcorot
