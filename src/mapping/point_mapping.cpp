#include "fastcorot/mapping/point_mapping.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fastcorot {

template <class Real>
void PointMapping<Real>::apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> out) const {
  if (out.size() != vertices.size()) {
    throw make_error("mapping: ", out.size(), " output points for a mapping of ", vertices.size());
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    Vec3<Real> p = Vec3<Real>::Zero();
    for (int k = 0; k < kSlots; ++k) {
      if (weights[i][static_cast<std::size_t>(k)] != 0) {
        p += x[static_cast<std::size_t>(vertices[i][static_cast<std::size_t>(k)])] * weights[i][static_cast<std::size_t>(k)];
      }
    }
    out[i] = p;
  }
}

template <class Real>
void PointMapping<Real>::apply_jt(std::span<const Vec3<Real>> forces, std::span<Vec3<Real>> parent_forces) const {
  if (forces.size() != vertices.size()) {
    throw make_error("mapping: ", forces.size(), " child forces for a mapping of ", vertices.size());
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (std::size_t k = 0; k < kSlots; ++k) {
      if (weights[i][k] != 0) parent_forces[static_cast<std::size_t>(vertices[i][k])] += forces[i] * weights[i][k];
    }
  }
}

template <class Real>
Index PointMapping<Real>::parent_extent() const {
  Index extent = 0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (std::size_t k = 0; k < kSlots; ++k) {
      if (weights[i][k] != 0) extent = std::max(extent, vertices[i][k] + 1);
    }
  }
  return extent;
}

template <class Real>
Eigen::SparseMatrix<Real, Eigen::RowMajor> PointMapping<Real>::matrix(Index parent_count) const {
  std::vector<Eigen::Triplet<Real>> entries;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (std::size_t k = 0; k < kSlots; ++k) {
      if (weights[i][k] != 0) entries.emplace_back(static_cast<Index>(i), vertices[i][k], weights[i][k]);
    }
  }
  Eigen::SparseMatrix<Real, Eigen::RowMajor> j(static_cast<Index>(vertices.size()), parent_count);
  j.setFromTriplets(entries.begin(), entries.end());
  return j;
}

template <class Real>
PointMapping<Real> PointMapping<Real>::after(const PointMapping& inner) const {
  PointMapping m;
  m.vertices.assign(vertices.size(), {});
  m.weights.assign(vertices.size(), {});
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    int used = 0;
    for (std::size_t k = 0; k < kSlots; ++k) {
      if (weights[i][k] == 0) continue;
      const auto middle = static_cast<std::size_t>(vertices[i][k]);
      if (middle >= inner.size()) throw make_error("mapping chain: point ", middle, " of a mapping of ", inner.size());
      for (std::size_t l = 0; l < kSlots; ++l) {
        const Real w = weights[i][k] * inner.weights[middle][l];
        if (inner.weights[middle][l] == 0) continue;
        const Index parent = inner.vertices[middle][l];
        int slot = 0;
        while (slot < used && m.vertices[i][static_cast<std::size_t>(slot)] != parent) ++slot;
        if (slot == used) {
          if (used == kSlots) {
            throw make_error("mapping chain: point ", i, " depends on more than ", kSlots, " points of the simulated object");
          }
          m.vertices[i][static_cast<std::size_t>(used++)] = parent;
        }
        m.weights[i][static_cast<std::size_t>(slot)] += w;
      }
    }
  }
  return m;
}

template <class Real>
PointMapping<Real> PointMapping<Real>::identity(std::size_t count) {
  std::vector<Index> all(count);
  std::iota(all.begin(), all.end(), Index{0});
  return subset(all);
}

template <class Real>
PointMapping<Real> PointMapping<Real>::subset(std::span<const Index> indices) {
  PointMapping m;
  m.vertices.assign(indices.size(), {});
  m.weights.assign(indices.size(), {});
  for (std::size_t i = 0; i < indices.size(); ++i) {
    m.vertices[i][0] = indices[i];
    m.weights[i][0] = 1;
  }
  return m;
}

template <class Real>
PointMapping<Real> PointMapping<Real>::from_barycentric(const TetMesh& mesh, const BarycentricMapping<Real>& mapping) {
  PointMapping m;
  m.vertices.assign(mapping.size(), {});
  m.weights.assign(mapping.size(), {});
  for (std::size_t i = 0; i < mapping.size(); ++i) {
    const Tetrahedron& t = mesh.tetrahedron(mapping.tetrahedron[i]);
    const Vec3<Real>& f = mapping.coordinates[i];
    const std::array<Real, 4> w = {1 - f[0] - f[1] - f[2], f[0], f[1], f[2]};
    for (std::size_t k = 0; k < 4; ++k) {
      m.vertices[i][k] = t[k];
      m.weights[i][k] = w[k];
    }
  }
  return m;
}

template <class Real>
PointMapping<Real> PointMapping<Real>::trilinear(const RegularGrid& grid, std::span<const Vec3<Real>> points) {
  validate_cells(grid);
  PointMapping m;
  m.vertices.assign(points.size(), {});
  m.weights.assign(points.size(), {});
  const Vec3<double> step = (grid.max - grid.min).cwiseQuotient(
      Vec3<double>(grid.n[0] - 1, grid.n[1] - 1, grid.n[2] - 1));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw make_error("BarycentricMapping: point ", i, " is not finite");
    // SOFA's findCube / findNearestCube: coordinates in cells from the grid's first corner.
    const Vec3<double> p = points[i].template cast<double>() - grid.origin();
    std::array<double, 3> f{};
    std::array<Index, 3> cell{};
    for (int a = 0; a < 3; ++a) {
      const double c = p[a] * step[a] / (step[a] * step[a]);
      const double lower = std::floor(c);
      const double clamped = std::min<double>(std::max<double>(lower, 0), grid.n[static_cast<std::size_t>(a)] - 2);
      cell[static_cast<std::size_t>(a)] = static_cast<Index>(clamped);
      f[static_cast<std::size_t>(a)] = c - clamped;
    }
    const auto corners = grid_cell_corners(grid, cell[0], cell[1], cell[2]);
    const double fx = f[0], fy = f[1], fz = f[2];
    // SOFA's weights per corner, in its hexahedron order.
    const std::array<double, 8> w = {(1 - fx) * (1 - fy) * (1 - fz), fx * (1 - fy) * (1 - fz), fx * fy * (1 - fz),
                                     (1 - fx) * fy * (1 - fz),       (1 - fx) * (1 - fy) * fz, fx * (1 - fy) * fz,
                                     fx * fy * fz,                   (1 - fx) * fy * fz};
    for (std::size_t k = 0; k < 8; ++k) {
      m.vertices[i][k] = corners[k];
      m.weights[i][k] = static_cast<Real>(w[k]);
    }
  }
  return m;
}

template struct PointMapping<float>;
template struct PointMapping<double>;

}  // namespace fastcorot
