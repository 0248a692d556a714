#include "fastcorot/topology/sphere_grid.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/cylinder_grid.h"

#include <algorithm>
#include <cmath>

namespace fastcorot {

std::vector<Vec3<double>> sphere_grid_points(const SphereGrid& grid) {
  const auto [nx, ny, nz] = grid.n;
  if (nx < 2 || ny < 2 || nz < 2) {
    throw make_error("SphereGridTopology: n = ", nx, " ", ny, " ", nz, ": needs at least 2 points along each axis");
  }
  if (!grid.axis.allFinite() || grid.axis.norm() == 0) throw make_error("SphereGridTopology: the axis must be a finite, non-zero vector");
  if (!std::isfinite(grid.radius) || !grid.center.allFinite()) {
    throw make_error("SphereGridTopology: center and radius must be finite");
  }
  const double r = grid.radius;
  const auto [x, y, z] = grid_axes(grid.axis);
  const auto cube = [r](Index i, Index count) {
    return static_cast<double>(i) * 2 * r / static_cast<double>(count - 1) - r;
  };
  std::vector<Vec3<double>> points;
  points.reserve(static_cast<std::size_t>(nx * ny * nz));
  for (Index k = 0; k < nz; ++k) {
    for (Index j = 0; j < ny; ++j) {
      for (Index i = 0; i < nx; ++i) {
        Vec3<double> p(cube(i, nx), cube(j, ny), cube(k, nz));
        if (p.norm() > 0.0000001) {
          const double largest = std::max(std::max(std::abs(p[0]), std::abs(p[1])), std::abs(p[2]));
          p *= largest / p.norm();
        }
        points.push_back(grid.center + x * p[0] + y * p[1] + z * p[2]);
      }
    }
  }
  return points;
}

}  // namespace fastcorot
