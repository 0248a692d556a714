#include "fastcorot/topology/mesh2point_mapping.h"

#include "fastcorot/core/error.h"

#include <string_view>

namespace fastcorot {

namespace {

// The corner positions of one element, checked against the point count.
template <std::size_t N>
std::array<Vec3<double>, N> corners(std::span<const Vec3<double>> points, const std::array<Index, N>& element,
                                    std::string_view kind, std::size_t e) {
  std::array<Vec3<double>, N> p;
  for (std::size_t j = 0; j < N; ++j) {
    if (element[j] < 0 || static_cast<std::size_t>(element[j]) >= points.size()) {
      throw make_error(kind, " ", e, " names point ", element[j], ", outside the input's ", points.size(), " points");
    }
    p[j] = points[static_cast<std::size_t>(element[j])];
  }
  return p;
}

}  // namespace

std::vector<Vec3<double>> mesh2point_points(const Mesh2PointInput& in, const Mesh2PointCoords& coords) {
  std::vector<Vec3<double>> out;
  if (!coords.point.empty()) {
    for (const Vec3<double>& p : in.points) {
      for (const Vec3<double>& c : coords.point) out.push_back(p + c);
    }
  }
  if (!coords.edge.empty()) {
    for (std::size_t e = 0; e < in.edges.size(); ++e) {
      const auto p = corners(in.points, in.edges[e], "edge", e);
      for (const Vec3<double>& c : coords.edge) out.push_back(p[0] * (1 - c[0]) + p[1] * c[0]);
    }
  }
  if (!coords.triangle.empty()) {
    for (std::size_t e = 0; e < in.triangles.size(); ++e) {
      const auto p = corners(in.points, in.triangles[e], "triangle", e);
      for (const Vec3<double>& c : coords.triangle) out.push_back(p[0] * (1 - c[0] - c[1]) + p[1] * c[0] + p[2] * c[1]);
    }
  }
  if (!coords.quad.empty()) {
    for (std::size_t e = 0; e < in.quads.size(); ++e) {
      const auto p = corners(in.points, in.quads[e], "quad", e);
      for (const Vec3<double>& c : coords.quad) {
        const double x = c[0], y = c[1];
        out.push_back(p[0] * ((1 - x) * (1 - y)) + p[1] * (x * (1 - y)) + p[2] * ((1 - x) * y) + p[3] * (x * y));
      }
    }
  }
  if (!coords.tetra.empty()) {
    for (std::size_t e = 0; e < in.tetrahedra.size(); ++e) {
      const auto p = corners(in.points, in.tetrahedra[e], "tetrahedron", e);
      for (const Vec3<double>& c : coords.tetra) {
        out.push_back(p[0] * (1 - c[0] - c[1] - c[2]) + p[1] * c[0] + p[2] * c[1] + p[3] * c[2]);
      }
    }
  }
  if (!coords.hexa.empty()) {
    for (std::size_t e = 0; e < in.hexahedra.size(); ++e) {
      const auto h = corners(in.points, in.hexahedra[e], "hexahedron", e);
      // Corners in lexicographic (x fastest) order from SOFA's counter-clockwise faces.
      const std::array<Vec3<double>, 8> p = {h[0], h[1], h[3], h[2], h[4], h[5], h[7], h[6]};
      for (const Vec3<double>& c : coords.hexa) {
        const double x = c[0], y = c[1], z = c[2];
        out.push_back(p[0] * ((1 - x) * (1 - y) * (1 - z)) + p[1] * (x * (1 - y) * (1 - z)) + p[2] * ((1 - x) * y * (1 - z)) +
                      p[3] * (x * y * (1 - z)) + p[4] * ((1 - x) * (1 - y) * z) + p[5] * (x * (1 - y) * z) +
                      p[6] * ((1 - x) * y * z) + p[7] * (x * y * z));
      }
    }
  }
  return out;
}

}  // namespace fastcorot
