// Tests of the .vtu and .pvd writers: a written grid reads back bitwise equal through read_vtu,
// fields are stored as documented (Float64, base64 with a UInt32 byte-count header, decoded here
// independently of the reader), the .pvd text is exact, and bad input is refused with an error
// naming the file.
#include "fastcorot/io/mesh_readers.h"
#include "fastcorot/io/vtu_writer.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <numbers>
#include <tinyxml2.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {
namespace {

std::filesystem::path temp_path(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   ("fastcorot_vtu_writer_" +
                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// Plain base64 decoding (RFC 4648) of one padded string, for checking the file independently.
std::string base64_decode(std::string_view text) {
  const std::string_view alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    const std::size_t v = alphabet.find(c);
    if (v == std::string_view::npos) continue;  // whitespace and '=' padding
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xff);
    }
  }
  return out;
}

// The values of the DataArray named `name` (Float64, little-endian host assumed as in CI).
std::vector<double> float64_array(const std::filesystem::path& path, const char* name) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(path.string().c_str()), tinyxml2::XML_SUCCESS);
  std::vector<const tinyxml2::XMLElement*> stack = {doc.RootElement()};
  while (!stack.empty()) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    if (std::strcmp(e->Name(), "DataArray") == 0 && e->Attribute("Name", name)) {
      EXPECT_STREQ(e->Attribute("type"), "Float64");
      EXPECT_STREQ(e->Attribute("format"), "binary");
      const std::string bytes = base64_decode(e->GetText());
      std::uint32_t header = 0;
      std::memcpy(&header, bytes.data(), 4);
      EXPECT_EQ(header, bytes.size() - 4);
      std::vector<double> values((bytes.size() - 4) / 8);
      std::memcpy(values.data(), bytes.data() + 4, 8 * values.size());
      return values;
    }
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
      stack.push_back(c);
  }
  ADD_FAILURE() << "no DataArray " << name;
  return {};
}

struct Grid {
  std::vector<Vec3<double>> points;
  std::vector<VtuCellBlock> cells;
};

// Two tetrahedra sharing a face, and that face as a triangle; coordinates with full mantissas.
Grid two_tetrahedra() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  Grid grid;
  grid.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  for (auto& p : grid.points) p += Vec3<double>(noise(rng), noise(rng), noise(rng));
  grid.cells = {VtuCellBlock{10, 4, {0, 1, 2, 3, 1, 2, 3, 4}}, VtuCellBlock{5, 3, {1, 2, 3}}};
  return grid;
}

TEST(VtuWriter, RoundTripIsExact) {
  const Grid grid = two_tetrahedra();
  const auto path = temp_path("grid.vtu");
  write_vtu(path, grid.points, grid.cells,
            {VtuField{"displacement", 3, std::vector<double>(15, 0.5)}},
            {VtuField{"stress", 1, {1, 2, 3}}});
  const MeshData mesh = read_vtu(path);
  EXPECT_EQ(mesh.points, grid.points);
  EXPECT_EQ(mesh.tetrahedra, (std::vector<Tetrahedron>{{0, 1, 2, 3}, {1, 2, 3, 4}}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{1, 2, 3}}));
}

TEST(VtuWriter, EmptyGridRoundTrips) {
  const auto path = temp_path("empty.vtu");
  write_vtu(path, {}, {}, {});
  const MeshData mesh = read_vtu(path);
  EXPECT_TRUE(mesh.points.empty());
  EXPECT_TRUE(mesh.tetrahedra.empty());
}

TEST(VtuWriter, FieldsAreFloat64WithAByteCountHeader) {
  const Grid grid = two_tetrahedra();
  const auto path = temp_path("fields.vtu");
  std::vector<double> displacement(15);
  for (std::size_t i = 0; i < displacement.size(); ++i)
    displacement[i] = 0.1 * static_cast<double>(i) - 1e-300;
  const std::vector<double> stress = {1.5, -2.25, std::numeric_limits<double>::max()};
  write_vtu(path, grid.points, grid.cells, {VtuField{"displacement", 3, displacement}},
            {VtuField{"von <Mises> & \"co\"", 1, stress}});
  EXPECT_EQ(float64_array(path, "displacement"), displacement);
  EXPECT_EQ(float64_array(path, "von <Mises> & \"co\""), stress);
  const std::string text = file_text(path);
  EXPECT_NE(text.find(R"(header_type="UInt32")"), std::string::npos);
  EXPECT_NE(text.find(R"(<DataArray type="Float64" Name="displacement" NumberOfComponents="3")"
                      R"( format="binary">)"),
            std::string::npos);
  EXPECT_NE(text.find(R"(<DataArray type="Int64" Name="connectivity" format="binary">)"),
            std::string::npos);
  EXPECT_NE(text.find(R"(<DataArray type="UInt8" Name="types" format="binary">)"),
            std::string::npos);
  EXPECT_NE(text.find(R"(<Piece NumberOfPoints="5" NumberOfCells="3">)"), std::string::npos);
}

std::string write_error(const std::vector<VtuCellBlock>& cells,
                        const std::vector<VtuField>& point_fields,
                        const std::vector<VtuField>& cell_fields) {
  const auto path = temp_path("bad.vtu");
  try {
    write_vtu(path, two_tetrahedra().points, cells, point_fields, cell_fields);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    return message;
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST(VtuWriter, BadInputIsRefused) {
  const auto contains = [](const std::string& text, std::string_view part) {
    return text.find(part) != std::string::npos;
  };
  const std::vector<VtuCellBlock> cells = two_tetrahedra().cells;
  EXPECT_TRUE(contains(write_error({VtuCellBlock{10, 4, {0, 1, 2, 5}}}, {}, {}),
                       "cell block 0: cell 0: point index 5 out of range [0, 5)"));
  EXPECT_TRUE(
      contains(write_error({VtuCellBlock{10, 4, {0, 1, 2}}}, {}, {}), "not a multiple of 4"));
  EXPECT_TRUE(contains(write_error({VtuCellBlock{10, 0, {}}}, {}, {}), "bad cell type"));
  EXPECT_TRUE(contains(write_error(cells, {VtuField{"u", 3, std::vector<double>(14)}}, {}),
                       "point field 'u' has 14 values, expected 5 × 3"));
  EXPECT_TRUE(contains(write_error(cells, {}, {VtuField{"s", 2, std::vector<double>(6)}}),
                       "cell field 's' has 2 components (must be 1, 3 or 4)"));
  EXPECT_TRUE(
      contains(write_error(cells, {}, {VtuField{"", 1, std::vector<double>(3)}}), "has no name"));
  const auto nowhere = temp_path("missing_folder") / "grid.vtu";
  try {
    write_vtu(nowhere, {}, {}, {});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              nowhere.string() + ": cannot open for writing: No such file or directory");
  }
}

TEST(VtuWriter, PvdListsTimeSteps) {
  const auto path = temp_path("series.pvd");
  write_pvd(path, {{0.0, "step_0.vtu"}, {0.1, "step_1.vtu"}, {1e-3, "a&b.vtu"}});
  EXPECT_EQ(file_text(path), R"(<?xml version="1.0"?>
<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">
  <Collection>
    <DataSet timestep="0" group="" part="0" file="step_0.vtu"/>
    <DataSet timestep="0.1" group="" part="0" file="step_1.vtu"/>
    <DataSet timestep="0.001" group="" part="0" file="a&amp;b.vtu"/>
  </Collection>
</VTKFile>
)");
  EXPECT_THROW(write_pvd(path, {{std::numeric_limits<double>::quiet_NaN(), "x.vtu"}}), Error);
}

// Rigid frames: one vertex per rigid at its centre, its quaternion and its turned axes (a rigid
// turned 90° about z has x along y and y along -x), velocities and forces from its two blocks.
TEST(VtuWriter, RigidFramesHoldCentresOrientationsAndAxes) {
  RigidBlocks<double> rigids;
  rigids.block = {0, 2};
  rigids.orientation = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3<double>::UnitZ()))};
  rigids.rest_orientation = rigids.orientation;
  const std::vector<Vec3<double>> x = {{1, 2, 3}, {0, 0, 0}, {4, 5, 6}, {0, 0, 0}};
  const std::vector<Vec3<double>> v = {{1, 0, 0}, {0, 0, 2}, {0, 1, 0}, {3, 0, 0}};
  const std::vector<Vec3<double>> f = {{0, 0, -1}, {0, 1, 0}, {0, 0, -2}, {1, 1, 1}};
  const auto path = temp_path("frames.vtu");
  write_rigid_frames_vtu(path, rigids, x, v, f);
  const MeshData mesh = read_vtu(path);
  EXPECT_EQ(mesh.points, (std::vector<Vec3<double>>{{1, 2, 3}, {4, 5, 6}}));
  const auto q = float64_array(path, "orientation");
  ASSERT_EQ(q.size(), 8u);
  EXPECT_NEAR(q[6], std::sqrt(0.5), 1e-15);  // z of the second
  EXPECT_NEAR(q[7], std::sqrt(0.5), 1e-15);  // w
  const auto ax = float64_array(path, "axis_x"), ay = float64_array(path, "axis_y");
  EXPECT_NEAR(ax[4], 1, 1e-15);   // second rigid's x axis is the world's y
  EXPECT_NEAR(ay[3], -1, 1e-15);  // its y axis is -x
  EXPECT_EQ(float64_array(path, "angular_velocity"), (std::vector<double>{0, 0, 2, 3, 0, 0}));
  EXPECT_EQ(float64_array(path, "torque"), (std::vector<double>{0, 1, 0, 1, 1, 1}));
}

}  // namespace
}  // namespace fastcorot
