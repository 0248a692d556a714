// Gmsh .msh reader, formats 2.2 and 4.1, ASCII and binary, after the format description in the
// Gmsh reference manual (section "MSH file format"). Node tags may be any positive numbers in any
// order (format 4.1 files saved from a physical group keep the model's tags, with gaps); they are
// mapped to 0-based indices in file order. Only 4-node tetrahedra (type 4) and 3-node triangles
// (type 2) are kept; the node counts of the other types below are needed to step over them in
// binary files.
#include "fastcorot/io/mesh_readers.h"

#include "mesh_reader_support.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace fastcorot {

namespace {

using detail::FileCursor;

constexpr int kTriangleType = 2;     // MSH_TRI_3
constexpr int kTetrahedronType = 4;  // MSH_TET_4

// Nodes per element of the Gmsh element types (GmshDefines.h: MSH_LIN_2 = 1 ... MSH_TET_56 = 31,
// MSH_HEX_64 = 92, MSH_HEX_125 = 93); 0 for a type this reader does not know.
int nodes_per_element(std::int64_t type) {
  static constexpr int kCounts[] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                                    8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
  if (type >= 0 && type < static_cast<std::int64_t>(std::size(kCounts))) {
    return kCounts[type];
  }
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}

// Node tag → 0-based index. Tags are usually 1..n, so a dense table serves them; sparse tags far
// beyond the node count go to a hash map.
class NodeTags {
 public:
  void set_expected_count(std::uint64_t count) {
    dense_limit_ = std::min<std::uint64_t>(2 * count + 1024, std::uint64_t{1} << 28);
  }

  // False when the tag is already there.
  bool add(std::uint64_t tag, Index index) {
    if (tag < dense_limit_) {
      if (tag >= dense_.size())
        dense_.resize(std::max<std::size_t>(tag + 1, 2 * dense_.size()), -1);
      if (dense_[tag] >= 0) return false;
      dense_[tag] = index;
      return true;
    }
    return sparse_.emplace(tag, index).second;
  }

  // -1 when the tag is unknown.
  Index find(std::uint64_t tag) const {
    if (tag < dense_.size()) return dense_[tag];
    const auto it = sparse_.find(tag);
    return it == sparse_.end() ? -1 : it->second;
  }

 private:
  std::uint64_t dense_limit_ = 1024;
  std::vector<Index> dense_;
  std::unordered_map<std::uint64_t, Index> sparse_;
};

class GmshReader {
 public:
  GmshReader(std::string_view data, std::string file) : in_(data, std::move(file)) {}

  MeshData read() {
    read_format();
    while (in_.skip_whitespace()) {
      const std::size_t section_start = in_.position();
      const std::string_view section = in_.token("a section");
      if (section.size() < 2 || section.front() != '$') {
        in_.set_position(section_start);
        in_.fail_text("expected a section ($Nodes, $Elements, ...), found '",
                      FileCursor::printable(section), "'");
      }
      if (major_ == 1 && (section == "$NOD" || section == "$NOE")) {
        if (have_nodes_) in_.fail_text("a second $NOD section");
        read_nodes_v2();
        have_nodes_ = true;
        in_.expect(section == "$NOD" ? "$ENDNOD" : "$ENDNOE");
      } else if (major_ == 1 && section == "$ELM") {
        if (!have_nodes_) in_.fail_text("$ELM before $NOD");
        read_elements_v1();
        in_.expect("$ENDELM");
      } else if (major_ == 1 && section.front() == '$') {
        in_.set_position(section_start);
        in_.fail_text("unknown section ", FileCursor::printable(section), " in a Gmsh format 1 file");
      } else if (section == "$Nodes") {
        if (have_nodes_) in_.fail_text("a second $Nodes section");
        major_ == 2 ? read_nodes_v2() : read_nodes_v4();
        have_nodes_ = true;
        in_.expect("$EndNodes");
      } else if (section == "$Elements") {
        if (!have_nodes_) in_.fail_text("$Elements before $Nodes");
        major_ == 2 ? read_elements_v2() : read_elements_v4();
        in_.expect("$EndElements");
      } else if (section == "$Entities" && major_ == 4 && binary_) {
        skip_entities_binary();
        in_.expect("$EndEntities");
      } else {
        // $PhysicalNames, $Entities (ASCII), $Periodic, $NodeData, ...: not needed here.
        const std::string end = "$End" + std::string(section.substr(1));
        if (!in_.skip_past(end)) {
          in_.set_position(section_start);
          in_.fail_text("section ", FileCursor::printable(section), " has no ",
                        FileCursor::printable(end));
        }
      }
    }
    if (!have_nodes_) in_.fail_text("no $Nodes section");
    detail::check_mesh_data(mesh_, in_.file());
    return std::move(mesh_);
  }

 private:
  void read_format() {
    const std::size_t start = (in_.skip_whitespace(), in_.position());
    const std::string_view magic = in_.token("$MeshFormat");
    if (magic == "$NOD" || magic == "$NOE") {
      // Format 1 (Gmsh 1, most of SOFA's own meshes): no header; $NOD and $ELM sections.
      major_ = 1;
      in_.set_position(start);
      return;
    }
    if (magic != "$MeshFormat") {
      in_.set_position(0);
      in_.fail_text("not a Gmsh mesh file: expected '$MeshFormat', found '",
                    FileCursor::printable(magic), "'");
    }
    in_.skip_whitespace();
    const std::size_t version_start = in_.position();
    const std::string_view version = in_.token("the format version");
    if (version == "2.2" || version == "2.1" || version == "2.0" || version == "2") {
      major_ = 2;
    } else if (version == "4.1") {
      major_ = 4;
    } else {
      in_.set_position(version_start);
      in_.fail_text("unsupported Gmsh format version '", FileCursor::printable(version),
                    "' (supported: 2.2 and 4.1, ASCII or binary)");
    }
    const int file_type = in_.integer<int>("the file type");
    if (file_type != 0 && file_type != 1) {
      in_.fail_text("file type ", file_type, " is neither 0 (ASCII) nor 1 (binary)");
    }
    binary_ = file_type == 1;
    const int data_size = in_.integer<int>("the data size");
    // Format 2 gives sizeof(double); format 4 gives sizeof(size_t), the size of tags and counts.
    if (major_ == 2 ? data_size != 8 : (data_size != 8 && data_size != 4)) {
      in_.fail_text("unsupported data size ", data_size,
                    major_ == 2 ? " (must be 8)" : " (must be 4 or 8)");
    }
    size_t_bytes_ = data_size;
    if (binary_) {
      in_.rest_of_line();
      const auto one = in_.binary<std::int32_t>(false, "the endianness check");
      if (one == 1) {
        swap_ = false;
      } else if (one == detail::byteswap_value<std::int32_t>(1)) {
        swap_ = true;
      } else {
        in_.fail_binary("bad endianness check: expected the integer 1, found ", one);
      }
    }
    in_.expect("$EndMeshFormat");
  }

  // --- format 2 ----------------------------------------------------------------------------

  void read_nodes_v2() {
    const auto count = in_.integer<std::int64_t>("the node count");
    if (detail::to_index(count) < 0) in_.fail_text("bad node count ", count);
    check_node_count(static_cast<std::uint64_t>(count));
    tags_.set_expected_count(static_cast<std::uint64_t>(count));
    mesh_.points.reserve(
        std::min<std::size_t>(static_cast<std::size_t>(count), in_.remaining() / 8));
    if (binary_) in_.rest_of_line();
    for (std::int64_t i = 0; i < count; ++i) {
      std::int64_t tag = 0;
      Vec3<double> x;
      if (binary_) {
        tag = in_.binary<std::int32_t>(swap_, "a node tag");
        for (int k = 0; k < 3; ++k) x[k] = in_.binary<double>(swap_, "a node coordinate");
      } else {
        tag = in_.integer<std::int64_t>("a node tag");
        for (int k = 0; k < 3; ++k) x[k] = in_.real("a node coordinate");
      }
      add_node(tag, x);
    }
  }

  void read_elements_v2() {
    const auto count = in_.integer<std::int64_t>("the element count");
    if (count < 0) in_.fail_text("bad element count ", count);
    std::vector<std::uint64_t> nodes;
    if (!binary_) {
      for (std::int64_t e = 0; e < count; ++e) {
        const auto tag = in_.integer<std::int64_t>("an element tag");
        const auto type = in_.integer<std::int64_t>("an element type");
        const auto num_tags = in_.integer<std::int64_t>("the number of element tags");
        if (num_tags < 0) in_.fail_text("element ", tag, ": bad number of tags ", num_tags);
        const int k = nodes_per_element(type);
        if (k == 0) {  // unknown type: the line ends the element
          in_.rest_of_line();
          continue;
        }
        for (std::int64_t i = 0; i < num_tags; ++i) in_.integer<std::int64_t>("an element tag");
        nodes.resize(static_cast<std::size_t>(k));
        for (auto& n : nodes) n = node_tag(in_.integer<std::int64_t>("an element node"), tag);
        add_element(type, nodes, tag);
      }
      return;
    }
    in_.rest_of_line();
    std::int64_t done = 0;
    while (done < count) {
      const auto type = in_.binary<std::int32_t>(swap_, "an element type");
      const auto follow = in_.binary<std::int32_t>(swap_, "an element count");
      const auto num_tags = in_.binary<std::int32_t>(swap_, "the number of element tags");
      const int k = nodes_per_element(type);
      if (k == 0) in_.fail_binary("unknown element type ", type, " (cannot step over it)");
      if (follow < 0 || follow > count - done || num_tags < 0) {
        in_.fail_binary("bad element block header (type ", type, ", ", follow, " elements, ",
                        num_tags, " tags)");
      }
      nodes.resize(static_cast<std::size_t>(k));
      for (std::int32_t e = 0; e < follow; ++e) {
        const auto tag = in_.binary<std::int32_t>(swap_, "an element tag");
        in_.bytes(4 * static_cast<std::size_t>(num_tags), "the element tags");
        for (auto& n : nodes) n = node_tag(in_.binary<std::int32_t>(swap_, "an element node"), tag);
        add_element(type, nodes, tag);
      }
      done += follow;
    }
  }

  // --- format 1 -----------------------------------------------------------------------------

  // Each element: number, type, physical region, elementary region, node count, nodes.
  void read_elements_v1() {
    const auto count = in_.integer<std::int64_t>("the element count");
    if (count < 0) in_.fail_text("bad element count ", count);
    std::vector<std::uint64_t> nodes;
    for (std::int64_t e = 0; e < count; ++e) {
      const auto tag = in_.integer<std::int64_t>("an element number");
      const auto type = in_.integer<std::int64_t>("an element type");
      in_.integer<std::int64_t>("a physical region");
      in_.integer<std::int64_t>("an elementary region");
      const auto num_nodes = in_.integer<std::int64_t>("the element's node count");
      const int k = nodes_per_element(type);
      if (k != 0 && num_nodes != k) {
        in_.fail_text("element ", tag, " of type ", type, " has ", num_nodes, " nodes; expected ", k);
      }
      if (num_nodes < 0 || num_nodes > 1000) in_.fail_text("element ", tag, ": bad node count ", num_nodes);
      nodes.resize(static_cast<std::size_t>(num_nodes));
      for (auto& n : nodes) n = node_tag(in_.integer<std::int64_t>("an element node"), tag);
      if (k != 0) add_element(type, nodes, tag);
    }
  }

  // --- format 4.1 --------------------------------------------------------------------------

  std::uint64_t size_value(std::string_view what) {
    if (!binary_) {
      const auto value = in_.integer<std::int64_t>(what);
      if (value < 0) in_.fail_text("negative ", what, " ", value);
      return static_cast<std::uint64_t>(value);
    }
    return size_t_bytes_ == 8 ? in_.binary<std::uint64_t>(swap_, what)
                              : in_.binary<std::uint32_t>(swap_, what);
  }

  int int_value(std::string_view what) {
    return binary_ ? in_.binary<std::int32_t>(swap_, what) : in_.integer<int>(what);
  }

  double real_value(std::string_view what) {
    return binary_ ? in_.binary<double>(swap_, what) : in_.real(what);
  }

  [[noreturn]] void fail(const std::string& message) {
    if (binary_) in_.fail_binary(message);
    in_.fail_text(message);
  }

  void read_nodes_v4() {
    if (binary_) in_.rest_of_line();
    const std::uint64_t num_blocks = size_value("the number of node blocks");
    const std::uint64_t count = size_value("the node count");
    size_value("the smallest node tag");
    size_value("the largest node tag");
    if (count > static_cast<std::uint64_t>(INT32_MAX))
      fail("bad node count " + std::to_string(count));
    check_node_count(count);
    tags_.set_expected_count(count);
    mesh_.points.reserve(std::min<std::size_t>(count, in_.remaining() / 8));
    std::vector<std::uint64_t> block_tags;
    for (std::uint64_t b = 0; b < num_blocks; ++b) {
      const int dim = int_value("the entity dimension");
      int_value("the entity tag");
      const int parametric = int_value("the parametric flag");
      const std::uint64_t n = size_value("the number of nodes in the block");
      if (dim < 0 || dim > 3 || (parametric != 0 && parametric != 1)) {
        fail("bad node block header (dimension " + std::to_string(dim) + ", parametric " +
             std::to_string(parametric) + ")");
      }
      if (n > count - mesh_.points.size())
        fail("node blocks hold more nodes than the header's count");
      if (n > in_.remaining() / 2)
        fail("a node block of " + std::to_string(n) + " nodes is larger than the file");
      const int extra = parametric ? dim : 0;  // u, (u v) or (u v w) after x y z
      block_tags.resize(static_cast<std::size_t>(n));
      for (auto& tag : block_tags) tag = size_value("a node tag");
      for (const std::uint64_t tag : block_tags) {
        Vec3<double> x;
        for (int k = 0; k < 3; ++k) x[k] = real_value("a node coordinate");
        for (int k = 0; k < extra; ++k) real_value("a parametric coordinate");
        add_node(tag, x);
      }
    }
    if (mesh_.points.size() != count)
      fail("the node blocks hold fewer nodes than the header's count");
  }

  void read_elements_v4() {
    if (binary_) in_.rest_of_line();
    const std::uint64_t num_blocks = size_value("the number of element blocks");
    const std::uint64_t count = size_value("the element count");
    size_value("the smallest element tag");
    size_value("the largest element tag");
    std::uint64_t done = 0;
    std::vector<std::uint64_t> nodes;
    for (std::uint64_t b = 0; b < num_blocks; ++b) {
      int_value("the entity dimension");
      int_value("the entity tag");
      const int type = int_value("the element type");
      const std::uint64_t n = size_value("the number of elements in the block");
      if (n > count - done) fail("element blocks hold more elements than the header's count");
      done += n;
      const int k = nodes_per_element(type);
      if (k == 0) {
        if (binary_)
          fail("unknown element type " + std::to_string(type) + " (cannot step over it)");
        for (std::uint64_t e = 0; e < n; ++e) {  // one element per line
          in_.skip_whitespace();
          in_.rest_of_line();
        }
        continue;
      }
      nodes.resize(static_cast<std::size_t>(k));
      for (std::uint64_t e = 0; e < n; ++e) {
        const std::uint64_t tag = size_value("an element tag");
        for (auto& node : nodes) node = size_value("an element node");
        add_element(type, nodes, static_cast<std::int64_t>(tag));
      }
    }
    if (done != count) fail("the element blocks hold fewer elements than the header's count");
  }

  // Binary $Entities: points (tag, x y z, physical tags), then curves, surfaces and volumes (tag,
  // bounding box, physical tags, bounding entities).
  void skip_entities_binary() {
    in_.rest_of_line();
    std::uint64_t counts[4];
    for (auto& c : counts) c = size_value("an entity count");
    for (int dim = 0; dim < 4; ++dim) {
      for (std::uint64_t e = 0; e < counts[dim]; ++e) {
        in_.bytes(4 + (dim == 0 ? 3 : 6) * 8, "an entity");
        const std::uint64_t num_physical = size_value("the number of physical tags");
        if (num_physical > in_.remaining() / 4) fail("bad number of physical tags");
        in_.bytes(4 * num_physical, "the physical tags");
        if (dim > 0) {
          const std::uint64_t num_bounding = size_value("the number of bounding entities");
          if (num_bounding > in_.remaining() / 4) fail("bad number of bounding entities");
          in_.bytes(4 * num_bounding, "the bounding entities");
        }
      }
    }
  }

  // --- shared ------------------------------------------------------------------------------

  // Every node takes at least 8 bytes ("1 0 0 0" and a line break); a larger count is a corrupt
  // header, refused before anything is allocated for it.
  void check_node_count(std::uint64_t count) {
    if (count > in_.remaining() / 8) {
      fail("node count " + std::to_string(count) + " is larger than the file can hold");
    }
  }

  void add_node(std::int64_t tag, const Vec3<double>& x) {
    if (tag < 0) fail("negative node tag " + std::to_string(tag));
    add_node(static_cast<std::uint64_t>(tag), x);
  }

  void add_node(std::uint64_t tag, const Vec3<double>& x) {
    if (!tags_.add(tag, static_cast<Index>(mesh_.points.size()))) {
      fail("node tag " + std::to_string(tag) + " appears twice");
    }
    mesh_.points.push_back(x);
  }

  std::uint64_t node_tag(std::int64_t tag, std::int64_t element) {
    if (tag < 0) {
      fail("element " + std::to_string(element) + ": negative node tag " + std::to_string(tag));
    }
    return static_cast<std::uint64_t>(tag);
  }

  Index node_index(std::uint64_t tag, std::int64_t element) {
    const Index index = tags_.find(tag);
    if (index < 0) {
      fail("element " + std::to_string(element) + " uses node tag " + std::to_string(tag) +
           ", which is not in $Nodes");
    }
    return index;
  }

  void add_element(std::int64_t type, const std::vector<std::uint64_t>& nodes, std::int64_t tag) {
    if (type == kTetrahedronType) {
      mesh_.tetrahedra.push_back({node_index(nodes[0], tag), node_index(nodes[1], tag),
                                  node_index(nodes[2], tag), node_index(nodes[3], tag)});
    } else if (type == kTriangleType) {
      mesh_.triangles.push_back(
          {node_index(nodes[0], tag), node_index(nodes[1], tag), node_index(nodes[2], tag)});
    }
  }

  FileCursor in_;
  int major_ = 0;
  bool binary_ = false;
  bool swap_ = false;
  int size_t_bytes_ = 8;
  bool have_nodes_ = false;
  NodeTags tags_;
  MeshData mesh_;
};

}  // namespace

MeshData read_gmsh(const std::filesystem::path& path) {
  const std::string data = detail::read_file_bytes(path);
  return GmshReader(data, path.string()).read();
}

MeshData read_gmsh_bytes(std::string_view bytes, const std::string& name) { return GmshReader(bytes, name).read(); }

}  // namespace fastcorot
