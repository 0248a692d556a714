#include "fastcorot/io/mesh_readers.h"

#include "mesh_reader_support.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace fastcorot {

namespace detail {

std::string read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw make_error(path.string(), ": no such file");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw make_error(path.string(), ": not a regular file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw make_error(path.string(), ": cannot open file for reading");
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) throw make_error(path.string(), ": read error");
  return std::move(contents).str();
}

std::size_t line_number(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<std::size_t>(std::count(
                 text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

void check_mesh_data(const MeshData& mesh, const std::string& file) {
  const auto num_points = static_cast<std::int64_t>(mesh.points.size());
  if (num_points > INT32_MAX) {
    throw make_error(file, ": ", num_points, " points, more than the supported ", INT32_MAX);
  }
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    if (!mesh.points[i].allFinite()) {
      throw make_error(file, ": point ", i, " has a coordinate that is not finite (",
                       mesh.points[i].x(), " ", mesh.points[i].y(), " ", mesh.points[i].z(), ")");
    }
  }
  const auto check = [&](const auto& cells, const char* kind) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      for (const Index v : cells[c]) {
        if (v < 0 || v >= num_points) {
          throw make_error(file, ": ", kind, " ", c, ": point index ", v, " out of range [0, ",
                           num_points, ")");
        }
      }
    }
  };
  check(mesh.tetrahedra, "tetrahedron");
  check(mesh.triangles, "triangle");
}

}  // namespace detail

MeshData read_mesh_file(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".msh") return read_gmsh(path);
  if (extension == ".vtk") {
    // SOFA's MeshVTKLoader reads both VTK formats whatever the extension: an XML file (<VTKFile ...>)
    // named .vtk is read as one.
    std::ifstream in(path, std::ios::binary);
    std::string start(64, '\0');
    in.read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<std::size_t>(in.gcount()));
    const auto first = start.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && start.compare(first, 8, "<VTKFile") == 0) return read_vtu(path);
    if (first != std::string::npos && start.compare(first, 5, "<?xml") == 0) return read_vtu(path);
    return read_vtk_legacy(path);
  }
  if (extension == ".vtu") return read_vtu(path);
  if (extension == ".gidmsh") return read_gid(path);
  throw make_error(path.string(), ": unknown mesh file extension '", path.extension().string(),
                   "' (supported: .msh (Gmsh), .vtk (legacy VTK), .vtu (VTK XML), .gidmsh (GiD))");
}

}  // namespace fastcorot
