// GiD's ASCII mesh format as SOFA's GIDMeshLoader reads it: a header line "MESH dimension D
// ElemType T Nnode N", then "Coordinates" ... "End Coordinates" with one "id x y [z]" line per
// point (ids are not read: points are in file order, as SOFA keeps them), then "Elements" ...
// "End Elements" with one "id n1 n2 ..." line per element, node numbers from 1. Keywords are
// case-insensitive. Tetrahedra (4 nodes, or 10 of which the first 4 are the corners, as SOFA
// takes them) and triangles are kept; other element types are refused.
#include "fastcorot/io/mesh_readers.h"

#include "mesh_reader_support.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace fastcorot {

namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

}  // namespace

MeshData read_gid_bytes(std::string_view bytes, const std::string& name) {
  std::istringstream in{std::string(bytes)};
  std::string line;
  std::size_t number = 0;
  const auto fail = [&](const std::string& why) { return make_error(name, ":", number, ": ", why); };
  const auto next = [&]() -> bool {
    if (!std::getline(in, line)) return false;
    ++number;
    line = trimmed(line);
    return true;
  };
  // The header.
  while (next() && line.empty()) {
  }
  std::istringstream header(line);
  std::string word, element_type;
  int dimension = 0, nodes = 0;
  bool mesh = false;
  while (header >> word) {
    const std::string key = lower(word);
    if (key == "mesh") mesh = true;
    if (key == "dimension" && !(header >> dimension)) throw fail("MESH header: no number after dimension");
    if (key == "elemtype" && !(header >> element_type)) throw fail("MESH header: no type after ElemType");
    if (key == "nnode" && !(header >> nodes)) throw fail("MESH header: no number after Nnode");
  }
  if (!mesh) throw fail("expected a header line \"MESH dimension 3 ElemType Tetrahedra Nnode 4\"");
  if (dimension != 2 && dimension != 3) throw fail("MESH header: dimension " + std::to_string(dimension) + " (2 or 3 expected)");
  const std::string type = lower(element_type);
  int corners = 0;
  if (type == "tetrahedra") {
    if (nodes != 4 && nodes != 10) throw fail("Tetrahedra with Nnode " + std::to_string(nodes) + " (4 or 10 expected)");
    corners = 4;
  } else if (type == "triangle") {
    if (nodes != 3 && nodes != 6) throw fail("Triangle with Nnode " + std::to_string(nodes) + " (3 or 6 expected)");
    corners = 3;
  } else {
    throw fail("ElemType " + element_type + ": fastcorot reads Tetrahedra and Triangle");
  }
  MeshData data;
  const auto section = [&](const char* title) {
    while (next()) {
      if (lower(line) == title) return;
    }
    throw fail(std::string("no \"") + title + "\" section");
  };
  section("coordinates");
  while (true) {
    if (!next()) throw fail("unexpected end of file in Coordinates (no \"End Coordinates\")");
    if (lower(line) == "end coordinates") break;
    if (line.empty()) continue;
    std::istringstream point(line);
    long id = 0;
    Vec3<double> p = Vec3<double>::Zero();
    if (!(point >> id)) throw fail("expected \"id x y" + std::string(dimension == 3 ? " z" : "") + "\"");
    for (int d = 0; d < dimension; ++d) {
      if (!(point >> p[d])) throw fail("point " + std::to_string(id) + ": expected " + std::to_string(dimension) + " coordinates");
    }
    data.points.push_back(p);
  }
  section("elements");
  while (true) {
    if (!next()) throw fail("unexpected end of file in Elements (no \"End Elements\")");
    if (lower(line) == "end elements") break;
    if (line.empty()) continue;
    std::istringstream element(line);
    long id = 0;
    std::array<long, 4> v{};
    if (!(element >> id)) throw fail("expected \"id n1 n2 ...\"");
    for (int k = 0; k < corners; ++k) {
      if (!(element >> v[static_cast<std::size_t>(k)])) throw fail("element " + std::to_string(id) + ": expected " + std::to_string(nodes) + " node numbers");
      if (v[static_cast<std::size_t>(k)] < 1 || v[static_cast<std::size_t>(k)] > static_cast<long>(data.points.size())) {
        throw fail("element " + std::to_string(id) + ": node " + std::to_string(v[static_cast<std::size_t>(k)]) + " out of range [1, " +
                   std::to_string(data.points.size()) + "]");
      }
    }
    if (corners == 4) {
      data.tetrahedra.push_back({static_cast<Index>(v[0] - 1), static_cast<Index>(v[1] - 1), static_cast<Index>(v[2] - 1),
                                 static_cast<Index>(v[3] - 1)});
    } else {
      data.triangles.push_back({static_cast<Index>(v[0] - 1), static_cast<Index>(v[1] - 1), static_cast<Index>(v[2] - 1)});
    }
  }
  detail::check_mesh_data(data, name);
  return data;
}

MeshData read_gid(const std::filesystem::path& path) { return read_gid_bytes(detail::read_file_bytes(path), path.string()); }

}  // namespace fastcorot
