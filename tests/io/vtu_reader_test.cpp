// Tests of the VTK XML .vtu reader on files VTK 9.1 and meshio 5.0 wrote (tests/data/meshes, see
// its README.md): ascii, inline base64 "binary", appended raw and base64 data, zlib-compressed or
// not, UInt32 and UInt64 headers, Float32 and Float64 points, Int32 and Int64 cells, little- and
// big-endian; plus values read from the file text by eye, small hand-written files (several
// pieces, one tetrahedron) and an error naming file and line for each kind of bad input.
#include "fastcorot/io/mesh_readers.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fastcorot {
namespace {

std::filesystem::path mesh_path(const std::string& name) {
  return std::filesystem::path(FASTCOROT_TEST_DATA_DIR) / "meshes" / name;
}

// Writes `contents` to a file of this test's own temporary folder.
std::filesystem::path write_temp(const std::string& name, std::string_view contents) {
  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   ("fastcorot_vtu_" +
                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

std::string read_error(std::string_view contents) {
  const auto path = write_temp("bad.vtu", contents);
  try {
    read_vtu(path);
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

std::string replaced(std::string text, std::string_view from, std::string_view to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(VtuReader, BoxAsciiValuesReadFromTheFileByEye) {
  // Written by vtkXMLUnstructuredGridWriter (VTK 9.1) in ascii mode.
  const MeshData mesh = read_vtu(mesh_path("box_vtk_ascii.vtu"));
  // Points, lines 79-81: "0 0 0.5 0 0 0" / "0 0.5 0.5 0 0.5 0" / "1 0 0.5 1 0 0"
  ASSERT_EQ(mesh.points.size(), 44u);
  EXPECT_EQ(mesh.points[0], Vec3<double>(0, 0, 0.5));
  EXPECT_EQ(mesh.points[1], Vec3<double>(0, 0, 0));
  EXPECT_EQ(mesh.points[2], Vec3<double>(0, 0.5, 0.5));
  EXPECT_EQ(mesh.points[5], Vec3<double>(1, 0, 0));
  // connectivity, lines 165-166: "41 41 42 23 32 42" / "35 41 35 32 34 38": the first
  // tetrahedron starts at entry 316 = 8 vertices + 28 × 2 (lines) + 84 × 3 (triangles).
  ASSERT_EQ(mesh.tetrahedra.size(), 90u);
  EXPECT_EQ(mesh.tetrahedra[0], (Tetrahedron{32, 42, 35, 41}));
  EXPECT_EQ(mesh.tetrahedra[1], (Tetrahedron{35, 32, 34, 38}));
  EXPECT_EQ(mesh.triangles.size(), 84u);
}

TEST(VtuReader, AllEncodingsAgree) {
  const MeshData reference = read_vtu(mesh_path("box_vtk_appended_raw.vtu"));
  // (file, coordinate tolerance): meshio writes ascii with 12 significant digits.
  const std::vector<std::pair<const char*, double>> files = {
      {"box_vtk_appended_raw_zlib_uint64.vtu", 0},
      {"box_vtk_appended_base64_zlib.vtu", 0},
      {"box_vtk_appended_raw_zlib_bigendian.vtu", 0},
      {"box_vtk_binary_zlib_uint32.vtu", 0},
      {"box_vtk_binary.vtu", 0},
      {"box_vtk_ascii.vtu", 0},
      {"box_vtk_float32.vtu", 1e-7},
      {"box_meshio_ascii.vtu", 1e-11},
      {"box_meshio_binary.vtu", 0},
      {"box_meshio_binary_zlib.vtu", 0},
      {"box_meshio_binary_zlib_uint64.vtu", 0},
      {"box_meshio_float32_int32.vtu", 1e-7}};
  for (const auto& [name, tolerance] : files) {
    SCOPED_TRACE(name);
    const MeshData mesh = read_vtu(mesh_path(name));
    ASSERT_EQ(mesh.points.size(), reference.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
      EXPECT_LE((mesh.points[i] - reference.points[i]).norm(), tolerance) << "point " << i;
    }
    EXPECT_EQ(mesh.tetrahedra, reference.tetrahedra);
    EXPECT_EQ(mesh.triangles, reference.triangles);
  }
}

// One tetrahedron and one triangle, ascii; the error tests below change one piece of it.
constexpr std::string_view kTetrahedron = R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="4" NumberOfCells="2">
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
          0 0 0 1 0 0 0 1 0 0 0 1
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3 3 2 1</DataArray>
        <DataArray type="Int32" Name="offsets" format="ascii">4 7</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10 5</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)";

TEST(VtuReader, HandWrittenAscii) {
  const MeshData mesh = read_vtu(write_temp("tet.vtu", kTetrahedron));
  ASSERT_EQ(mesh.points.size(), 4u);
  EXPECT_EQ(mesh.points[3], Vec3<double>(0, 0, 1));
  EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{0, 1, 2, 3}}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{3, 2, 1}}));
}

TEST(VtuReader, PiecesAreConcatenated) {
  std::string two = std::string(kTetrahedron);
  const std::size_t begin = two.find("    <Piece");
  const std::size_t end = two.find("</Piece>\n") + 9;
  two.insert(end, two.substr(begin, end - begin));
  const MeshData mesh = read_vtu(write_temp("two.vtu", two));
  ASSERT_EQ(mesh.points.size(), 8u);
  EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{0, 1, 2, 3}, {4, 5, 6, 7}}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{3, 2, 1}, {7, 6, 5}}));
}

TEST(VtuReader, BinaryHeaderAndDataEncodedApartOrTogether) {
  // offsets = {4} as Int64: header 8 (UInt32) then 04 00 00 00 00 00 00 00.
  // Together: base64(08 00 00 00 04 00 ...) = "CAAAAAQAAAAAAAAA"; apart: "CAAAAA==" +
  // "BAAAAAAAAAA=".
  for (const char* encoded :
       {"CAAAAAQAAAAAAAAA", "CAAAAA==BAAAAAAAAAA=", "CAAA AA==\n BAAAAAAAAAA="}) {
    SCOPED_TRACE(encoded);
    std::string text =
        replaced(std::string(kTetrahedron), R"(NumberOfCells="2")", R"(NumberOfCells="1")");
    text =
        replaced(text, R"(<DataArray type="Int32" Name="offsets" format="ascii">4 7</DataArray>)",
                 std::string(R"(<DataArray type="Int64" Name="offsets" format="binary">)") +
                     encoded + "</DataArray>");
    text = replaced(text, ">10 5<", ">10<");
    text = replaced(text, "0 1 2 3 3 2 1", "0 1 2 3");
    const MeshData mesh = read_vtu(write_temp("binary.vtu", text));
    EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{0, 1, 2, 3}}));
  }
}

TEST(VtuReader, ErrorsNameFileLineAndProblem) {
  const std::string tet(kTetrahedron);
  const auto error = [&](std::string_view from, std::string_view to) {
    return read_error(replaced(tet, from, to));
  };
  EXPECT_TRUE(
      contains(error(R"(type="UnstructuredGrid")", R"(type="PolyData")"),
               "bad.vtu:2: VTKFile type 'PolyData' is not supported (only UnstructuredGrid)"));
  EXPECT_TRUE(
      contains(error(R"(byte_order="LittleEndian")",
                     R"(byte_order="LittleEndian" compressor="vtkLZ4DataCompressor")"),
               "compressor 'vtkLZ4DataCompressor' is not supported (only vtkZLibDataCompressor)"));
  EXPECT_TRUE(contains(error("LittleEndian", "MiddleEndian"), "unknown byte_order 'MiddleEndian'"));
  EXPECT_TRUE(contains(error(R"(version="0.1")", R"(version="0.1" header_type="UInt16")"),
                       "unknown header_type 'UInt16'"));
  EXPECT_TRUE(contains(error("</Points>", "</Pointz>"), "bad.vtu:5: XML error"));
  EXPECT_TRUE(contains(error(R"(NumberOfPoints="4" )", ""),
                       "bad.vtu:4: <Piece> needs an integer attribute NumberOfPoints"));
  EXPECT_TRUE(contains(error("0 1 2 3 3 2 1", "0 1 2 4 3 2 1"),
                       "bad.vtu:11: cell 0: point index 4 out of range [0, 4)"));
  EXPECT_TRUE(contains(error("0 1 2 3 3 2 1", "0 1 2 3 3 2"),
                       "bad.vtu:11: DataArray 'connectivity': 6 values, expected 7"));
  EXPECT_TRUE(contains(error(">4 7<", ">4 3<"), "bad.vtu:12: offsets decrease at cell 1"));
  EXPECT_TRUE(
      contains(error(">10 5<", ">10 10<"), "cell 1: a tetrahedron (type 10) with 3 points"));
  EXPECT_TRUE(contains(error("0 0 0 1 0 0", "0 0 0 1 zero 0"),
                       "bad.vtu:6: DataArray '': value 4 is not a number of type Float64: 'zero'"));
  EXPECT_TRUE(contains(error(R"(type="Int32" Name="offsets")", R"(type="Float32" Name="offsets")"),
                       "DataArray 'offsets': must hold integers, not Float32"));
  EXPECT_TRUE(contains(error(R"(type="Int32" Name="offsets")", R"(type="Int128" Name="offsets")"),
                       "DataArray 'offsets': unsupported type 'Int128'"));
  EXPECT_TRUE(contains(error(R"(Name="offsets" format="ascii")", R"(Name="offsets" format="hex")"),
                       "unknown format 'hex' (expected ascii, binary or appended)"));
  EXPECT_TRUE(contains(error(R"(Name="types")", R"(Name="typos")"),
                       "no <DataArray Name=\"types\"> in <Cells>"));
  EXPECT_TRUE(contains(error("<UnstructuredGrid>", "<UnstructuredGrid><Nothing>"), "XML error"));

  const std::string binary_offsets = R"(<DataArray type="Int32" Name="offsets" format="binary">)";
  const std::string ascii_offsets =
      R"(<DataArray type="Int32" Name="offsets" format="ascii">4 7</DataArray>)";
  // Two Int32 offsets are 8 bytes: "CAAAAA==" is the header 8, "EAAAAA==" says 16.
  EXPECT_TRUE(contains(error(ascii_offsets, binary_offsets + "CAAAAA==</DataArray>"),
                       "bad.vtu:12: DataArray 'offsets': data ends early (truncated data)"));
  EXPECT_TRUE(contains(error(ascii_offsets, binary_offsets + "EAAAAA==</DataArray>"),
                       "DataArray 'offsets': the header gives 16 bytes, expected 8"));
  EXPECT_TRUE(contains(error(ascii_offsets, binary_offsets + "CA!AAA==</DataArray>"),
                       "invalid base64 data"));
  EXPECT_TRUE(contains(error(ascii_offsets, binary_offsets + "</DataArray>"), "truncated header"));

  const std::string appended_offsets =
      R"(<DataArray type="Int32" Name="offsets" format="appended" offset="0"/>)";
  EXPECT_TRUE(contains(error(ascii_offsets, appended_offsets),
                       "format=\"appended\" but no <AppendedData>"));
  EXPECT_TRUE(
      contains(error("</VTKFile>", "<AppendedData encoding=\"hex\">_ABCD</AppendedData></VTKFile>"),
               "unknown AppendedData encoding 'hex' (expected raw or base64)"));
  EXPECT_TRUE(
      contains(error("</VTKFile>", "<AppendedData encoding=\"raw\">ABCD</AppendedData></VTKFile>"),
               "bad.vtu:17: <AppendedData> does not start with the '_' marker"));
  std::string appended = replaced(tet, ascii_offsets, appended_offsets);
  appended = replaced(appended, "</VTKFile>", "<AppendedData encoding=\"raw\">\n_\x08");
  EXPECT_TRUE(
      contains(read_error(appended), "DataArray 'offsets': data ends early (truncated header)"));
  EXPECT_TRUE(
      contains(read_error("<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid/></VTKFile>"),
               "bad.vtu:1: no <Piece> element"));
  EXPECT_TRUE(contains(read_error("<Grid/>"), "the root element is not <VTKFile>"));
}

}  // namespace
}  // namespace fastcorot
