#include "fastcorot/topology/tetrahedron_subdivision.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

Subdivision subdivide_tetrahedra(const TetMesh& mesh, std::span<const Vec3<double>> points) {
  if (points.size() != static_cast<std::size_t>(mesh.num_points())) {
    throw make_error("subdivision: ", points.size(), " positions for a mesh of ", mesh.num_points(), " points");
  }
  Subdivision out;
  out.points.assign(points.begin(), points.end());
  for (const Edge& e : mesh.edges()) {
    const Vec3<double>& a = points[static_cast<std::size_t>(e[0])];
    const Vec3<double>& b = points[static_cast<std::size_t>(e[1])];
    out.points.emplace_back((a.x() + b.x()) / 2, (a.y() + b.y()) / 2, (a.z() + b.z()) / 2);
  }
  const Index first_midpoint = mesh.num_points();
  for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
    const Tetrahedron& v = mesh.tetrahedron(t);
    std::array<Index, 6> m{};
    for (std::size_t k = 0; k < 6; ++k) m[k] = first_midpoint + mesh.edges_of_tetrahedron(t)[k];
    // Corners with the midpoints of their three edges, then the inner octahedron split along the
    // diagonal between the midpoints of edges 0-2 and 1-3 (SOFA's table).
    const std::array<Tetrahedron, 8> children = {{{v[0], m[0], m[1], m[2]},
                                                  {v[1], m[0], m[4], m[3]},
                                                  {v[2], m[1], m[3], m[5]},
                                                  {v[3], m[2], m[5], m[4]},
                                                  {m[1], m[0], m[3], m[5]},
                                                  {m[1], m[0], m[5], m[2]},
                                                  {m[4], m[0], m[5], m[3]},
                                                  {m[4], m[0], m[2], m[5]}}};
    out.tetrahedra.insert(out.tetrahedra.end(), children.begin(), children.end());
  }
  return out;
}

}  // namespace fastcorot
