#include "fastcorot/topology/generate_grid.h"

#include "fastcorot/core/error.h"

#include <limits>

namespace fastcorot {

GeneratedGrid generate_grid(const Vec3<double>& min, const Vec3<double>& max, const std::array<long long, 3>& resolution) {
  const auto [cells_x, cells_y, cells_z] = resolution;
  if (cells_x < 1 || cells_y < 1 || cells_z < 0) {
    throw make_error("resolution = ", cells_x, " ", cells_y, " ", cells_z,
                     ": needs at least 1 cell along x and y and 0 or more along z (0: a flat grid of quads)");
  }
  if (!min.allFinite() || !max.allFinite()) throw make_error("min and max must be finite");
  const double limit = static_cast<double>(std::numeric_limits<Index>::max());
  if (static_cast<double>(cells_x + 1) * static_cast<double>(cells_y + 1) * static_cast<double>(cells_z + 1) * 6 > limit) {
    throw make_error("resolution = ", cells_x, " ", cells_y, " ", cells_z, ": too many points");
  }
  const Index nx = static_cast<Index>(cells_x), ny = static_cast<Index>(cells_y), nz = static_cast<Index>(cells_z);
  // SOFA's step per axis: the size over the count, then point = index * step + min.
  const Vec3<double> size = max - min;
  const double length = size[0] / static_cast<double>(nx), width = size[1] / static_cast<double>(ny);
  const double height = nz == 0 ? 0.0 : size[2] / static_cast<double>(nz);
  GeneratedGrid out;
  out.points.reserve(static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1)));
  for (Index k = 0; k <= nz; ++k) {
    for (Index j = 0; j <= ny; ++j) {
      for (Index i = 0; i <= nx; ++i) {
        const Vec3<double> step(static_cast<double>(i) * length, static_cast<double>(j) * width,
                                static_cast<double>(k) * height);
        out.points.push_back(step + min);
      }
    }
  }
  const auto point = [&](Index i, Index j, Index k) { return i + j * (nx + 1) + k * (nx + 1) * (ny + 1); };
  if (nz == 0) {
    for (Index i = 0; i < nx; ++i) {
      for (Index j = 0; j < ny; ++j) {
        const Quad q = {point(i, j, 0), point(i + 1, j, 0), point(i + 1, j + 1, 0), point(i, j + 1, 0)};
        out.quads.push_back(q);
        out.triangles.push_back({q[0], q[1], q[3]});
        out.triangles.push_back({q[3], q[1], q[2]});
      }
    }
    return out;
  }
  for (Index i = 0; i < nx; ++i) {
    for (Index j = 0; j < ny; ++j) {
      for (Index k = 0; k < nz; ++k) {
        const Hexahedron h = {point(i, j, k),     point(i + 1, j, k),     point(i + 1, j + 1, k),     point(i, j + 1, k),
                              point(i, j, k + 1), point(i + 1, j, k + 1), point(i + 1, j + 1, k + 1), point(i, j + 1, k + 1)};
        out.hexahedra.push_back(h);
        out.tetrahedra.push_back({h[0], h[5], h[1], h[6]});
        out.tetrahedra.push_back({h[0], h[1], h[3], h[6]});
        out.tetrahedra.push_back({h[1], h[3], h[6], h[2]});
        out.tetrahedra.push_back({h[6], h[3], h[0], h[7]});
        out.tetrahedra.push_back({h[6], h[7], h[0], h[5]});
        out.tetrahedra.push_back({h[7], h[5], h[4], h[0]});
      }
    }
  }
  return out;
}

}  // namespace fastcorot
