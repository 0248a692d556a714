// Legacy VTK .vtk reader for DATASET UNSTRUCTURED_GRID, after "VTK File Formats" (VTK User's
// Guide) and vtkDataReader / vtkUnstructuredGridReader. Two cell layouts exist:
//  - versions up to 4.2: `CELLS n size` followed by `size` integers, each cell as
//    (point count, point indices...);
//  - version 5.1 (VTK 9): `CELLS n_offsets n_connectivity` followed by `OFFSETS <type>` and
//    `CONNECTIVITY <type>` arrays.
// BINARY files store the arrays big-endian right after the keyword line. Attribute data
// (POINT_DATA, CELL_DATA) comes after the geometry in every writer, so reading stops there.
#include "fastcorot/io/mesh_readers.h"

#include "mesh_reader_support.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

namespace {

using detail::FileCursor;

constexpr std::int64_t kVtkTriangle = 5;
constexpr std::int64_t kVtkTetrahedron = 10;

struct ValueType {
  std::string_view name;
  int bytes;
  bool integral;
  bool is_signed;
};

// The names vtkDataWriter writes (vtkDataWriter::WriteArray). "long" is 8 bytes as on the
// 64-bit platforms that write it.
constexpr std::array<ValueType, 13> kValueTypes = {{{"unsigned_char", 1, true, false},
                                                    {"char", 1, true, true},
                                                    {"signed_char", 1, true, true},
                                                    {"unsigned_short", 2, true, false},
                                                    {"short", 2, true, true},
                                                    {"unsigned_int", 4, true, false},
                                                    {"int", 4, true, true},
                                                    {"unsigned_long", 8, true, false},
                                                    {"long", 8, true, true},
                                                    {"vtktypeint64", 8, true, true},
                                                    {"vtktypeuint64", 8, true, false},
                                                    {"float", 4, false, true},
                                                    {"double", 8, false, true}}};

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

// Cell lists (4.2) and cell types are always written as int.
constexpr ValueType kInt = kValueTypes[6];

// Legacy binary files are big-endian.
constexpr bool kSwap = detail::kHostIsLittleEndian;

class LegacyReader {
 public:
  LegacyReader(std::string_view data, std::string file) : in_(data, std::move(file)) {}

  MeshData read() {
    read_header();
    std::vector<std::int64_t> offsets;  // cell c is connectivity[offsets[c], offsets[c + 1])
    std::vector<std::int64_t> connectivity;
    std::vector<std::int64_t> types;
    std::size_t cells_at = 0;
    bool have_points = false;
    bool have_cells = false;
    bool have_types = false;
    while (!(have_points && have_cells && have_types) && in_.skip_whitespace()) {
      const std::size_t keyword_at = in_.position();
      const std::string_view keyword = in_.token("a keyword");
      if (iequals(keyword, "POINTS")) {
        if (have_points) in_.fail_text_at(keyword_at, "a second POINTS section");
        read_points();
        have_points = true;
      } else if (iequals(keyword, "CELLS")) {
        if (have_cells) in_.fail_text_at(keyword_at, "a second CELLS section");
        cells_at = keyword_at;
        version5_ ? read_cells_v5(offsets, connectivity) : read_cells_v4(offsets, connectivity);
        have_cells = true;
      } else if (iequals(keyword, "CELL_TYPES")) {
        if (!have_cells) in_.fail_text_at(keyword_at, "CELL_TYPES before CELLS");
        const auto count = count_value("the cell count");
        if (count + 1 != offsets.size()) {
          in_.fail_text_at(keyword_at, "CELL_TYPES has ", count, " cells, CELLS has ",
                           offsets.size() - 1);
        }
        read_integers(kInt, count, types, "the cell types");
        have_types = true;
      } else if (iequals(keyword, "METADATA")) {
        skip_metadata();
      } else if (iequals(keyword, "FIELD")) {
        skip_field();
      } else if (iequals(keyword, "POINT_DATA") || iequals(keyword, "CELL_DATA")) {
        break;  // attributes follow the geometry; none of them is needed
      } else {
        in_.fail_text_at(keyword_at, "unexpected keyword '", FileCursor::printable(keyword), "'");
      }
    }
    if (!have_points) in_.fail_text("no POINTS section");
    if (have_cells && !have_types) in_.fail_text("CELLS without CELL_TYPES");
    for (std::size_t c = 0; c + 1 < offsets.size(); ++c) {
      const std::int64_t first = offsets[c];
      const std::int64_t count = offsets[c + 1] - first;
      if (types[c] == kVtkTetrahedron) {
        if (count != 4)
          in_.fail_text_at(cells_at, "cell ", c, ": a tetrahedron (type 10) with ", count,
                           " points");
        mesh_.tetrahedra.push_back({point_index(connectivity, first, c, cells_at),
                                    point_index(connectivity, first + 1, c, cells_at),
                                    point_index(connectivity, first + 2, c, cells_at),
                                    point_index(connectivity, first + 3, c, cells_at)});
      } else if (types[c] == kVtkTriangle) {
        if (count != 3)
          in_.fail_text_at(cells_at, "cell ", c, ": a triangle (type 5) with ", count, " points");
        mesh_.triangles.push_back({point_index(connectivity, first, c, cells_at),
                                   point_index(connectivity, first + 1, c, cells_at),
                                   point_index(connectivity, first + 2, c, cells_at)});
      }
    }
    detail::check_mesh_data(mesh_, in_.file());
    return std::move(mesh_);
  }

 private:
  void read_header() {
    constexpr std::string_view kMagic = "# vtk DataFile Version";
    const std::string_view first = in_.rest_of_line();
    if (first.substr(0, kMagic.size()) != kMagic) {
      in_.set_position(0);
      in_.fail_text("not a legacy VTK file: the first line is not '# vtk DataFile Version x.x'");
    }
    std::string_view version = first.substr(kMagic.size());
    while (!version.empty() && std::isspace(static_cast<unsigned char>(version.front())))
      version.remove_prefix(1);
    while (!version.empty() && std::isspace(static_cast<unsigned char>(version.back())))
      version.remove_suffix(1);
    if (version == "5.1") {
      version5_ = true;
    } else if (!(version == "4.2" || version == "4.1" || version == "4.0" || version == "3.0" ||
                 version == "2.0" || version == "1.0")) {
      in_.set_position(0);
      in_.fail_text("unsupported legacy VTK version '", FileCursor::printable(version),
                    "' (supported: 4.2 and earlier, and 5.1)");
    }
    if (in_.at_end()) in_.fail_text("unexpected end of file, expected the title line");
    in_.rest_of_line();  // the title
    const std::size_t encoding_at = (in_.skip_whitespace(), in_.position());
    const std::string_view encoding = in_.token("ASCII or BINARY");
    if (iequals(encoding, "BINARY")) {
      binary_ = true;
    } else if (!iequals(encoding, "ASCII")) {
      in_.fail_text_at(encoding_at, "unknown encoding '", FileCursor::printable(encoding),
                       "' (expected ASCII or BINARY)");
    }
    const std::size_t dataset_at = (in_.skip_whitespace(), in_.position());
    if (!iequals(in_.token("DATASET"), "DATASET"))
      in_.fail_text_at(dataset_at, "expected 'DATASET'");
    const std::string_view dataset = in_.token("the dataset type");
    if (!iequals(dataset, "UNSTRUCTURED_GRID")) {
      in_.fail_text_at(dataset_at, "dataset type '", FileCursor::printable(dataset),
                       "' is not supported (only UNSTRUCTURED_GRID)");
    }
  }

  std::size_t count_value(std::string_view what) {
    const auto count = in_.integer<std::int64_t>(what);
    if (count < 0 || count > INT32_MAX) in_.fail_text("bad ", what, " ", count);
    return static_cast<std::size_t>(count);
  }

  const ValueType& value_type() {
    const std::size_t at = (in_.skip_whitespace(), in_.position());
    const std::string_view name = in_.token("a data type");
    for (const ValueType& type : kValueTypes) {
      if (iequals(name, type.name)) return type;
    }
    in_.fail_text_at(at, "unsupported data type '", FileCursor::printable(name),
                     "' (supported: float, double and the integer types)");
  }

  // Binary arrays start after the line break that ends the keyword line.
  void begin_array(const ValueType& type, std::size_t count, std::string_view what) {
    if (!binary_) return;
    in_.rest_of_line();
    if (count > in_.remaining() / static_cast<std::size_t>(type.bytes)) {
      in_.fail_binary("unexpected end of file in ", what, " (", count, " values of ", type.bytes,
                      " bytes needed)");
    }
  }

  template <class Out>
  Out binary_value(const ValueType& type, std::string_view what) {
    const char* p = in_.bytes(static_cast<std::size_t>(type.bytes), what).data();
    if (!type.integral) {
      return static_cast<Out>(type.bytes == 4 ? detail::load_value<float>(p, kSwap)
                                              : detail::load_value<double>(p, kSwap));
    }
    switch (type.bytes) {
      case 1:
        return static_cast<Out>(type.is_signed
                                    ? static_cast<std::int64_t>(static_cast<signed char>(*p))
                                    : static_cast<std::int64_t>(static_cast<unsigned char>(*p)));
      case 2:
        return static_cast<Out>(type.is_signed ? detail::load_value<std::int16_t>(p, kSwap)
                                               : detail::load_value<std::uint16_t>(p, kSwap));
      case 4:
        return static_cast<Out>(type.is_signed ? detail::load_value<std::int32_t>(p, kSwap)
                                               : detail::load_value<std::uint32_t>(p, kSwap));
      default:
        return static_cast<Out>(type.is_signed ? detail::load_value<std::int64_t>(p, kSwap)
                                               : static_cast<std::int64_t>(
                                                     detail::load_value<std::uint64_t>(p, kSwap)));
    }
  }

  void read_reals(const ValueType& type, std::size_t count, std::vector<double>& out,
                  std::string_view what) {
    begin_array(type, count, what);
    out.clear();
    out.reserve(std::min(count, in_.remaining()));
    for (std::size_t i = 0; i < count; ++i) {
      out.push_back(binary_ ? binary_value<double>(type, what) : in_.real(what));
    }
  }

  void read_integers(const ValueType& type, std::size_t count, std::vector<std::int64_t>& out,
                     std::string_view what) {
    if (!type.integral) in_.fail_text(what, " must be integers, not ", type.name);
    begin_array(type, count, what);
    out.clear();
    out.reserve(std::min(count, in_.remaining()));
    for (std::size_t i = 0; i < count; ++i) {
      out.push_back(binary_ ? binary_value<std::int64_t>(type, what)
                            : in_.integer<std::int64_t>(what));
    }
  }

  void read_points() {
    const std::size_t count = count_value("the point count");
    const ValueType& type = value_type();
    std::vector<double> xyz;
    read_reals(type, 3 * count, xyz, "the point coordinates");
    mesh_.points.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      mesh_.points[i] = Vec3<double>(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    }
  }

  void read_cells_v4(std::vector<std::int64_t>& offsets, std::vector<std::int64_t>& connectivity) {
    const std::size_t cells_at = in_.position();
    const std::size_t count = count_value("the cell count");
    const std::size_t size = count_value("the cell list size");
    std::vector<std::int64_t> list;
    read_integers(kInt, size, list, "the cell list");
    offsets.assign(1, 0);
    connectivity.clear();
    std::size_t at = 0;
    for (std::size_t c = 0; c < count; ++c) {
      const std::int64_t n = at < list.size() ? list[at] : -1;
      if (at >= list.size() || n < 0 || static_cast<std::size_t>(n) > list.size() - at - 1) {
        in_.fail_text_at(cells_at, "CELLS: cell ", c, " runs past the cell list of ", size,
                         " integers");
      }
      connectivity.insert(
          connectivity.end(), list.begin() + static_cast<std::ptrdiff_t>(at + 1),
          list.begin() + static_cast<std::ptrdiff_t>(at + 1 + static_cast<std::size_t>(n)));
      at += 1 + static_cast<std::size_t>(n);
      offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    if (at != list.size()) {
      in_.fail_text_at(cells_at, "CELLS: ", count, " cells use ", at, " of the ", size,
                       " integers");
    }
  }

  void read_cells_v5(std::vector<std::int64_t>& offsets, std::vector<std::int64_t>& connectivity) {
    const std::size_t cells_at = in_.position();
    const std::size_t num_offsets = count_value("the offset count");
    const std::size_t num_connectivity = count_value("the connectivity size");
    in_.expect("OFFSETS");
    read_integers(value_type(), num_offsets, offsets, "the cell offsets");
    in_.expect("CONNECTIVITY");
    read_integers(value_type(), num_connectivity, connectivity, "the cell connectivity");
    if (offsets.empty()) offsets.push_back(0);  // no cells
    if (offsets.front() != 0 || offsets.back() != static_cast<std::int64_t>(num_connectivity)) {
      in_.fail_text_at(cells_at, "CELLS: offsets must run from 0 to the connectivity size ",
                       num_connectivity, ", they run from ", offsets.front(), " to ",
                       offsets.back());
    }
    for (std::size_t c = 0; c + 1 < offsets.size(); ++c) {
      if (offsets[c + 1] < offsets[c]) {
        in_.fail_text_at(cells_at, "CELLS: offsets decrease at cell ", c);
      }
    }
  }

  Index point_index(const std::vector<std::int64_t>& connectivity, std::int64_t at,
                    std::size_t cell, std::size_t cells_at) {
    const std::int64_t v = connectivity[static_cast<std::size_t>(at)];
    if (v < 0 || v >= static_cast<std::int64_t>(mesh_.points.size())) {
      in_.fail_text_at(cells_at, "cell ", cell, ": point index ", v, " out of range [0, ",
                       mesh_.points.size(), ")");
    }
    return static_cast<Index>(v);
  }

  // METADATA blocks (VTK 9) end with an empty line.
  void skip_metadata() {
    in_.rest_of_line();
    while (!in_.at_end()) {
      const std::string_view line = in_.rest_of_line();
      if (line.find_first_not_of(" \t\r") == std::string_view::npos) return;
    }
  }

  // FIELD name n, then n arrays `name components tuples type` with their values.
  void skip_field() {
    in_.token("the field name");
    const std::size_t num_arrays = count_value("the number of field arrays");
    for (std::size_t a = 0; a < num_arrays; ++a) {
      in_.skip_whitespace();
      std::size_t name_at = in_.position();
      std::string_view name = in_.token("a field array name");
      if (iequals(name, "METADATA")) {
        skip_metadata();
        in_.skip_whitespace();
        name_at = in_.position();
        name = in_.token("a field array name");
      }
      if (name == "NULL_ARRAY") continue;
      const std::size_t components = count_value("the number of components");
      const std::size_t tuples = count_value("the number of tuples");
      const ValueType& type = value_type();
      if (tuples != 0 && components > SIZE_MAX / tuples)
        in_.fail_text_at(name_at, "field array too large");
      const std::size_t count = components * tuples;
      if (binary_) {
        begin_array(type, count, "a field array");
        in_.bytes(count * static_cast<std::size_t>(type.bytes), "a field array");
      } else {
        for (std::size_t i = 0; i < count; ++i) in_.token("a field value");
      }
    }
  }

  FileCursor in_;
  bool binary_ = false;
  bool version5_ = false;
  MeshData mesh_;
};

}  // namespace

MeshData read_vtk_legacy(const std::filesystem::path& path) {
  const std::string data = detail::read_file_bytes(path);
  return LegacyReader(data, path.string()).read();
}

MeshData read_vtk_legacy_bytes(std::string_view bytes, const std::string& name) { return LegacyReader(bytes, name).read(); }

}  // namespace fastcorot
