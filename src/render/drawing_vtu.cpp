#include "fastcorot/render/drawing_vtu.h"

#include "fastcorot/render/tetrahedron_drawing.h"

namespace fastcorot {

DrawnTetrahedraGrid drawn_tetrahedra_grid(const SimulatedObject<double>& object,
                                          TetrahedronDrawing mode) {
  DrawnTetrahedraGrid grid;
  VtuField displacement{"displacement", 3, {}};
  VtuField color{"drawColor", 3, {}}, opacity{"opacity", 1, {}}, tetrahedron{"tetrahedron", 1, {}},
      face{"face", 1, {}};
  const auto& x = object.system.state.position;
  const auto& rest = object.system.state.rest_position;
  for (std::size_t f = 0; f < object.system.force_fields.size(); ++f) {
    if (!draws_tetrahedra(object, f, mode)) continue;
    const ForceFieldDrawing drawing =
        f < object.force_field_drawing.size() ? object.force_field_drawing[f] : ForceFieldDrawing{};
    const auto tetrahedra = object.system.force_fields[f]->mesh().tetrahedra();
    for (std::size_t t = 0; t < tetrahedra.size(); ++t) {
      const auto first = static_cast<Index>(grid.points.size());
      const auto corners = shrunk_tetrahedron<double>(tetrahedron_points<double>(tetrahedra[t], x));
      // The corners are the same affine combination of the vertices in every configuration, so
      // the displacement of a corner is that combination of the vertices' displacements.
      const auto rest_corners =
          rest.size() == x.size()
              ? shrunk_tetrahedron<double>(tetrahedron_points<double>(tetrahedra[t], rest))
              : corners;
      for (int j = 0; j < 4; ++j) {
        grid.points.push_back(corners[j]);
        const Vec3<double> u = corners[j] - rest_corners[j];
        displacement.values.insert(displacement.values.end(), {u.x(), u.y(), u.z()});
      }
      for (std::size_t k = 0; k < 4; ++k) {
        for (int corner : kDrawnFaces[k]) grid.triangles.connectivity.push_back(first + corner);
        const Rgba& c = drawing.colors[k];
        color.values.insert(color.values.end(), {c[0], c[1], c[2]});
        opacity.values.push_back(c[3]);
        tetrahedron.values.push_back(static_cast<double>(t));
        face.values.push_back(kOppositeVertexOfDrawnFace[k]);
      }
    }
  }
  grid.point_fields = {std::move(displacement)};
  grid.cell_fields = {std::move(color), std::move(opacity), std::move(tetrahedron),
                      std::move(face)};
  return grid;
}

void write_drawn_tetrahedra_vtu(const std::filesystem::path& path,
                                const DrawnTetrahedraGrid& grid) {
  write_vtu(path, grid.points, {grid.triangles}, grid.point_fields, grid.cell_fields);
}

}  // namespace fastcorot
