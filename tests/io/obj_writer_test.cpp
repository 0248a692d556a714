// write_obj: what read_obj (an independent parser) reads back is what was written, to the bit; bad
// triangles are refused before anything is written.
#include "fastcorot/io/obj_writer.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/surface_readers.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <vector>

namespace fastcorot {
namespace {

std::filesystem::path temp_path(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / ("obj_writer_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

TEST(ObjWriter, ReadsBackBitwise) {
  const std::vector<Vec3<double>> points = {{0.1, 1.0 / 3.0, -2e-17}, {1e300, -0.0, 7}, {3.5, 2, 1}, {-1, -2, -3}};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {3, 2, 1}};
  const auto path = temp_path("surface.obj");
  write_obj(path, points, triangles, "a test");
  const SurfaceData read = read_obj(path);
  EXPECT_EQ(read.points, points);
  EXPECT_EQ(read.triangles, triangles);
}

TEST(ObjWriter, TrianglesOutsideThePointsAreRefused) {
  const auto path = temp_path("bad.obj");
  const std::vector<Vec3<double>> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  try {
    write_obj(path, points, std::vector<Triangle>{{0, 1, 3}}, "bad");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("names point 3 of a surface of 3 points"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace fastcorot
