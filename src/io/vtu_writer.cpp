// VTK XML writers: an UnstructuredGrid (.vtu) with every DataArray inline as format="binary"
// (base64 of a UInt32 byte count followed by the little-endian data, uncompressed: what VTK
// itself writes for an uncompressed inline array), and a ParaView collection (.pvd) that lists
// the files of a time series. Both are written atomically (atomic_file.h): a reader never sees
// half a file.
#include "fastcorot/io/vtu_writer.h"

#include "fastcorot/io/atomic_file.h"

#include "mesh_reader_support.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

namespace {

constexpr std::string_view kBase64Alphabet =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string base64_encode(std::string_view bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t bits =
        (static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16) |
        (static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8) |
        static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 2]));
    out += kBase64Alphabet[(bits >> 18) & 63];
    out += kBase64Alphabet[(bits >> 12) & 63];
    out += kBase64Alphabet[(bits >> 6) & 63];
    out += kBase64Alphabet[bits & 63];
  }
  if (i < bytes.size()) {
    std::uint32_t bits = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size())
      bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    out += kBase64Alphabet[(bits >> 18) & 63];
    out += kBase64Alphabet[(bits >> 12) & 63];
    out += i + 1 < bytes.size() ? kBase64Alphabet[(bits >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// Appends `value` little-endian.
template <class T>
void append_little_endian(std::string& out, T value) {
  if constexpr (!detail::kHostIsLittleEndian) value = detail::byteswap_value(value);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

std::string xml_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// The shortest text that reads back as the same double.
std::string shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

class DataArrayWriter {
 public:
  DataArrayWriter(std::ostream& out, std::string file) : out_(out), file_(std::move(file)) {}

  // `data` holds the little-endian values; the UInt32 header is their byte count.
  void write(std::string_view indent, std::string_view type, std::string_view name, int components,
             std::string_view data) {
    if (data.size() > UINT32_MAX) {
      throw make_error(file_, ": DataArray '", name, "' has ", data.size(),
                       " bytes, more than a UInt32 header can count");
    }
    std::string bytes;
    bytes.reserve(4 + data.size());
    append_little_endian(bytes, static_cast<std::uint32_t>(data.size()));
    bytes.append(data);
    out_ << indent << "<DataArray type=\"" << type << "\" Name=\"" << xml_escape(name) << '"';
    if (components != 1) out_ << " NumberOfComponents=\"" << components << '"';
    out_ << " format=\"binary\">\n"
         << indent << "  " << base64_encode(bytes) << '\n'
         << indent << "</DataArray>\n";
  }

 private:
  std::ostream& out_;
  std::string file_;
};

std::string doubles_bytes(const double* values, std::size_t count) {
  std::string bytes;
  bytes.reserve(8 * count);
  for (std::size_t i = 0; i < count; ++i) append_little_endian(bytes, values[i]);
  return bytes;
}

void check_fields(const std::string& file, const std::vector<VtuField>& fields, std::size_t count,
                  const char* kind) {
  for (const VtuField& field : fields) {
    if (field.name.empty()) throw make_error(file, ": a ", kind, " field has no name");
    if (field.components != 1 && field.components != 3 && field.components != 4) {
      throw make_error(file, ": ", kind, " field '", field.name, "' has ", field.components,
                       " components (must be 1, 3 or 4)");
    }
    if (field.values.size() != count * static_cast<std::size_t>(field.components)) {
      throw make_error(file, ": ", kind, " field '", field.name, "' has ", field.values.size(),
                       " values, expected ", count, " × ", field.components);
    }
  }
}

}  // namespace

VtuCellBlock tetrahedron_cells(std::span<const Tetrahedron> tetrahedra) {
  VtuCellBlock block;
  block.connectivity.reserve(4 * tetrahedra.size());
  for (const auto& t : tetrahedra) block.connectivity.insert(block.connectivity.end(), t.begin(), t.end());
  return block;
}

void write_vtu(const std::filesystem::path& path, const std::vector<Vec3<double>>& points,
               const std::vector<VtuCellBlock>& cells, const std::vector<VtuField>& point_fields,
               const std::vector<VtuField>& cell_fields) {
  const std::string file = path.string();
  std::size_t num_cells = 0;
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const VtuCellBlock& block = cells[b];
    if (block.nodes_per_cell <= 0 || block.vtk_cell_type < 1 || block.vtk_cell_type > 255) {
      throw make_error(file, ": cell block ", b, ": bad cell type ", block.vtk_cell_type,
                       " or nodes per cell ", block.nodes_per_cell);
    }
    if (block.connectivity.size() % static_cast<std::size_t>(block.nodes_per_cell) != 0) {
      throw make_error(file, ": cell block ", b, ": ", block.connectivity.size(),
                       " indices is not a multiple of ", block.nodes_per_cell, " nodes per cell");
    }
    for (std::size_t i = 0; i < block.connectivity.size(); ++i) {
      const Index v = block.connectivity[i];
      if (v < 0 || static_cast<std::size_t>(v) >= points.size()) {
        throw make_error(file, ": cell block ", b, ": cell ",
                         i / static_cast<std::size_t>(block.nodes_per_cell), ": point index ", v,
                         " out of range [0, ", points.size(), ")");
      }
    }
    num_cells += block.connectivity.size() / static_cast<std::size_t>(block.nodes_per_cell);
  }
  check_fields(file, point_fields, points.size(), "point");
  check_fields(file, cell_fields, num_cells, "cell");

  std::ostringstream out;  // the file is written whole once complete (atomic_file.h)
  DataArrayWriter arrays(out, file);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt32\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << points.size() << "\" NumberOfCells=\"" << num_cells
      << "\">\n";
  const auto write_fields = [&](const char* tag, const std::vector<VtuField>& fields) {
    if (fields.empty()) return;
    out << "      <" << tag << ">\n";
    for (const VtuField& field : fields) {
      arrays.write("        ", "Float64", field.name, field.components,
                   doubles_bytes(field.values.data(), field.values.size()));
    }
    out << "      </" << tag << ">\n";
  };
  write_fields("PointData", point_fields);
  write_fields("CellData", cell_fields);

  out << "      <Points>\n";
  arrays.write("        ", "Float64", "Points", 3,
               doubles_bytes(points.empty() ? nullptr : points.front().data(), 3 * points.size()));
  out << "      </Points>\n";

  std::string connectivity;
  std::string offsets;
  std::string types;
  std::int64_t end = 0;
  for (const VtuCellBlock& block : cells) {
    for (const Index v : block.connectivity)
      append_little_endian(connectivity, static_cast<std::int64_t>(v));
    const std::size_t n =
        block.connectivity.size() / static_cast<std::size_t>(block.nodes_per_cell);
    for (std::size_t c = 0; c < n; ++c) {
      end += block.nodes_per_cell;
      append_little_endian(offsets, end);
      types += static_cast<char>(static_cast<std::uint8_t>(block.vtk_cell_type));
    }
  }
  out << "      <Cells>\n";
  arrays.write("        ", "Int64", "connectivity", 1, connectivity);
  arrays.write("        ", "Int64", "offsets", 1, offsets);
  arrays.write("        ", "UInt8", "types", 1, types);
  out << "      </Cells>\n"
      << "    </Piece>\n"
      << "  </UnstructuredGrid>\n"
      << "</VTKFile>\n";
  write_stream_atomically(path, [&](std::ostream& file_out) { file_out << out.view(); });
}

void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& time_steps) {
  const std::string file = path.string();
  for (std::size_t i = 0; i < time_steps.size(); ++i) {
    if (!std::isfinite(time_steps[i].first)) {
      throw make_error(file, ": time step ", i, " ('", time_steps[i].second, "') has time ",
                       time_steps[i].first);
    }
  }
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const auto& [time, name] : time_steps) {
    out << "    <DataSet timestep=\"" << shortest(time) << "\" group=\"\" part=\"0\" file=\""
        << xml_escape(name) << "\"/>\n";
  }
  out << "  </Collection>\n"
      << "</VTKFile>\n";
  write_stream_atomically(path, [&](std::ostream& file_out) { file_out << out.view(); });
}

void write_rigid_frames_vtu(const std::filesystem::path& path, const RigidBlocks<double>& rigids,
                            std::span<const Vec3<double>> x, std::span<const Vec3<double>> v,
                            std::span<const Vec3<double>> f) {
  std::vector<Vec3<double>> centres;
  VtuCellBlock vertices{1, 1, {}};
  VtuField orientation{"orientation", 4, {}}, axis_x{"axis_x", 3, {}}, axis_y{"axis_y", 3, {}}, axis_z{"axis_z", 3, {}};
  VtuField velocity{"velocity", 3, {}}, angular{"angular_velocity", 3, {}}, force{"force", 3, {}}, torque{"torque", 3, {}};
  const auto add = [](VtuField& field, const Vec3<double>& value) { field.values.insert(field.values.end(), {value.x(), value.y(), value.z()}); };
  for (std::size_t k = 0; k < rigids.size(); ++k) {
    const RigidCoord<double> c = rigids.coord(x, k);
    const auto b = static_cast<std::size_t>(rigids.block[k]);
    vertices.connectivity.push_back(static_cast<Index>(k));
    centres.push_back(c.center);
    for (int i = 0; i < 4; ++i) orientation.values.push_back(c.orientation.coeffs()[i]);
    add(axis_x, c.rotate(Vec3<double>::UnitX()));
    add(axis_y, c.rotate(Vec3<double>::UnitY()));
    add(axis_z, c.rotate(Vec3<double>::UnitZ()));
    add(velocity, v[b]);
    add(angular, v[b + 1]);
    add(force, f[b]);
    add(torque, f[b + 1]);
  }
  write_vtu(path, centres, {vertices}, {orientation, axis_x, axis_y, axis_z, velocity, angular, force, torque});
}

}  // namespace fastcorot
