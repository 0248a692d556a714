#include "fastcorot/io/surface_readers.h"

#include "mesh_reader_support.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>

namespace fastcorot {

std::vector<Triangle> SurfaceData::all_triangles() const {
  std::vector<Triangle> out = triangles;
  for (const Quad& q : quads) {
    out.push_back({q[0], q[1], q[2]});
    out.push_back({q[0], q[2], q[3]});
  }
  return out;
}

namespace {

void check_surface(const SurfaceData& surface, const std::string& file) {
  const auto n = static_cast<Index>(surface.points.size());
  for (std::size_t i = 0; i < surface.points.size(); ++i) {
    if (!surface.points[i].allFinite()) throw make_error(file, ": point ", i, " has a coordinate that is not finite");
  }
  const auto check = [&](const auto& cell, std::size_t c, const char* what) {
    for (Index v : cell) {
      if (v < 0 || v >= n) throw make_error(file, ": ", what, " ", c, " has vertex ", v, ", outside [0, ", n, ")");
    }
  };
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) check(surface.triangles[t], t, "triangle");
  for (std::size_t q = 0; q < surface.quads.size(); ++q) check(surface.quads[q], q, "quad");
}

// One entry of an OBJ face ("7", "7/2", "7//3", "7/2/3"): the point index, 0-based.
Index obj_vertex(std::string_view entry, Index num_points, const detail::FileCursor& cursor, std::size_t at) {
  const std::string_view first = entry.substr(0, entry.find('/'));
  long long index = 0;
  const auto [end, ec] = std::from_chars(first.data(), first.data() + first.size(), index);
  if (first.empty() || ec != std::errc() || end != first.data() + first.size()) {
    cursor.fail_text_at(at, "face vertex '", detail::FileCursor::printable(entry), "' is not an index");
  }
  // 1-based, or negative: relative to the points read so far (-1 is the last one).
  const long long zero_based = index > 0 ? index - 1 : index < 0 ? num_points + index : -1;
  if (zero_based < 0 || zero_based >= num_points) {
    cursor.fail_text_at(at, "face vertex ", index, " refers to no point (", num_points, " read so far)");
  }
  return static_cast<Index>(zero_based);
}

}  // namespace

SurfaceData read_obj_bytes(std::string_view bytes, const std::string& name) {
  detail::FileCursor cursor(bytes, name);
  SurfaceData surface;
  while (cursor.skip_whitespace()) {
    const std::size_t line_start = cursor.position();
    const std::string_view keyword = cursor.token("a statement");
    if (keyword.front() == '#') {
      cursor.rest_of_line();
      continue;
    }
    if (keyword == "v") {
      Vec3<double> p;
      for (int k = 0; k < 3; ++k) p[k] = cursor.real("a coordinate");
      cursor.rest_of_line();  // an optional w
      if (!p.allFinite()) cursor.fail_text_at(line_start, "point ", surface.points.size(), " is not finite");
      surface.points.push_back(p);
    } else if (keyword == "f") {
      std::vector<Index> face;
      for (std::string_view entry = cursor.token_on_line(); !entry.empty(); entry = cursor.token_on_line()) {
        face.push_back(obj_vertex(entry, static_cast<Index>(surface.points.size()), cursor, line_start));
      }
      cursor.rest_of_line();
      if (face.size() < 3) cursor.fail_text_at(line_start, "a face needs 3 vertices or more, found ", face.size());
      if (face.size() == 4) {
        surface.quads.push_back({face[0], face[1], face[2], face[3]});
      } else {
        for (std::size_t j = 2; j < face.size(); ++j) surface.triangles.push_back({face[0], face[j - 1], face[j]});
      }
    } else {
      cursor.rest_of_line();  // vt, vn, l, o, g, s, usemtl, mtllib: not needed for the surface
    }
  }
  if (surface.points.empty()) throw make_error(name, ": no vertices (v lines): not an OBJ surface");
  check_surface(surface, name);
  return surface;
}

SurfaceData read_obj(const std::filesystem::path& path) {
  return read_obj_bytes(detail::read_file_bytes(path), path.string());
}

namespace {

// Merges coincident corners (exact coordinates) into points in order of first appearance.
class CornerPoints {
 public:
  Index add(const Vec3<double>& p) {
    const auto key = std::array<double, 3>{p.x(), p.y(), p.z()};
    const auto [it, inserted] = index_.emplace(key, static_cast<Index>(points.size()));
    if (inserted) points.push_back(p);
    return it->second;
  }
  std::vector<Vec3<double>> points;

 private:
  std::map<std::array<double, 3>, Index> index_;
};

SurfaceData read_binary_stl(std::string_view bytes, const std::string& name) {
  detail::FileCursor cursor(bytes, name);
  cursor.bytes(80, "the header");
  const auto count = cursor.binary<std::uint32_t>(!detail::kHostIsLittleEndian, "the triangle count");
  CornerPoints corners;
  SurfaceData surface;
  for (std::uint32_t t = 0; t < count; ++t) {
    for (int k = 0; k < 3; ++k) cursor.binary<float>(!detail::kHostIsLittleEndian, "a normal");
    Triangle triangle;
    for (int c = 0; c < 3; ++c) {
      Vec3<double> p;
      for (int k = 0; k < 3; ++k) p[k] = cursor.binary<float>(!detail::kHostIsLittleEndian, "a vertex");
      if (!p.allFinite()) cursor.fail_binary("triangle ", t, " has a vertex that is not finite");
      triangle[static_cast<std::size_t>(c)] = corners.add(p);
    }
    cursor.bytes(2, "the attribute byte count");
    surface.triangles.push_back(triangle);
  }
  surface.points = std::move(corners.points);
  return surface;
}

SurfaceData read_ascii_stl(std::string_view bytes, const std::string& name) {
  detail::FileCursor cursor(bytes, name);
  cursor.expect("solid");
  cursor.rest_of_line();
  CornerPoints corners;
  SurfaceData surface;
  while (true) {
    const std::string_view keyword = cursor.token("facet or endsolid");
    if (keyword == "endsolid") break;
    if (keyword != "facet") cursor.fail_text("expected 'facet' or 'endsolid', found '", detail::FileCursor::printable(keyword), "'");
    cursor.expect("normal");
    for (int k = 0; k < 3; ++k) cursor.real("a normal");
    cursor.expect("outer");
    cursor.expect("loop");
    Triangle triangle;
    for (int c = 0; c < 3; ++c) {
      cursor.expect("vertex");
      Vec3<double> p;
      for (int k = 0; k < 3; ++k) p[k] = cursor.real("a coordinate");
      if (!p.allFinite()) cursor.fail_text("a vertex that is not finite");
      triangle[static_cast<std::size_t>(c)] = corners.add(p);
    }
    cursor.expect("endloop");
    cursor.expect("endfacet");
    surface.triangles.push_back(triangle);
  }
  surface.points = std::move(corners.points);
  return surface;
}

}  // namespace

SurfaceData read_stl_bytes(std::string_view bytes, const std::string& name) {
  // Binary when the size is that of its triangle count (ASCII files may start with "solid" too).
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (!detail::kHostIsLittleEndian) count = detail::byteswap_value(count);
    if (84 + 50 * static_cast<std::uint64_t>(count) == bytes.size()) {
      SurfaceData surface = read_binary_stl(bytes, name);
      check_surface(surface, name);
      return surface;
    }
  }
  const auto start = bytes.find_first_not_of(" \t\r\n");
  if (start == std::string_view::npos || bytes.substr(start, 5) != "solid") {
    throw make_error(name, ": not an STL file (neither 'solid' text nor a binary file of 84 + 50 n bytes)");
  }
  SurfaceData surface = read_ascii_stl(bytes, name);
  check_surface(surface, name);
  return surface;
}

SurfaceData read_stl(const std::filesystem::path& path) {
  return read_stl_bytes(detail::read_file_bytes(path), path.string());
}

SurfaceData read_surface_file(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".obj") return read_obj(path);
  if (extension == ".stl") return read_stl(path);
  throw make_error(path.string(), ": unknown surface file extension '", path.extension().string(),
                   "' (supported: .obj, .stl)");
}

}  // namespace fastcorot
