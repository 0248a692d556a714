// Reading tetrahedral mesh files: Gmsh .msh (formats 2.2 and 4.1, ASCII and binary),
// legacy VTK .vtk (4.2 and 5.1, ASCII and binary) and VTK XML .vtu (ascii, base64 "binary" and raw
// or base64 "appended" data, zlib-compressed or not) — whatever gmsh, meshio and ParaView write by
// default. Points are kept in file order (all of them, as SOFA's loaders keep them); tetrahedra are
// the file's linear tetrahedra in file order; other cell types are skipped (triangles are kept
// apart as the surface). Errors name the file, the line (text formats) or byte offset, and the
// fault.
#pragma once

#include "fastcorot/core/types.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

// A mesh as a file holds it, in the file's units. Vertex order within each tetrahedron is the
// file's (gmsh and VTK share the linear tetrahedron's node order); nothing is reoriented.
struct MeshData {
  std::vector<Vec3<double>> points;     // #V points, file order
  std::vector<Tetrahedron> tetrahedra;  // 0-based indices into points
  std::vector<Triangle> triangles;  // triangles the file holds (often the boundary), may be empty
};

// Chooses the reader from the extension (.msh, .vtk, .vtu, .gidmsh; case-insensitive). Throws
// fastcorot::Error for an unknown extension, a missing or unreadable file, a corrupt or truncated
// file, an unsupported format version or encoding, and indices out of range.
MeshData read_mesh_file(const std::filesystem::path& path);

// Gmsh .msh 2.2 (also 2.0, 2.1) and 4.1, ASCII or binary of either byte order. Node tags may
// be any non-negative numbers, in any order and with gaps; they map to 0-based indices in file
// order. Keeps element types 4 (tetrahedron) and 2 (triangle).
MeshData read_gmsh(const std::filesystem::path& path);
// Legacy VTK DATASET UNSTRUCTURED_GRID, versions up to 4.2 (CELLS with counts) and 5.1 (OFFSETS
// and CONNECTIVITY), ASCII or BINARY. Keeps VTK cell types 10 (tetrahedron) and 5 (triangle).
MeshData read_vtk_legacy(const std::filesystem::path& path);
// VTK XML UnstructuredGrid: ascii, binary and appended (raw or base64) arrays, zlib-compressed
// or not, UInt32 or UInt64 headers, either byte order; all pieces, concatenated. Keeps VTK cell
// types 10 and 5.
MeshData read_vtu(const std::filesystem::path& path);
// GiD's ASCII mesh (.gidmsh), as SOFA's GIDMeshLoader reads it (src/io/gid_reader.cpp): Tetrahedra
// (4 or 10 nodes, the first 4 kept) or Triangle elements, node numbers from 1.
MeshData read_gid(const std::filesystem::path& path);

// The same readers on bytes already in memory; `name` stands for the file in messages.
MeshData read_gmsh_bytes(std::string_view bytes, const std::string& name);
MeshData read_vtk_legacy_bytes(std::string_view bytes, const std::string& name);
MeshData read_vtu_bytes(std::string_view bytes, const std::string& name);
MeshData read_gid_bytes(std::string_view bytes, const std::string& name);

}  // namespace fastcorot
