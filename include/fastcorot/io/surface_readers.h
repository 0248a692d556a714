// Reading triangle surfaces: Wavefront .obj (as SOFA's MeshOBJLoader reads it) and STL (ASCII and
// binary, as MeshSTLLoader reads it). These are the visual surfaces SOFA scenes map onto their
// tetrahedra. Errors name the file and the line (text) or byte (binary STL).
#pragma once

#include "fastcorot/core/types.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

using Quad = std::array<Index, 4>;

// A surface as the file holds it: points in file order, triangles and quads (0-based) in file
// order. OBJ faces of three vertices are triangles, of four quads, of more a fan of triangles
// (0, j - 1, j) as SOFA makes them; `l` lines and texture / normal indices are read and checked
// but not kept.
struct SurfaceData {
  std::vector<Vec3<double>> points;
  std::vector<Triangle> triangles;
  std::vector<Quad> quads;
  // The triangles to draw: the triangles, then each quad (a, b, c, d) as (a, b, c) and (a, c, d).
  std::vector<Triangle> all_triangles() const;
};

// Chooses the reader from the extension (.obj, .stl; case-insensitive).
SurfaceData read_surface_file(const std::filesystem::path& path);

// Wavefront OBJ: `v x y z [w]`, `f` with `v`, `v/vt`, `v//vn` or `v/vt/vn` entries, 1-based or
// negative (relative) indices; other statements (vt, vn, o, g, s, usemtl, mtllib, l) are skipped.
SurfaceData read_obj(const std::filesystem::path& path);
SurfaceData read_obj_bytes(std::string_view bytes, const std::string& name);

// STL, ASCII (`solid ... facet normal ... outer loop vertex ... endloop endfacet ... endsolid`) or
// binary (80-byte header, triangle count, 50 bytes per triangle); a binary file is recognised by
// its size. Each triangle's three corners become points; coincident corners are merged into one
// point, as SOFA's loader does, in order of first appearance.
SurfaceData read_stl(const std::filesystem::path& path);
SurfaceData read_stl_bytes(std::string_view bytes, const std::string& name);

}  // namespace fastcorot
