// The drawn tetrahedra of an object as a VTK unstructured grid, so that ParaView shows what the
// pictures show: every tetrahedron of a force field with drawing on (draw_geometry.h) gives its
// four shrunk corners (tetrahedron_drawing.h) and its four triangles in SOFA's face order. Cell
// data: `drawColor` (RGB in [0, 1]; in ParaView colour by it with "Map Scalars" off), `opacity`,
// `tetrahedron` (the element's index in its mesh) and `face` (the local vertex the triangle is
// opposite to). Point data: `displacement`, interpolated from the mesh points like the corners
// themselves, so "Warp By Vector" and glyphs behave as on the mesh.
#pragma once

#include "fastcorot/render/draw_geometry.h"
#include "fastcorot/io/vtu_writer.h"

#include <filesystem>

namespace fastcorot {

struct DrawnTetrahedraGrid {
  std::vector<Vec3<double>> points;  // 4 per drawn tetrahedron
  VtuCellBlock triangles{5, 3, {}};  // 4 per drawn tetrahedron (VTK triangles)
  std::vector<VtuField> point_fields;
  std::vector<VtuField> cell_fields;

  bool empty() const { return triangles.connectivity.empty(); }
};

// The grid of `object` at its current positions; empty when no force field of it is drawn.
DrawnTetrahedraGrid drawn_tetrahedra_grid(const SimulatedObject<double>& object,
                                          TetrahedronDrawing mode);

// write_vtu of the grid; throws fastcorot::Error naming the file when it cannot be written.
void write_drawn_tetrahedra_vtu(const std::filesystem::path& path, const DrawnTetrahedraGrid& grid);

}  // namespace fastcorot
