#include "fastcorot/mapping/barycentric_mapping.h"

#include "fastcorot/core/error.h"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace fastcorot {

template <class Real>
void BarycentricMapping<Real>::apply(const TetMesh& mesh, std::span<const Vec3<Real>> x,
                                     std::span<Vec3<Real>> out) const {
  if (out.size() != tetrahedron.size()) {
    throw make_error("BarycentricMapping: ", out.size(), " output points for a mapping of ", tetrahedron.size());
  }
  for (std::size_t i = 0; i < tetrahedron.size(); ++i) {
    const Tetrahedron& t = mesh.tetrahedron(tetrahedron[i]);
    const Vec3<Real>& f = coordinates[i];
    const Real w[4] = {1 - f[0] - f[1] - f[2], f[0], f[1], f[2]};
    Vec3<Real> p = Vec3<Real>::Zero();
    for (std::size_t j = 0; j < 4; ++j) p += x[static_cast<std::size_t>(t[j])] * w[j];
    out[i] = p;
  }
}

namespace {

using Cell = std::array<int, 3>;

template <class Real>
Cell cell_of(const Vec3<Real>& p, Real inverse_size) {
  return {static_cast<int>(std::floor(p[0] * inverse_size)), static_cast<int>(std::floor(p[1] * inverse_size)),
          static_cast<int>(std::floor(p[2] * inverse_size))};
}

// SOFA's 3x3 inverse (type/Mat.h invertMatrix: its determinant's six products, each cofactor
// divided by it) and matrix-vector product (row by row, left to right), so that the barycentric
// coordinates, and the mapped points, are SOFA's to the bit (Eigen's inverse multiplies by the
// determinant's reciprocal: last-bit differences, which decide exact ties downstream, e.g. which
// of two mirror contacts with one id a penalty keeps).
template <class Real>
Mat3<Real> sofa_inverse(const Mat3<Real>& m) {
  const Real det = m(0, 0) * m(1, 1) * m(2, 2) + m(1, 0) * m(2, 1) * m(0, 2) + m(2, 0) * m(0, 1) * m(1, 2) -
                   m(0, 0) * m(2, 1) * m(1, 2) - m(1, 0) * m(0, 1) * m(2, 2) - m(2, 0) * m(1, 1) * m(0, 2);
  Mat3<Real> r;
  r(0, 0) = (m(1, 1) * m(2, 2) - m(2, 1) * m(1, 2)) / det;
  r(1, 0) = (m(1, 2) * m(2, 0) - m(2, 2) * m(1, 0)) / det;
  r(2, 0) = (m(1, 0) * m(2, 1) - m(2, 0) * m(1, 1)) / det;
  r(0, 1) = (m(2, 1) * m(0, 2) - m(0, 1) * m(2, 2)) / det;
  r(1, 1) = (m(2, 2) * m(0, 0) - m(0, 2) * m(2, 0)) / det;
  r(2, 1) = (m(2, 0) * m(0, 1) - m(0, 0) * m(2, 1)) / det;
  r(0, 2) = (m(0, 1) * m(1, 2) - m(1, 1) * m(0, 2)) / det;
  r(1, 2) = (m(0, 2) * m(1, 0) - m(1, 2) * m(0, 0)) / det;
  r(2, 2) = (m(0, 0) * m(1, 1) - m(1, 0) * m(0, 1)) / det;
  return r;
}

template <class Real>
Vec3<Real> sofa_product(const Mat3<Real>& m, const Vec3<Real>& v) {
  Vec3<Real> r;
  for (int i = 0; i < 3; ++i) r[i] = m(i, 0) * v[0] + m(i, 1) * v[1] + m(i, 2) * v[2];
  return r;
}

template <class Real>
struct Nearest {
  Vec3<Real> coordinates = Vec3<Real>::Zero();
  Real distance = std::numeric_limits<Real>::max();
  Index tetrahedron = -1;
};

}  // namespace

template <class Real>
BarycentricMapping<Real> map_onto_tetrahedra(const TetMesh& mesh, std::span<const Vec3<Real>> x,
                                             std::span<const Vec3<Real>> points, TetrahedronSearch search) {
  if (mesh.num_tetrahedra() == 0) throw make_error("BarycentricMapping: the input topology has no tetrahedra");
  const auto n = static_cast<std::size_t>(mesh.num_tetrahedra());
  // Per tetrahedron the inverse of its edge matrix (columns b - a, c - a, d - a) and its centre.
  std::vector<Mat3<Real>> bases(n);
  std::vector<Vec3<Real>> centres(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto p = tetrahedron_points<Real>(mesh.tetrahedron(static_cast<Index>(t)), x);
    Mat3<Real> edges;
    for (int k = 0; k < 3; ++k) edges.col(k) = p[static_cast<std::size_t>(k) + 1] - p[0];
    bases[t] = sofa_inverse(edges);
    centres[t] = (p[0] + p[1] + p[2] + p[3]) * Real(0.25);
  }
  // The grid: cells of the mean edge length, each listing the tetrahedra whose boxes meet it.
  Real length = 0;
  for (const Edge& e : mesh.edges()) length += (x[static_cast<std::size_t>(e[0])] - x[static_cast<std::size_t>(e[1])]).norm();
  const Real cell_size = length / static_cast<Real>(mesh.num_edges());
  const Real inverse_size = 1 / cell_size;
  std::map<Cell, std::vector<Index>> grid;
  for (std::size_t t = 0; t < n; ++t) {
    const auto p = tetrahedron_points<Real>(mesh.tetrahedron(static_cast<Index>(t)), x);
    Vec3<Real> low = p[0], high = p[0];
    for (const auto& q : p) {
      low = low.cwiseMin(q);
      high = high.cwiseMax(q);
    }
    const Cell a = cell_of(low, inverse_size), b = cell_of(high, inverse_size);
    for (int i = a[0]; i <= b[0]; ++i) {
      for (int j = a[1]; j <= b[1]; ++j) {
        for (int k = a[2]; k <= b[2]; ++k) grid[{i, j, k}].push_back(static_cast<Index>(t));
      }
    }
  }
  const auto check = [&](Index t, const Vec3<Real>& point, Nearest<Real>& nearest) {
    const auto ti = static_cast<std::size_t>(t);
    const Vec3<Real> f = sofa_product(bases[ti], Vec3<Real>(point - x[static_cast<std::size_t>(mesh.tetrahedron(t)[0])]));
    // <= 0 inside (the smaller, the deeper), > 0 outside, where the centre's distance decides.
    Real distance = std::max(std::max(-f[0], -f[1]), std::max(-f[2], f[0] + f[1] + f[2] - 1));
    if (distance > 0) {
      const Vec3<Real> d = point - centres[ti];
      distance = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    }
    if (distance < nearest.distance) nearest = {f, distance, t};
  };
  BarycentricMapping<Real> mapping;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3<Real>& point = points[i];
    if (!point.allFinite()) throw make_error("BarycentricMapping: point ", i, " is not finite");
    Nearest<Real> nearest;
    if (search == TetrahedronSearch::exhaustive) {
      for (std::size_t t = 0; t < n; ++t) check(static_cast<Index>(t), point, nearest);
      mapping.tetrahedron.push_back(nearest.tetrahedron);
      mapping.coordinates.push_back(nearest.coordinates);
      continue;
    }
    const Cell cell = cell_of(point, inverse_size);
    if (const auto it = grid.find(cell); it != grid.end()) {
      for (Index t : it->second) check(t, point, nearest);
    }
    if (nearest.tetrahedron < 0) {
      for (std::size_t t = 0; t < n; ++t) check(static_cast<Index>(t), point, nearest);  // an empty cell
    } else if (std::abs(nearest.distance) > cell_size / 2) {
      // (SOFA compares the squared distance of a centre with half a cell's length; kept.)
      for (int a = -1; a <= 1; ++a) {
        for (int b = -1; b <= 1; ++b) {
          for (int c = -1; c <= 1; ++c) {
            if (const auto it = grid.find({cell[0] + a, cell[1] + b, cell[2] + c}); it != grid.end()) {
              for (Index t : it->second) check(t, point, nearest);
            }
          }
        }
      }
    }
    mapping.tetrahedron.push_back(nearest.tetrahedron);
    mapping.coordinates.push_back(nearest.coordinates);
  }
  return mapping;
}

template struct BarycentricMapping<float>;
template struct BarycentricMapping<double>;
template BarycentricMapping<float> map_onto_tetrahedra(const TetMesh&, std::span<const Vec3<float>>,
                                                       std::span<const Vec3<float>>, TetrahedronSearch);
template BarycentricMapping<double> map_onto_tetrahedra(const TetMesh&, std::span<const Vec3<double>>,
                                                        std::span<const Vec3<double>>, TetrahedronSearch);

}  // namespace fastcorot
