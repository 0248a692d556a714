// VTK XML UnstructuredGrid (.vtu) reader, after "VTK File Formats" (XML formats) and
// vtkXMLDataParser. A DataArray is stored as
//  - format="ascii": whitespace-separated numbers;
//  - format="binary": base64 text inside the element;
//  - format="appended": at byte `offset` after the '_' that opens <AppendedData>, raw bytes
//    (encoding="raw") or base64 text (encoding="base64").
// Binary data is a header of UInt32 or UInt64 integers (header_type) followed by the bytes:
// uncompressed, the header is the byte count; with compressor="vtkZLibDataCompressor" it is
// (number of blocks, block size, size of the last block or 0 when full, compressed size of each
// block) and each block is a zlib stream. VTK base64-encodes header and data either together or
// separately (then the header ends in '=' padding), so base64 is decoded group by group.
// Raw appended bytes are not XML, so the file is split at the '_' marker before parsing.
#include "fastcorot/io/mesh_readers.h"

#include "mesh_reader_support.h"

#include <tinyxml2.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace fastcorot {

namespace {

constexpr std::int64_t kVtkTriangle = 5;
constexpr std::int64_t kVtkTetrahedron = 10;

struct ArrayType {
  std::string_view name;
  int bytes;
  bool integral;
  bool is_signed;
};

constexpr std::array<ArrayType, 10> kArrayTypes = {{{"Int8", 1, true, true},
                                                    {"UInt8", 1, true, false},
                                                    {"Int16", 2, true, true},
                                                    {"UInt16", 2, true, false},
                                                    {"Int32", 4, true, true},
                                                    {"UInt32", 4, true, false},
                                                    {"Int64", 8, true, true},
                                                    {"UInt64", 8, true, false},
                                                    {"Float32", 4, false, true},
                                                    {"Float64", 8, false, true}}};

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

bool is_space(char c) {
  return c == ' ' || c == '\n' || c == '\r' || c == '\t';
}

// The bytes of one binary DataArray: raw bytes, or base64 text decoded on the fly.
class ByteSource {
 public:
  enum class Status { kOk, kEnd, kBadBase64 };

  ByteSource(std::string_view data, bool base64) : data_(data), base64_(base64) {}

  // Appends the next `count` bytes to `out`.
  Status take(std::size_t count, std::string& out) {
    if (!base64_) {
      if (count > data_.size() - pos_) return Status::kEnd;
      out.append(data_.substr(pos_, count));
      pos_ += count;
      return Status::kOk;
    }
    while (count > 0) {
      if (pending_begin_ == pending_size_) {
        const Status status = decode_group();
        if (status != Status::kOk) return status;
      }
      const std::size_t n = std::min(count, pending_size_ - pending_begin_);
      out.append(pending_.data() + pending_begin_, n);
      pending_begin_ += n;
      count -= n;
    }
    return Status::kOk;
  }

  // At least as many bytes as are left (to reject absurd sizes before allocating).
  std::size_t max_left() const {
    const std::size_t left = data_.size() - pos_;
    return base64_ ? left / 4 * 3 + 3 : left;
  }

 private:
  // Four base64 characters (whitespace skipped) → up to three bytes; '=' padding ends a group
  // early, which is how a separately encoded header ends.
  Status decode_group() {
    int values[4];
    int padding = 0;
    for (int i = 0; i < 4; ++i) {
      while (pos_ < data_.size() && is_space(data_[pos_])) ++pos_;
      if (pos_ >= data_.size() || data_[pos_] == '<') return Status::kEnd;
      const char c = data_[pos_++];
      if (c == '=' && i >= 2) {
        ++padding;
        values[i] = 0;
        continue;
      }
      values[i] = base64_value(c);
      if (values[i] < 0 || padding > 0) return Status::kBadBase64;
    }
    const std::uint32_t bits = (static_cast<std::uint32_t>(values[0]) << 18) |
                               (static_cast<std::uint32_t>(values[1]) << 12) |
                               (static_cast<std::uint32_t>(values[2]) << 6) |
                               static_cast<std::uint32_t>(values[3]);
    pending_[0] = static_cast<char>((bits >> 16) & 0xff);
    pending_[1] = static_cast<char>((bits >> 8) & 0xff);
    pending_[2] = static_cast<char>(bits & 0xff);
    pending_begin_ = 0;
    pending_size_ = static_cast<std::size_t>(3 - padding);
    return Status::kOk;
  }

  std::string_view data_;
  bool base64_;
  std::size_t pos_ = 0;
  std::array<char, 3> pending_{};
  std::size_t pending_begin_ = 0;
  std::size_t pending_size_ = 0;
};

class VtuReader {
 public:
  VtuReader(std::string_view data, std::string file) : data_(data), file_(std::move(file)) {}

  MeshData read() {
    parse_xml();
    const tinyxml2::XMLElement* root = doc_.RootElement();
    if (root == nullptr || std::strcmp(root->Name(), "VTKFile") != 0) {
      fail(root, "not a VTK XML file: the root element is not <VTKFile>");
    }
    read_file_attributes(root);
    const tinyxml2::XMLElement* grid = root->FirstChildElement("UnstructuredGrid");
    if (grid == nullptr) fail(root, "no <UnstructuredGrid> element");
    bool any_piece = false;
    for (const tinyxml2::XMLElement* piece = grid->FirstChildElement("Piece"); piece != nullptr;
         piece = piece->NextSiblingElement("Piece")) {
      read_piece(piece);
      any_piece = true;
    }
    if (!any_piece) fail(grid, "no <Piece> element");
    detail::check_mesh_data(mesh_, file_);
    return std::move(mesh_);
  }

 private:
  template <class... Parts>
  [[noreturn]] void fail(const tinyxml2::XMLElement* at, Parts&&... parts) const {
    if (at == nullptr) throw make_error(file_, ": ", std::forward<Parts>(parts)...);
    throw make_error(file_, ":", at->GetLineNum(), ": ", std::forward<Parts>(parts)...);
  }

  // Raw appended data is not XML: parse the part before it, closed by hand.
  void parse_xml() {
    std::string xml;
    const std::size_t tag = data_.find("<AppendedData");
    if (tag == std::string_view::npos) {
      xml = data_;
    } else {
      const std::size_t gt = data_.find('>', tag);
      if (gt == std::string_view::npos) {
        throw make_error(file_, ":", detail::line_number(data_, tag),
                         ": unterminated <AppendedData> tag");
      }
      if (data_[gt - 1] == '/') {  // <AppendedData/>: no data
        xml = data_;
      } else {
        std::size_t underscore = gt + 1;
        while (underscore < data_.size() && is_space(data_[underscore])) ++underscore;
        if (underscore >= data_.size() || data_[underscore] != '_') {
          throw make_error(file_, ":", detail::line_number(data_, underscore),
                           ": <AppendedData> does not start with the '_' marker");
        }
        xml.assign(data_.substr(0, gt + 1));
        xml += "</AppendedData></VTKFile>";
        appended_ = data_.substr(underscore + 1);
        have_appended_ = true;
      }
    }
    if (doc_.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
      throw make_error(file_, ":", doc_.ErrorLineNum(), ": XML error: ", doc_.ErrorStr());
    }
  }

  void read_file_attributes(const tinyxml2::XMLElement* root) {
    const char* type = root->Attribute("type");
    if (type == nullptr || std::strcmp(type, "UnstructuredGrid") != 0) {
      fail(root, "VTKFile type '", type ? type : "", "' is not supported (only UnstructuredGrid)");
    }
    const char* byte_order = root->Attribute("byte_order");
    if (byte_order == nullptr || std::strcmp(byte_order, "LittleEndian") == 0) {
      swap_ = !detail::kHostIsLittleEndian;
    } else if (std::strcmp(byte_order, "BigEndian") == 0) {
      swap_ = detail::kHostIsLittleEndian;
    } else {
      fail(root, "unknown byte_order '", byte_order, "' (expected LittleEndian or BigEndian)");
    }
    const char* header_type = root->Attribute("header_type");
    if (header_type == nullptr || std::strcmp(header_type, "UInt32") == 0) {
      header_bytes_ = 4;
    } else if (std::strcmp(header_type, "UInt64") == 0) {
      header_bytes_ = 8;
    } else {
      fail(root, "unknown header_type '", header_type, "' (expected UInt32 or UInt64)");
    }
    const char* compressor = root->Attribute("compressor");
    if (compressor == nullptr || compressor[0] == '\0') {
      zlib_ = false;
    } else if (std::strcmp(compressor, "vtkZLibDataCompressor") == 0) {
      zlib_ = true;
    } else {
      fail(root, "compressor '", compressor, "' is not supported (only vtkZLibDataCompressor)");
    }
    if (have_appended_) {
      const tinyxml2::XMLElement* appended = root->FirstChildElement("AppendedData");
      const char* encoding = appended ? appended->Attribute("encoding") : nullptr;
      if (encoding == nullptr || std::strcmp(encoding, "raw") == 0) {
        appended_base64_ = false;
      } else if (std::strcmp(encoding, "base64") == 0) {
        appended_base64_ = true;
      } else {
        fail(appended, "unknown AppendedData encoding '", encoding, "' (expected raw or base64)");
      }
    }
  }

  std::size_t count_attribute(const tinyxml2::XMLElement* e, const char* name) const {
    std::int64_t value = 0;
    if (e->QueryInt64Attribute(name, &value) != tinyxml2::XML_SUCCESS) {
      fail(e, "<", e->Name(), "> needs an integer attribute ", name);
    }
    if (value < 0 || value > INT32_MAX) fail(e, "bad ", name, " ", value);
    return static_cast<std::size_t>(value);
  }

  void read_piece(const tinyxml2::XMLElement* piece) {
    const std::size_t num_points = count_attribute(piece, "NumberOfPoints");
    const std::size_t num_cells = count_attribute(piece, "NumberOfCells");
    const std::size_t first_point = mesh_.points.size();
    if (first_point + num_points > static_cast<std::size_t>(INT32_MAX))
      fail(piece, "too many points");

    const tinyxml2::XMLElement* points = piece->FirstChildElement("Points");
    if (num_points > 0) {
      const tinyxml2::XMLElement* array = points ? points->FirstChildElement("DataArray") : nullptr;
      if (array == nullptr) fail(points ? points : piece, "no <Points> <DataArray>");
      const char* components = array->Attribute("NumberOfComponents");
      if (components == nullptr || std::strcmp(components, "3") != 0) {
        fail(array, "points must have NumberOfComponents=\"3\"");
      }
      std::vector<double> xyz;
      read_array(array, 3 * num_points, xyz);
      for (std::size_t i = 0; i < num_points; ++i) {
        mesh_.points.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
      }
    }
    if (num_cells == 0) return;

    const tinyxml2::XMLElement* cells = piece->FirstChildElement("Cells");
    if (cells == nullptr) fail(piece, "no <Cells> element");
    const auto find = [&](const char* name) {
      for (const tinyxml2::XMLElement* a = cells->FirstChildElement("DataArray"); a != nullptr;
           a = a->NextSiblingElement("DataArray")) {
        const char* n = a->Attribute("Name");
        if (n != nullptr && std::strcmp(n, name) == 0) return a;
      }
      fail(cells, "no <DataArray Name=\"", name, "\"> in <Cells>");
    };
    const tinyxml2::XMLElement* offsets_array = find("offsets");
    std::vector<std::int64_t> offsets;
    read_array(offsets_array, num_cells, offsets);
    std::int64_t previous = 0;
    for (std::size_t c = 0; c < num_cells; ++c) {
      if (offsets[c] < previous) fail(offsets_array, "offsets decrease at cell ", c);
      previous = offsets[c];
    }
    if (previous > INT32_MAX) fail(offsets_array, "connectivity too large: ", previous);
    const tinyxml2::XMLElement* connectivity_array = find("connectivity");
    std::vector<std::int64_t> connectivity;
    read_array(connectivity_array, static_cast<std::size_t>(previous), connectivity);
    std::vector<std::int64_t> types;
    read_array(find("types"), num_cells, types);

    const auto index = [&](std::int64_t at, std::size_t cell) {
      const std::int64_t v = connectivity[static_cast<std::size_t>(at)];
      if (v < 0 || static_cast<std::size_t>(v) >= num_points) {
        fail(connectivity_array, "cell ", cell, ": point index ", v, " out of range [0, ",
             num_points, ")");
      }
      return static_cast<Index>(first_point + static_cast<std::size_t>(v));
    };
    for (std::size_t c = 0; c < num_cells; ++c) {
      const std::int64_t begin = c == 0 ? 0 : offsets[c - 1];
      const std::int64_t count = offsets[c] - begin;
      if (types[c] == kVtkTetrahedron) {
        if (count != 4)
          fail(connectivity_array, "cell ", c, ": a tetrahedron (type 10) with ", count, " points");
        mesh_.tetrahedra.push_back(
            {index(begin, c), index(begin + 1, c), index(begin + 2, c), index(begin + 3, c)});
      } else if (types[c] == kVtkTriangle) {
        if (count != 3)
          fail(connectivity_array, "cell ", c, ": a triangle (type 5) with ", count, " points");
        mesh_.triangles.push_back({index(begin, c), index(begin + 1, c), index(begin + 2, c)});
      }
    }
  }

  static std::string array_name(const tinyxml2::XMLElement* array) {
    const char* name = array->Attribute("Name");
    return std::string("DataArray '") + (name ? name : "") + "'";
  }

  // Reads `count` values of a DataArray into `out` (double or std::int64_t).
  template <class Out>
  void read_array(const tinyxml2::XMLElement* array, std::size_t count, std::vector<Out>& out) {
    const char* type_name = array->Attribute("type");
    const ArrayType* type = nullptr;
    for (const ArrayType& t : kArrayTypes) {
      if (type_name != nullptr && t.name == type_name) type = &t;
    }
    if (type == nullptr) {
      fail(array, array_name(array), ": unsupported type '", type_name ? type_name : "",
           "' (supported: Int8 to UInt64, Float32, Float64)");
    }
    if (std::is_integral_v<Out> && !type->integral) {  // points may be stored as integers
      fail(array, array_name(array), ": must hold integers, not ", type->name);
    }
    const char* format = array->Attribute("format");
    if (format == nullptr) fail(array, array_name(array), ": no format attribute");
    out.clear();
    if (std::strcmp(format, "ascii") == 0) {
      read_ascii(array, count, *type, out);
      return;
    }
    std::string bytes;
    if (std::strcmp(format, "binary") == 0) {
      const char* text = array->GetText();
      ByteSource source(text ? std::string_view(text) : std::string_view(), true);
      read_binary(array, source, count * static_cast<std::size_t>(type->bytes), bytes);
    } else if (std::strcmp(format, "appended") == 0) {
      if (!have_appended_)
        fail(array, array_name(array), ": format=\"appended\" but no <AppendedData>");
      std::int64_t offset = 0;
      if (array->QueryInt64Attribute("offset", &offset) != tinyxml2::XML_SUCCESS || offset < 0) {
        fail(array, array_name(array), ": no valid offset attribute");
      }
      if (static_cast<std::uint64_t>(offset) > appended_.size()) {
        fail(array, array_name(array), ": offset ", offset, " lies past the end of the ",
             appended_.size(), " bytes of appended data (truncated file?)");
      }
      ByteSource source(appended_.substr(static_cast<std::size_t>(offset)), appended_base64_);
      read_binary(array, source, count * static_cast<std::size_t>(type->bytes), bytes);
    } else {
      fail(array, array_name(array), ": unknown format '", format,
           "' (expected ascii, binary or appended)");
    }
    out.resize(count);
    const char* p = bytes.data();
    for (std::size_t i = 0; i < count; ++i, p += type->bytes) out[i] = convert<Out>(p, *type);
  }

  template <class Out>
  Out convert(const char* p, const ArrayType& type) const {
    using detail::load_value;
    if (!type.integral) {
      return static_cast<Out>(type.bytes == 4 ? load_value<float>(p, swap_)
                                              : load_value<double>(p, swap_));
    }
    switch (type.bytes) {
      case 1:
        return static_cast<Out>(type.is_signed ? static_cast<int>(static_cast<signed char>(*p))
                                               : static_cast<int>(static_cast<unsigned char>(*p)));
      case 2:
        return static_cast<Out>(
            type.is_signed ? static_cast<std::int64_t>(load_value<std::int16_t>(p, swap_))
                           : static_cast<std::int64_t>(load_value<std::uint16_t>(p, swap_)));
      case 4:
        return static_cast<Out>(
            type.is_signed ? static_cast<std::int64_t>(load_value<std::int32_t>(p, swap_))
                           : static_cast<std::int64_t>(load_value<std::uint32_t>(p, swap_)));
      default: {
        if (type.is_signed) return static_cast<Out>(load_value<std::int64_t>(p, swap_));
        // Values past INT64_MAX become -1: out of range for any index check.
        const std::uint64_t v = load_value<std::uint64_t>(p, swap_);
        return static_cast<Out>(v > static_cast<std::uint64_t>(INT64_MAX)
                                    ? std::int64_t{-1}
                                    : static_cast<std::int64_t>(v));
      }
    }
  }

  template <class Out>
  void read_ascii(const tinyxml2::XMLElement* array, std::size_t count, const ArrayType& type,
                  std::vector<Out>& out) {
    const char* text = array->GetText();
    std::string_view rest = text ? std::string_view(text) : std::string_view();
    out.reserve(std::min(count, rest.size() / 2 + 1));
    while (true) {
      const std::size_t start = rest.find_first_not_of(" \t\r\n");
      if (start == std::string_view::npos) break;
      rest.remove_prefix(start);
      const std::size_t end = std::min(rest.find_first_of(" \t\r\n"), rest.size());
      const std::string_view token = rest.substr(0, end);
      rest.remove_prefix(end);
      if (out.size() == count) {
        fail(array, array_name(array), ": more than the expected ", count, " values");
      }
      std::from_chars_result result{};
      if (type.integral) {
        std::int64_t value = 0;
        result = std::from_chars(token.data(), token.data() + token.size(), value);
        out.push_back(static_cast<Out>(value));
      } else {
        double value = 0;
        result = std::from_chars(token.data(), token.data() + token.size(), value);
        out.push_back(static_cast<Out>(value));
      }
      if (result.ec != std::errc() || result.ptr != token.data() + token.size()) {
        fail(array, array_name(array), ": value ", out.size() - 1, " is not a number of type ",
             type.name, ": '", detail::FileCursor::printable(token), "'");
      }
    }
    if (out.size() != count) {
      fail(array, array_name(array), ": ", out.size(), " values, expected ", count);
    }
  }

  std::uint64_t header_value(const tinyxml2::XMLElement* array, ByteSource& source) {
    std::string bytes;
    take(array, source, static_cast<std::size_t>(header_bytes_), bytes, "header");
    return header_bytes_ == 4 ? detail::load_value<std::uint32_t>(bytes.data(), swap_)
                              : detail::load_value<std::uint64_t>(bytes.data(), swap_);
  }

  void take(const tinyxml2::XMLElement* array, ByteSource& source, std::size_t count,
            std::string& out, const char* what) {
    switch (source.take(count, out)) {
      case ByteSource::Status::kOk:
        return;
      case ByteSource::Status::kEnd:
        fail(array, array_name(array), ": data ends early (truncated ", what, ")");
      case ByteSource::Status::kBadBase64:
        fail(array, array_name(array), ": invalid base64 data");
    }
  }

  // Header and data of a binary array; `expected` is the byte count the attributes imply.
  void read_binary(const tinyxml2::XMLElement* array, ByteSource& source, std::size_t expected,
                   std::string& out) {
    if (!zlib_) {
      const std::uint64_t size = header_value(array, source);
      if (size != expected) {
        fail(array, array_name(array), ": the header gives ", size, " bytes, expected ", expected);
      }
      out.reserve(std::min(expected, source.max_left()));
      take(array, source, expected, out, "data");
      return;
    }
    const std::uint64_t num_blocks = header_value(array, source);
    const std::uint64_t block_size = header_value(array, source);
    const std::uint64_t last_size = header_value(array, source);
    const std::uint64_t full_last = last_size == 0 ? block_size : last_size;
    const bool consistent = num_blocks == 0
                                ? expected == 0
                                : (last_size <= block_size && block_size > 0 &&
                                   num_blocks - 1 <= expected / block_size &&
                                   (num_blocks - 1) * block_size + full_last == expected);
    if (!consistent) {
      fail(array, array_name(array), ": compressed header (", num_blocks, " blocks of ", block_size,
           " bytes, last ", last_size, ") does not give the expected ", expected, " bytes");
    }
    if (num_blocks > source.max_left() / static_cast<std::size_t>(header_bytes_)) {
      fail(array, array_name(array), ": data ends early (truncated header)");
    }
    std::vector<std::uint64_t> compressed_sizes(static_cast<std::size_t>(num_blocks));
    std::uint64_t total_compressed = 0;
    for (auto& size : compressed_sizes) {
      size = header_value(array, source);
      total_compressed += std::min<std::uint64_t>(size, UINT32_MAX);
    }
    if (total_compressed > source.max_left()) {
      fail(array, array_name(array), ": data ends early (truncated data)");
    }
    // zlib expands at most about 1032:1; a larger claim is a corrupt header, not a reason to
    // allocate gigabytes.
    if (expected / 2048 > total_compressed + num_blocks) {
      fail(array, array_name(array), ": ", expected, " bytes cannot come from ", total_compressed,
           " compressed bytes");
    }
    out.resize(expected);
    std::string block;
    for (std::size_t b = 0; b < compressed_sizes.size(); ++b) {
      block.clear();
      take(array, source, static_cast<std::size_t>(compressed_sizes[b]), block, "data");
      const std::uint64_t size = b + 1 == compressed_sizes.size() ? full_last : block_size;
      uLongf produced = static_cast<uLongf>(size);
      const int status = uncompress(reinterpret_cast<Bytef*>(out.data() + b * block_size),
                                    &produced, reinterpret_cast<const Bytef*>(block.data()),
                                    static_cast<uLong>(block.size()));
      if (status != Z_OK || produced != size) {
        fail(array, array_name(array), ": zlib block ", b, " does not decompress to ", size,
             " bytes (", status == Z_OK ? "wrong size" : zError(status), ")");
      }
    }
  }

  std::string_view data_;
  std::string file_;
  tinyxml2::XMLDocument doc_;
  std::string_view appended_;
  bool have_appended_ = false;
  bool appended_base64_ = false;
  bool swap_ = false;
  bool zlib_ = false;
  int header_bytes_ = 4;
  MeshData mesh_;
};

}  // namespace

MeshData read_vtu(const std::filesystem::path& path) {
  const std::string data = detail::read_file_bytes(path);
  return VtuReader(data, path.string()).read();
}

MeshData read_vtu_bytes(std::string_view bytes, const std::string& name) { return VtuReader(bytes, name).read(); }

}  // namespace fastcorot
