// Tests of the legacy VTK reader on files VTK 9.1 and meshio 5.0 wrote (tests/data/meshes, see
// its README.md) and on small hand-written files: values read from the file text by eye, the 4.2
// and 5.1 cell layouts, ASCII and big-endian BINARY, float points, FIELD and METADATA blocks
// before the geometry, skipped cell types, and an error naming file and line for bad input.
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
                   ("fastcorot_vtk_" +
                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

std::string read_error(std::string_view contents) {
  const auto path = write_temp("bad.vtk", contents);
  try {
    read_vtk_legacy(path);
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

TEST(VtkLegacyReader, BoxV42AsciiValuesReadFromTheFileByEye) {
  // Written by vtkUnstructuredGridWriter (VTK 9.1, FileVersion 42).
  const MeshData mesh = read_vtk_legacy(mesh_path("box_vtk_v42_ascii.vtk"));
  // "POINTS 44 double" then "0 0 0.5 0 0 0 0 0.5 0.5 " / "0 0.5 0 1 0 0.5 1 0 0 "
  ASSERT_EQ(mesh.points.size(), 44u);
  EXPECT_EQ(mesh.points[0], Vec3<double>(0, 0, 0.5));
  EXPECT_EQ(mesh.points[1], Vec3<double>(0, 0, 0));
  EXPECT_EQ(mesh.points[2], Vec3<double>(0, 0.5, 0.5));
  EXPECT_EQ(mesh.points[4], Vec3<double>(1, 0, 0.5));
  // "CELLS 210 886"; line 147, the first 4-point cell: "4 32 42 35 41 ", then "4 35 32 34 38 ".
  ASSERT_EQ(mesh.tetrahedra.size(), 90u);
  EXPECT_EQ(mesh.tetrahedra[0], (Tetrahedron{32, 42, 35, 41}));
  EXPECT_EQ(mesh.tetrahedra[1], (Tetrahedron{35, 32, 34, 38}));
  EXPECT_EQ(mesh.triangles.size(), 84u);
}

TEST(VtkLegacyReader, AllVersionsAndEncodingsAgree) {
  const MeshData reference = read_vtk_legacy(mesh_path("box_vtk_v51_binary.vtk"));
  for (const char* name :
       {"box_vtk_v42_ascii.vtk", "box_vtk_v42_binary.vtk", "box_vtk_v51_ascii.vtk",
        "box_meshio_v42_ascii.vtk", "box_meshio_v42_binary.vtk", "box_meshio_v51_ascii.vtk",
        "box_meshio_v51_binary.vtk"}) {
    SCOPED_TRACE(name);
    const MeshData mesh = read_vtk_legacy(mesh_path(name));
    ASSERT_EQ(mesh.points.size(), reference.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
      // VTK writes ASCII coordinates with 11 significant digits.
      EXPECT_LE((mesh.points[i] - reference.points[i]).norm(), 1e-10) << "point " << i;
    }
    EXPECT_EQ(mesh.tetrahedra, reference.tetrahedra);
    EXPECT_EQ(mesh.triangles, reference.triangles);
  }
}

constexpr std::string_view kV42 = R"(# vtk DataFile Version 4.2
hand-written: a field, metadata, a vertex, a triangle, a tetrahedron, a hexahedron
ASCII
DATASET UNSTRUCTURED_GRID
FIELD FieldData 2
TIME 1 1 double
0.5
CYCLE 1 1 int
3
POINTS 8 float
0 0 0  1 0 0  0 1 0  0 0 1
1 1 0  1 0 1  0 1 1  1 1 1
METADATA
INFORMATION 0

CELLS 4 20
1 7
3 0 1 2
4 0 1 2 3
8 0 1 4 2 3 5 7 6
CELL_TYPES 4
1 5 10 12
CELL_DATA 4
SCALARS id int 1
LOOKUP_TABLE default
0 1 2 3
)";

TEST(VtkLegacyReader, HandWrittenV42KeepsTetrahedraAndTriangles) {
  const MeshData mesh = read_vtk_legacy(write_temp("v42.vtk", kV42));
  ASSERT_EQ(mesh.points.size(), 8u);
  EXPECT_EQ(mesh.points[7], Vec3<double>(1, 1, 1));
  EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{0, 1, 2, 3}}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}}));
}

TEST(VtkLegacyReader, HandWrittenV51) {
  const MeshData mesh = read_vtk_legacy(write_temp("v51.vtk", R"(# vtk DataFile Version 5.1
vtk output
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 5 double
0 0 0 1 0 0 0 1 0
0 0 1 1 1 1
CELLS 4 10
OFFSETS vtktypeint64
0 4 7 10
CONNECTIVITY vtktypeint64
0 1 2 3 1 2 4 4 2 3
CELL_TYPES 3
10
5
5
)"));
  EXPECT_EQ(mesh.points.size(), 5u);
  EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{0, 1, 2, 3}}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{1, 2, 4}, {4, 2, 3}}));
}

template <class T>
void append_big_endian(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::little) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  out.append(bytes, sizeof(T));
}

TEST(VtkLegacyReader, HandWrittenBinaryWithFloatPoints) {
  std::string s =
      "# vtk DataFile Version 4.2\nbinary\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n";
  for (const float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.25f})
    append_big_endian(s, x);
  s += "\nCELLS 1 5\n";
  for (const std::int32_t v : {4, 3, 2, 1, 0}) append_big_endian(s, v);
  s += "\nCELL_TYPES 1\n";
  append_big_endian<std::int32_t>(s, 10);
  s += "\n";
  const MeshData mesh = read_vtk_legacy(write_temp("binary.vtk", s));
  ASSERT_EQ(mesh.points.size(), 4u);
  EXPECT_EQ(mesh.points[3], Vec3<double>(0, 0, 0.25));
  EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{3, 2, 1, 0}}));
}

TEST(VtkLegacyReader, ErrorsNameFileLineAndProblem) {
  EXPECT_TRUE(contains(read_error("hello\n"), "bad.vtk:1: not a legacy VTK file"));
  const std::string version = read_error("# vtk DataFile Version 6.0\nt\nASCII\n");
  EXPECT_TRUE(contains(
      version, "unsupported legacy VTK version '6.0' (supported: 4.2 and earlier, and 5.1)"))
      << version;
  EXPECT_TRUE(contains(read_error("# vtk DataFile Version 4.2\nt\nHEX\n"),
                       "bad.vtk:3: unknown encoding 'HEX' (expected ASCII or BINARY)"));
  EXPECT_TRUE(
      contains(read_error("# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\n"),
               "bad.vtk:4: dataset type 'POLYDATA' is not supported (only UNSTRUCTURED_GRID)"));
  const std::string head = "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  const std::string points = "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n";
  const std::string range = read_error(head + points + "CELLS 1 5\n4 0 1 2 4\nCELL_TYPES 1\n10\n");
  EXPECT_TRUE(contains(range, "bad.vtk:7: cell 0: point index 4 out of range [0, 4)")) << range;
  EXPECT_TRUE(contains(read_error(head + points + "CELLS 1 4\n4 0 1 2\nCELL_TYPES 1\n10\n"),
                       "cell 0 runs past the cell list"));
  EXPECT_TRUE(contains(read_error(head + points + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n10\n"),
                       "a tetrahedron (type 10) with 3 points"));
  EXPECT_TRUE(contains(read_error(head + points + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n"),
                       "CELL_TYPES has 2 cells, CELLS has 1"));
  EXPECT_TRUE(
      contains(read_error(head + points + "CELLS 1 5\n4 0 1 2 3\n"), "CELLS without CELL_TYPES"));
  EXPECT_TRUE(
      contains(read_error(head + "POINTS 4 bit\n"), "bad.vtk:5: unsupported data type 'bit'"));
  EXPECT_TRUE(
      contains(read_error(head + "POINTS 4 double\n0 0 0 1 0\n"), "unexpected end of file"));
  EXPECT_TRUE(
      contains(read_error(head + "POINTS 1 double\n0 x 0\n"), "bad.vtk:6: expected a number"));
  EXPECT_TRUE(contains(read_error(head + "SPOTS 1\n"), "bad.vtk:5: unexpected keyword 'SPOTS'"));
  EXPECT_TRUE(contains(read_error(head), "no POINTS section"));
  const std::string v51 =
      "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n" + points;
  EXPECT_TRUE(contains(
      read_error(v51 +
                 "CELLS 2 4\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1 2 3\n"),
      "offsets must run from 0 to the connectivity size 4"));
  EXPECT_TRUE(contains(read_error(v51 + "CELLS 2 4\nOFFSETS float\n0 4\n"), "must be integers"));
  std::string binary =
      "# vtk DataFile Version 4.2\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n";
  binary += std::string(40, '\0');
  EXPECT_TRUE(contains(read_error(binary),
                       "bad.vtk: byte 78: unexpected end of file in the point coordinates"));
}

}  // namespace
}  // namespace fastcorot
