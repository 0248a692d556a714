// Tests of the OBJ and STL surface readers: small files written here with values checked by eye,
// every face form SOFA's MeshOBJLoader reads (v, v/vt, v//vn, v/vt/vn, negative indices,
// polygons), a binary and an ASCII STL of the same triangles, SOFA's own example surfaces, and
// malformed files.
#include "fastcorot/io/surface_readers.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace fastcorot {
namespace {

std::string error_of(const std::string& text, bool stl = false) {
  try {
    if (stl) {
      read_stl_bytes(text, "t.stl");
    } else {
      read_obj_bytes(text, "t.obj");
    }
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(ObjReader, ReadsPointsTrianglesQuadsAndPolygonsAsSofaDoes) {
  const SurfaceData s = read_obj_bytes(R"(# a comment
mtllib box.mtl
o box
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0 1.0
vt 0 0
vn 0 0 1
v 0.5 0.5 1
usemtl red
s off
f 1 2 3
f 1/1 3/1 4/1
f 1//1 2//1 3//1 4//1
f -5/1/1 -4/1/1 -3/1/1 -2/1/1 -1/1/1
l 1 2
)",
                                       "box.obj");
  ASSERT_EQ(s.points.size(), 5u);
  EXPECT_EQ(s.points[3], Vec3<double>(0, 1, 0));
  EXPECT_EQ(s.points[4], Vec3<double>(0.5, 0.5, 1));
  // Triangles in file order; the pentagon as SOFA's fan (0, j - 1, j).
  ASSERT_EQ(s.triangles.size(), 5u);
  EXPECT_EQ(s.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(s.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(s.triangles[2], (Triangle{0, 1, 2}));
  EXPECT_EQ(s.triangles[3], (Triangle{0, 2, 3}));
  EXPECT_EQ(s.triangles[4], (Triangle{0, 3, 4}));
  ASSERT_EQ(s.quads.size(), 1u);
  EXPECT_EQ(s.quads[0], (Quad{0, 1, 2, 3}));
  EXPECT_EQ(s.all_triangles().size(), 7u);
  EXPECT_EQ(s.all_triangles()[6], (Triangle{0, 2, 3}));
}

TEST(ObjReader, BadFilesNameTheLine) {
  EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").find("t.obj:4: face vertex 4 refers to no point (3 read so far)"),
            std::string::npos)
      << error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nf 1 2\n").find("t.obj:3: a face needs 3 vertices"), std::string::npos);
  EXPECT_NE(error_of("v 0 zero 0\n").find("t.obj:1: expected a number"), std::string::npos);
  EXPECT_NE(error_of("v 0 0 0\nf 1 x 1\n").find("face vertex 'x' is not an index"), std::string::npos);
  EXPECT_NE(error_of("v 0 0 0\nf 0 1 1\n").find("face vertex 0 refers to no point"), std::string::npos);
  EXPECT_NE(error_of("v 0 0 nan\n").find("not finite"), std::string::npos);
  EXPECT_NE(error_of("# nothing\n").find("no vertices"), std::string::npos);
  EXPECT_NE(error_of("v 0 0\n").find("t.obj:2: unexpected end of file"), std::string::npos) << error_of("v 0 0\n");
}

std::string binary_stl(const std::vector<std::array<Vec3<double>, 3>>& triangles) {
  std::string bytes(80, ' ');
  const auto put = [&](auto value) {
    char raw[sizeof(value)];
    std::memcpy(raw, &value, sizeof(value));
    bytes.append(raw, sizeof(value));
  };
  put(static_cast<std::uint32_t>(triangles.size()));
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) put(0.0f);
    for (const auto& p : t) {
      for (int k = 0; k < 3; ++k) put(static_cast<float>(p[k]));
    }
    put(static_cast<std::uint16_t>(0));
  }
  return bytes;
}

TEST(StlReader, BinaryAndAsciiGiveTheSameSurfaceWithSharedCornersMerged) {
  const std::vector<std::array<Vec3<double>, 3>> triangles = {
      {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0)},
      {Vec3<double>(1, 0, 0), Vec3<double>(1, 1, 0), Vec3<double>(0, 1, 0)}};
  const SurfaceData binary = read_stl_bytes(binary_stl(triangles), "b.stl");
  const SurfaceData ascii = read_stl_bytes(R"(solid square
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 1 0 0
      vertex 0 1 0
    endloop
  endfacet
  facet normal 0 0 1
    outer loop
      vertex 1 0 0
      vertex 1 1 0
      vertex 0 1 0
    endloop
  endfacet
endsolid square
)",
                                            "a.stl");
  for (const SurfaceData* s : {&binary, &ascii}) {
    ASSERT_EQ(s->points.size(), 4u);  // six corners, four points
    EXPECT_EQ(s->points[2], Vec3<double>(0, 1, 0));
    ASSERT_EQ(s->triangles.size(), 2u);
    EXPECT_EQ(s->triangles[1], (Triangle{1, 3, 2}));
  }
  // A binary file whose first bytes spell "solid" is still read as binary (its size says so).
  std::string tricky = binary_stl(triangles);
  tricky.replace(0, 5, "solid");
  EXPECT_EQ(read_stl_bytes(tricky, "c.stl").triangles.size(), 2u);
}

TEST(StlReader, BadFilesAreErrors) {
  EXPECT_NE(error_of("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n endloop\n", true)
                .find("expected 'vertex'"),
            std::string::npos);
  EXPECT_NE(error_of("nothing here", true).find("not an STL file"), std::string::npos);
  std::string truncated = binary_stl({{Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0)}});
  truncated.resize(truncated.size() - 10);
  EXPECT_NE(error_of(truncated, true).find("not an STL file"), std::string::npos);
}

TEST(SurfaceFiles, SofasExampleSurfacesRead) {
  // SOFA's meshes, as shipped beside the project (../shared/sofa-scenes/share/mesh), when present.
  const std::filesystem::path dir = std::filesystem::path(FASTCOROT_SOURCE_DIR) / "../shared/sofa-scenes/share/mesh";
  if (!std::filesystem::exists(dir / "liver-smooth.obj")) GTEST_SKIP() << "no " << dir;
  const SurfaceData liver = read_surface_file(dir / "liver-smooth.obj");
  EXPECT_GT(liver.points.size(), 100u);
  EXPECT_GT(liver.all_triangles().size(), 100u);
  const SurfaceData cube = read_surface_file(dir / "smCube125.obj");
  EXPECT_GT(cube.points.size(), 8u);
  EXPECT_THROW(read_surface_file(dir / "liver.msh"), Error);  // not a surface extension
}

}  // namespace
}  // namespace fastcorot
