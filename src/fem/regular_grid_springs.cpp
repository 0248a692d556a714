#include "fastcorot/fem/regular_grid_springs.h"

#include "fastcorot/core/error.h"

#include <cmath>

namespace fastcorot {

namespace {

// One family of springs: from point (x, y, z) + `from` to (x, y, z) + `to` for every cell origin in
// [0, n - extent) per axis (extent 1 along the axes the springs cross, 0 along the others), with the
// rest length |length|.
template <class Real>
void add_family(std::vector<Spring<Real>>& springs, const RegularGrid& grid, std::array<Index, 3> extent,
                std::array<Index, 3> from, std::array<Index, 3> to, const Vec3<double>& length, Real stiffness,
                Real damping) {
  const auto rest = static_cast<Real>(length.norm());
  const auto point = [&](Index x, Index y, Index z) { return x + grid.n[0] * (y + grid.n[1] * z); };
  for (Index z = 0; z < grid.n[2] - extent[2]; ++z) {
    for (Index y = 0; y < grid.n[1] - extent[1]; ++y) {
      for (Index x = 0; x < grid.n[0] - extent[0]; ++x) {
        Spring<Real> s;
        s.a = point(x + from[0], y + from[1], z + from[2]);
        s.b = point(x + to[0], y + to[1], z + to[2]);
        s.rest_length = rest;
        s.stiffness = stiffness / rest;
        s.damping = damping / rest;
        springs.push_back(s);
      }
    }
  }
}

}  // namespace

template <class Real>
std::vector<Spring<Real>> regular_grid_springs(const RegularGrid& grid, const RegularGridSpringParameters<Real>& p) {
  validate(grid);
  for (Real value : {p.lines_stiffness, p.lines_damping, p.quads_stiffness, p.quads_damping, p.cubes_stiffness, p.cubes_damping}) {
    if (!(value >= 0) || !std::isfinite(value)) {
      throw make_error("RegularGridSpringForceField: stiffness or damping ", value, ": must be finite and >= 0");
    }
  }
  // SOFA's spacing vectors: (max - min) / (n - 1) along each axis, max - min along an axis with a
  // single point (a flat grid, a cloth: no spring runs along that axis).
  const auto spacing = [&](int a) {
    const double extent = grid.max[a] - grid.min[a];
    const Index n = grid.n[static_cast<std::size_t>(a)];
    return n > 1 ? extent / static_cast<double>(n - 1) : extent;
  };
  const Vec3<double> dx(spacing(0), 0, 0);
  const Vec3<double> dy(0, spacing(1), 0);
  const Vec3<double> dz(0, 0, spacing(2));
  std::vector<Spring<Real>> springs;
  if (p.lines_stiffness != 0 || p.lines_damping != 0) {
    add_family(springs, grid, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}, dx, p.lines_stiffness, p.lines_damping);
    add_family(springs, grid, {0, 1, 0}, {0, 0, 0}, {0, 1, 0}, dy, p.lines_stiffness, p.lines_damping);
    add_family(springs, grid, {0, 0, 1}, {0, 0, 0}, {0, 0, 1}, dz, p.lines_stiffness, p.lines_damping);
  }
  if (p.quads_stiffness != 0 || p.quads_damping != 0) {
    // SOFA interleaves each face's two diagonals: build each plane's pair, then interleave them.
    const auto plane = [&](std::array<Index, 3> extent, std::array<Index, 3> a1, std::array<Index, 3> b1,
                           std::array<Index, 3> a2, std::array<Index, 3> b2, const Vec3<double>& l1,
                           const Vec3<double>& l2) {
      std::vector<Spring<Real>> first, second;
      add_family(first, grid, extent, a1, b1, l1, p.quads_stiffness, p.quads_damping);
      add_family(second, grid, extent, a2, b2, l2, p.quads_stiffness, p.quads_damping);
      for (std::size_t s = 0; s < first.size(); ++s) {
        springs.push_back(first[s]);
        springs.push_back(second[s]);
      }
    };
    plane({1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}, dx + dy, dx - dy);
    plane({1, 0, 1}, {0, 0, 0}, {1, 0, 1}, {1, 0, 0}, {0, 0, 1}, dx + dz, dx - dz);
    // (SOFA gives the yz plane's second diagonal the stiffness over |dy + dz|: the same length, as
    // dy and dz are orthogonal.)
    plane({0, 1, 1}, {0, 0, 0}, {0, 1, 1}, {0, 1, 0}, {0, 0, 1}, dy + dz, dy - dz);
  }
  if (p.cubes_stiffness != 0 || p.cubes_damping != 0) {
    std::vector<Spring<Real>> diagonals[4];
    add_family(diagonals[0], grid, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}, dx + dy + dz, p.cubes_stiffness, p.cubes_damping);
    add_family(diagonals[1], grid, {1, 1, 1}, {1, 0, 0}, {0, 1, 1}, -dx + dy + dz, p.cubes_stiffness, p.cubes_damping);
    add_family(diagonals[2], grid, {1, 1, 1}, {0, 1, 0}, {1, 0, 1}, dx - dy + dz, p.cubes_stiffness, p.cubes_damping);
    add_family(diagonals[3], grid, {1, 1, 1}, {0, 0, 1}, {1, 1, 0}, dx + dy - dz, p.cubes_stiffness, p.cubes_damping);
    for (std::size_t s = 0; s < diagonals[0].size(); ++s) {
      for (const auto& family : diagonals) springs.push_back(family[s]);
    }
  }
  return springs;
}

template std::vector<Spring<double>> regular_grid_springs(const RegularGrid&, const RegularGridSpringParameters<double>&);
template std::vector<Spring<float>> regular_grid_springs(const RegularGrid&, const RegularGridSpringParameters<float>&);

}  // namespace fastcorot
