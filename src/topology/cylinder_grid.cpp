#include "fastcorot/topology/cylinder_grid.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>

namespace fastcorot {

std::array<Vec3<double>, 3> grid_axes(const Vec3<double>& axis) {
  Vec3<double> z = axis.normalized();
  Vec3<double> x = (z - Vec3<double>(1, 0, 0)).norm() < 0.000001 ? Vec3<double>(0, 1, 0) : Vec3<double>(1, 0, 0);
  Vec3<double> y = z.cross(x);
  x = y.cross(z);
  x.normalize();
  y.normalize();
  z.normalize();  // again, as SOFA does (it can change the last bits)
  return {x, y, z};
}

std::vector<Vec3<double>> cylinder_grid_points(const CylinderGrid& grid) {
  const auto [nx, ny, nz] = grid.n;
  if (nx < 2 || ny < 2 || nz < 1) {
    throw make_error("CylinderGridTopology: n = ", nx, " ", ny, " ", nz, ": needs at least 2 points across and 1 along the axis");
  }
  if (!grid.axis.allFinite() || grid.axis.norm() == 0) throw make_error("CylinderGridTopology: the axis must be a finite, non-zero vector");
  if (!std::isfinite(grid.radius) || !std::isfinite(grid.length) || !grid.center.allFinite()) {
    throw make_error("CylinderGridTopology: center, radius and length must be finite");
  }
  const double r = grid.radius, l = grid.length;
  const auto [x, y, z] = grid_axes(grid.axis);
  std::vector<Vec3<double>> points;
  points.reserve(static_cast<std::size_t>(nx * ny * nz));
  for (Index k = 0; k < nz; ++k) {
    for (Index j = 0; j < ny; ++j) {
      for (Index i = 0; i < nx; ++i) {
        Vec3<double> p(static_cast<double>(i) * 2 * r / static_cast<double>(nx - 1) - r,
                       static_cast<double>(j) * 2 * r / static_cast<double>(ny - 1) - r, 0);
        if (p.norm() > 0.0000001) p *= std::max(std::abs(p[0]), std::abs(p[1])) / p.norm();
        if (nz > 1) p[2] = static_cast<double>(k) * l / static_cast<double>(nz - 1);
        points.push_back(grid.center + x * p[0] + y * p[1] + z * p[2]);
      }
    }
  }
  return points;
}

}  // namespace fastcorot
