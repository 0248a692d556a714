// Tests of the Gmsh .msh reader on files gmsh 4.8.4 wrote (tests/data/meshes, see its README.md
// for the commands) and on small hand-written files: values read from the file text by eye,
// agreement of formats 2.2 / 4.1, ASCII / binary, non-contiguous node tags, both byte orders,
// skipped element types, and an error naming the file and line for each kind of bad input.
#include "fastcorot/io/mesh_readers.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace fastcorot {
namespace {

std::filesystem::path mesh_path(const std::string& name) {
  return std::filesystem::path(FASTCOROT_TEST_DATA_DIR) / "meshes" / name;
}

// Writes `contents` to a file of this test's own temporary folder.
std::filesystem::path write_temp(const std::string& name, std::string_view contents) {
  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   ("fastcorot_gmsh_" +
                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

// The message of the fastcorot::Error that reading `contents` as a .msh file throws.
std::string read_error(std::string_view contents) {
  const auto path = write_temp("bad.msh", contents);
  try {
    read_gmsh(path);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    return message;
  }
  ADD_FAILURE() << "no error for:\n" << contents;
  return {};
}

bool contains(const std::string& text, std::string_view part) {
  return text.find(part) != std::string::npos;
}

TEST(GmshReader, BoxV22AsciiValuesReadFromTheFileByEye) {
  const MeshData mesh = read_gmsh(mesh_path("box_gmsh_v22_ascii.msh"));
  // $Nodes: "44", then "1 0 0 0.5", "2 0 0 0", "3 0 0.5 0.5", "4 0 0.5 0", "5 1 0 0.5".
  ASSERT_EQ(mesh.points.size(), 44u);
  EXPECT_EQ(mesh.points[0], Vec3<double>(0, 0, 0.5));
  EXPECT_EQ(mesh.points[1], Vec3<double>(0, 0, 0));
  EXPECT_EQ(mesh.points[2], Vec3<double>(0, 0.5, 0.5));
  EXPECT_EQ(mesh.points[4], Vec3<double>(1, 0, 0.5));
  // $Elements: 210 = 8 points (type 15) + 28 lines (1) + 84 triangles (2) + 90 tetrahedra (4).
  ASSERT_EQ(mesh.tetrahedra.size(), 90u);
  ASSERT_EQ(mesh.triangles.size(), 84u);
  // "121 4 2 0 1 33 43 36 42", "122 4 2 0 1 36 33 35 39", last "210 4 2 0 1 39 35 38 41".
  EXPECT_EQ(mesh.tetrahedra[0], (Tetrahedron{32, 42, 35, 41}));
  EXPECT_EQ(mesh.tetrahedra[1], (Tetrahedron{35, 32, 34, 38}));
  EXPECT_EQ(mesh.tetrahedra[89], (Tetrahedron{38, 34, 37, 40}));
  // "37 2 2 0 1 9 1 25"
  EXPECT_EQ(mesh.triangles[0], (Triangle{8, 0, 24}));
}

TEST(GmshReader, FormatsV22AndV41AsciiAndBinaryAgree) {
  const MeshData reference = read_gmsh(mesh_path("box_gmsh_v41_binary.msh"));
  for (const char* name : {"box_gmsh_v22_ascii.msh", "box_gmsh_v22_binary.msh",
                           "box_gmsh_v41_ascii.msh", "box_gmsh_v41_parametric.msh"}) {
    SCOPED_TRACE(name);
    const MeshData mesh = read_gmsh(mesh_path(name));
    ASSERT_EQ(mesh.points.size(), reference.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
      // gmsh writes ASCII coordinates with 16 significant digits.
      EXPECT_LE((mesh.points[i] - reference.points[i]).norm(), 1e-15) << "point " << i;
    }
    EXPECT_EQ(mesh.tetrahedra, reference.tetrahedra);
    EXPECT_EQ(mesh.triangles, reference.triangles);
  }
}

TEST(GmshReader, NonContiguousNodeTagsMapToFileOrder) {
  // part_gmsh_v41_*.msh keep the whole model's node tags (5..88, with gaps: the first node
  // block reads "0 5 0 1" / "5" / "0.5 0 0"); gmsh renumbers them 1..45 in the 2.2 file, in the
  // same order, so both must give the same mesh.
  const MeshData renumbered = read_gmsh(mesh_path("part_gmsh_v22_ascii.msh"));
  ASSERT_EQ(renumbered.points.size(), 45u);
  ASSERT_EQ(renumbered.tetrahedra.size(), 100u);
  EXPECT_EQ(renumbered.points[0], Vec3<double>(0.5, 0, 0));
  for (const char* name : {"part_gmsh_v41_ascii.msh", "part_gmsh_v41_binary.msh"}) {
    SCOPED_TRACE(name);
    const MeshData mesh = read_gmsh(mesh_path(name));
    ASSERT_EQ(mesh.points.size(), renumbered.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
      EXPECT_LE((mesh.points[i] - renumbered.points[i]).norm(), 1e-15) << "point " << i;
    }
    EXPECT_EQ(mesh.tetrahedra, renumbered.tetrahedra);
    EXPECT_TRUE(mesh.triangles.empty());
  }
}

TEST(GmshReader, HandWrittenV41WithUnorderedTagsAndSkippedTypes) {
  const MeshData mesh = read_gmsh(write_temp("tags.msh", R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
1
3 1 "solid"
$EndPhysicalNames
$Entities
0 0 0 1
1 0 0 0 1 1 1 1 1 0
$EndEntities
$Nodes
2 5 7 700
3 1 0 3
700
7
30
0 0 0
1 0 0
0 1 0
2 1 1 2
45
8
0 0 1 0.1 0.2
2 2 2 0.3 0.4
$EndNodes
$Elements
3 4 1 4
3 1 4 2
1 30 7 700 45
2 7 700 8 45
2 1 2 1
3 30 7 700
3 1 11 1
4 30 7 700 45 8 8 8 8 8 8
$EndElements
)"));
  ASSERT_EQ(mesh.points.size(), 5u);
  EXPECT_EQ(mesh.points[0], Vec3<double>(0, 0, 0));  // tag 700
  EXPECT_EQ(mesh.points[3], Vec3<double>(0, 0, 1));  // tag 45, parametric (u, v) skipped
  EXPECT_EQ(mesh.points[4], Vec3<double>(2, 2, 2));  // tag 8
  ASSERT_EQ(mesh.tetrahedra.size(), 2u);
  EXPECT_EQ(mesh.tetrahedra[0], (Tetrahedron{2, 1, 0, 3}));
  EXPECT_EQ(mesh.tetrahedra[1], (Tetrahedron{1, 0, 4, 3}));
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangles[0], (Triangle{2, 1, 0}));  // the 10-node tetrahedron is skipped
}

TEST(GmshReader, HandWrittenV22SkipsPointsLinesAndSecondOrderElements) {
  const MeshData mesh = read_gmsh(write_temp("v22.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
7 0 0 0
3 1 0 0
100 0 1 0
42 0 0 1
$EndNodes
$Elements
5
1 15 2 0 1 7
2 1 2 0 1 7 3
3 2 2 0 1 7 3 100
4 4 3 0 1 5 7 3 100 42
5 11 2 0 1 7 3 100 42 7 3 100 42 7 3
$EndElements
)"));
  ASSERT_EQ(mesh.points.size(), 4u);
  EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{0, 1, 2, 3}}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}}));
}

template <class T>
void append(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  out.append(bytes, sizeof(T));
}

// A binary 2.2 file: four nodes (tags 10, 20, 30, 40), a point element and a tetrahedron.
std::string binary_v22(bool big_endian, std::int32_t one = 1) {
  std::string s = "$MeshFormat\n2.2 1 8\n";
  append<std::int32_t>(s, one, big_endian);
  s += "\n$EndMeshFormat\n$Nodes\n4\n";
  const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 4; ++i) {
    append<std::int32_t>(s, 10 * (i + 1), big_endian);
    for (const double x : xyz[i]) append(s, x, big_endian);
  }
  s += "\n$EndNodes\n$Elements\n2\n";
  for (const std::int32_t v : {15, 1, 2, /*element*/ 1, 0, 0, 30}) append(s, v, big_endian);
  for (const std::int32_t v : {4, 1, 2, /*element*/ 2, 0, 0, 40, 30, 20, 10})
    append(s, v, big_endian);
  s += "\n$EndElements\n";
  return s;
}

TEST(GmshReader, Format1AsSofasOwnMeshesUseIt) {
  // Gmsh 1 (no header; $NOD, $ELM: number, type, physical and elementary region, node count,
  // nodes), values by eye: tags 10, 20, 30, 40, 50; a line (type 1) skipped, a triangle kept.
  const MeshData mesh = read_gmsh_bytes(R"($NOD
5
10 0 0 0
20 1 0 0
30 0 1 0
40 0 0 1
50 1 1 1
$ENDNOD
$ELM
4
1 1 0 1 2 10 20
2 2 0 1 3 10 20 30
3 4 0 1 4 10 20 30 40
4 4 0 1 4 20 30 40 50
$ENDELM
)",
                                        "v1.msh");
  ASSERT_EQ(mesh.points.size(), 5u);
  EXPECT_EQ(mesh.points[4], Vec3<double>(1, 1, 1));
  ASSERT_EQ(mesh.tetrahedra.size(), 2u);
  EXPECT_EQ(mesh.tetrahedra[1], (Tetrahedron{1, 2, 3, 4}));
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangles[0], (Triangle{0, 1, 2}));
  // SOFA's liver (../shared/sofa-scenes/share/mesh, beside the project, when present).
  const auto liver = std::filesystem::path(FASTCOROT_SOURCE_DIR) / "../shared/sofa-scenes/share/mesh/liver.msh";
  if (std::filesystem::exists(liver)) {
    const MeshData sofa = read_gmsh(liver);
    EXPECT_EQ(sofa.points.size(), 181u);  // its $NOD count
    EXPECT_GT(sofa.tetrahedra.size(), 100u);
  }
}

TEST(GmshReader, BinaryInBothByteOrders) {
  for (const bool big_endian : {false, true}) {
    SCOPED_TRACE(big_endian ? "big-endian" : "little-endian");
    const MeshData mesh =
        read_gmsh(write_temp(big_endian ? "big.msh" : "little.msh", binary_v22(big_endian)));
    ASSERT_EQ(mesh.points.size(), 4u);
    EXPECT_EQ(mesh.points[1], Vec3<double>(1, 0, 0));
    EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{3, 2, 1, 0}}));
  }
}

TEST(GmshReader, ErrorsNameFileLineAndProblem) {
  EXPECT_TRUE(contains(read_error("hello\n"), "not a Gmsh mesh file"));
  EXPECT_TRUE(contains(read_error(""), "unexpected end of file"));
  const std::string version = read_error("$MeshFormat\n4 0 8\n$EndMeshFormat\n");
  EXPECT_TRUE(contains(version, "bad.msh:2: unsupported Gmsh format version '4'")) << version;
  EXPECT_TRUE(contains(version, "supported: 2.2 and 4.1")) << version;
  // Format 1: an element naming a node that does not exist, and a node count that does not match.
  EXPECT_TRUE(contains(read_error("$NOD\n1\n1 0 0 0\n$ENDNOD\n$ELM\n1\n1 4 1 1 4 1 2 3 4\n$ENDELM\n"), "bad.msh:7: element 1 uses node tag 2"))
      << read_error("$NOD\n1\n1 0 0 0\n$ENDNOD\n$ELM\n1\n1 4 1 1 4 1 2 3 4\n$ENDELM\n");
  EXPECT_TRUE(contains(read_error("$NOD\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$ENDNOD\n$ELM\n1\n1 4 1 1 3 1 2 3\n$ENDELM\n"),
                       "has 3 nodes; expected 4"));
  EXPECT_TRUE(contains(read_error("$NOD\n1\n1 0 0 0\n$ENDNOD\n$Nodes\n"), "unknown section $Nodes in a Gmsh format 1 file"));
  EXPECT_TRUE(contains(read_error("$MeshFormat\n2.2 0 4\n$EndMeshFormat\n"), "data size 4"));
  EXPECT_TRUE(contains(read_error("$MeshFormat\n2.2 3 8\n$EndMeshFormat\n"), "file type 3"));
  EXPECT_TRUE(contains(read_error(binary_v22(false, 2)), "bad endianness check"));

  const std::string header = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  const std::string nodes = "$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n";
  const std::string unknown =
      read_error(header + nodes + "$Elements\n1\n1 2 0 1 2 99\n$EndElements\n");
  EXPECT_TRUE(contains(unknown, "bad.msh:11: element 1 uses node tag 99, which is not in $Nodes"))
      << unknown;
  EXPECT_TRUE(contains(read_error(header + "$Nodes\n2\n1 0 0 0\n1 1 0 0\n$EndNodes\n"),
                       "node tag 1 appears twice"));
  const std::string number = read_error(header + "$Nodes\n1\n1 0 zero 0\n$EndNodes\n");
  EXPECT_TRUE(contains(number, "bad.msh:6: expected a number (a node coordinate), found 'zero'"))
      << number;
  EXPECT_TRUE(contains(read_error(header + "$Nodes\n1\n1 0 0 nan\n$EndNodes\n"), "not finite"));
  EXPECT_TRUE(contains(read_error(header + "$Nodes\n2\n1 0 0 0\n2 1 0 0\n$Elements\n"),
                       "expected '$EndNodes', found '$Elements'"));
  EXPECT_TRUE(
      contains(read_error(header + "$Nodes\n2\n1 0 0 0\n2 1.0 0.0"), "unexpected end of file"));
  EXPECT_TRUE(contains(read_error(header + "$Nodes\n1000\n1 0 0 0\n$EndNodes\n"),
                       "bad.msh:5: node count 1000 is larger than the file can hold"));
  EXPECT_TRUE(contains(read_error(header + "$PhysicalNames\n1\n3 1 \"a\"\n"),
                       "section $PhysicalNames has no $EndPhysicalNames"));
  EXPECT_TRUE(contains(read_error(header), "no $Nodes section"));
  EXPECT_TRUE(
      contains(read_error(header + "$Elements\n0\n$EndElements\n"), "$Elements before $Nodes"));
  EXPECT_TRUE(contains(read_error(header + nodes + "garbage\n"), "expected a section"));

  const std::string v41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  EXPECT_TRUE(
      contains(read_error(v41 + "$Nodes\n1 3 1 3\n2 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n"),
               "fewer nodes than the header's count"));
  EXPECT_TRUE(
      contains(read_error(v41 + "$Nodes\n1 1 1 1\n2 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n"),
               "more nodes than the header's count"));
}

TEST(GmshReader, MissingFileIsAnError) {
  const auto path = mesh_path("no_such_file.msh");
  try {
    read_gmsh(path);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": no such file");
  }
}

}  // namespace
}  // namespace fastcorot
