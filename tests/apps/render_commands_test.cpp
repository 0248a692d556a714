// `fastcorot run --png`, the drawn tetrahedra in `--vtu` output, and `fastcorot view` through the
// executable: pictures are written, not blank, identical for identical runs; bad options exit 2
// with a clear message; the viewer runs in Xvfb (xvfb-run) and its screenshot is not blank.
#include "fastcorot/render/image.h"
#include "fastcorot/io/mesh_readers.h"
#include "render/render_scenes.h"

#include "support/command.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

namespace fastcorot {
namespace {

using testing::CommandResult;
using testing::run_fastcorot;
using testing::shell;

std::filesystem::path output_dir(const std::string& name) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string write_scene(const std::filesystem::path& dir, const std::string& body) {
  const auto path = dir / "scene.scn";
  std::ofstream(path) << "<Node name=\"root\" gravity=\"0 -9.81 0\" dt=\"0.01\">\n"
                      << body << "\n</Node>\n";
  return path.string();
}

std::string bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Distinct colours in the picture: a blank one has a handful (its background gradient has at most
// one per row), a scene drawn on it many more.
std::size_t colours(const Image& image) {
  std::set<std::array<std::uint8_t, 3>> seen;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) seen.insert(image.pixel(x, y));
  }
  return seen.size();
}

TEST(RunPng, WritesOnePicturePerFrameIdenticalForIdenticalRuns) {
  const auto dir = output_dir("png_frames");
  const std::string scene = write_scene(dir, testing::small_beam("true"));
  for (const char* name : {"a", "b"}) {
    const auto result = run_fastcorot("run " + scene + " --steps 4 --every 2 --png " +
                                      (dir / name).string() + " --size 160x90 --quiet");
    ASSERT_EQ(result.status, 0) << result.output;
  }
  for (const char* step : {"00000", "00002", "00004"}) {
    const auto a = dir / "a" / ("step_" + std::string(step) + ".png");
    ASSERT_TRUE(std::filesystem::exists(a)) << a;
    EXPECT_EQ(bytes_of(a), bytes_of(dir / "b" / ("step_" + std::string(step) + ".png"))) << a;
    const Image image = read_png(a);
    EXPECT_EQ(image.width, 160);
    EXPECT_EQ(image.height, 90);
    EXPECT_GT(colours(image), 150u) << a;
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir / "a"),
                          std::filesystem::directory_iterator()),
            3);
  // The beam moves: the first and last frames differ.
  EXPECT_NE(bytes_of(dir / "a" / "step_00000.png"), bytes_of(dir / "a" / "step_00004.png"));
}

TEST(RunPng, AResumedRunDrawsTheSamePicturesAndDrawnTetrahedra) {
  // The camera is framed on the scene as built, also when resuming, so the frames after the
  // checkpoint are the uninterrupted run's, byte for byte (and so are the drawn-tetrahedra VTUs).
  const auto dir = output_dir("png_resume");
  const std::string scene = write_scene(dir, testing::small_beam("true"));
  const auto in = [&](const char* name) {
    return " --png " + (dir / name).string() + " --out " + (dir / name).string();
  };
  const std::string options = " --every 2 --size 160x90 --quiet --vtu";
  const std::string checkpoint = " --checkpoint " + (dir / "run.ckpt").string();
  for (const std::string& arguments :
       {" --steps 6" + in("whole"), " --steps 3 --checkpoint-every 2" + checkpoint + in("split"),
        " --steps 6 --resume " + (dir / "run.ckpt").string() + in("split")}) {
    const auto result = run_fastcorot("run " + scene + arguments + options);
    ASSERT_EQ(result.status, 0) << arguments << "\n" << result.output;
  }
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "whole")) {
    const auto name = entry.path().filename();
    EXPECT_EQ(bytes_of(entry.path()), bytes_of(dir / "split" / name)) << name;
    ++compared;
  }
  // step_00000, 2, 4, 6 pictures; beam and drawing frames 0, 2, 4, 6 and their two .pvd files.
  EXPECT_EQ(compared, 4 + 8 + 2);
}

TEST(RunPng, DrawingSwitchChangesThePicture) {
  const auto dir = output_dir("png_drawing");
  const std::string scene = write_scene(dir, testing::small_beam("false"));
  for (const char* mode : {"off", "on"}) {
    const auto result = run_fastcorot("run " + scene + " --steps 0 --png " + (dir / mode).string() +
                                      " --size 96x64 --drawing " + mode + " --quiet");
    ASSERT_EQ(result.status, 0) << result.output;
  }
  EXPECT_NE(bytes_of(dir / "off" / "step_00000.png"), bytes_of(dir / "on" / "step_00000.png"));
}

TEST(RunPng, BadPictureOptionsExitWith2AndSayWhy) {
  const auto dir = output_dir("png_bad");
  const std::string scene = write_scene(dir, testing::small_beam());
  const std::string png = " --steps 1 --png " + (dir / "out").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {png + " --size 0x10", "--size \"0x10\""},
      {png + " --size big", "--size \"big\""},
      {png + " --drawing maybe", "--drawing \"maybe\""},
      {png + " --constraints maybe", "--constraints \"maybe\""},
      {png + " --constraint-force-scale -1", "--constraint-force-scale -1"},
      {png + " --contacts maybe", "--contacts \"maybe\""},
      {png + " --camera-eye 1,2", "--camera-eye \"1,2\""},
      {png + " --camera-fov 200", "--camera-fov 200"},
      {" --steps 1 --png " + scene + "/inside-a-file", "cannot create the folder"},
      {" --steps 1 --size 100x100", "--size requires --png"},
  };
  for (const auto& [arguments, message] : cases) {
    const auto result = run_fastcorot("run " + scene + arguments);
    EXPECT_EQ(result.status, 2) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(message), std::string::npos) << arguments << "\n" << result.output;
  }
  if (getuid() != 0) {  // root writes anywhere
    std::filesystem::create_directories(dir / "locked");
    std::filesystem::permissions(
        dir / "locked", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    const auto result =
        run_fastcorot("run " + scene + " --steps 1 --png " + (dir / "locked").string());
    EXPECT_EQ(result.status, 2) << result.output;
    EXPECT_NE(result.output.find("not writable"), std::string::npos) << result.output;
  }
}

TEST(RunVtu, DrawnTetrahedraGoToTheirOwnSeries) {
  const auto dir = output_dir("vtu_drawing");
  const std::string scene = write_scene(dir, testing::small_beam("true"));
  const auto result = run_fastcorot("run " + scene + " --steps 2 --vtu --out " +
                                    (dir / "out").string() + " --quiet");
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* file : {"root_beam.pvd", "root_beam_2.vtu", "root_beam_drawing.pvd",
                           "root_beam_drawing_0.vtu", "root_beam_drawing_2.vtu"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / file)) << file;
  }
  const MeshData drawn = read_vtu(dir / "out" / "root_beam_drawing_2.vtu");
  EXPECT_EQ(drawn.points.size(), 4u * 12u);
  EXPECT_EQ(drawn.triangles.size(), 4u * 12u);
  // --drawing off: no drawing series.
  const auto off = run_fastcorot("run " + scene + " --steps 1 --vtu --drawing off --out " +
                                 (dir / "off").string() + " --quiet");
  ASSERT_EQ(off.status, 0) << off.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "off" / "root_beam_drawing.pvd"));
}

#ifdef FASTCOROT_WITH_VIEWER

TEST(View, RunsUnderXvfbAndItsScreenshotIsNotBlank) {
  if (shell("command -v xvfb-run").status != 0) {
    GTEST_SKIP() << "xvfb-run not found: install Debian's xvfb and xauth (scripts/setup does) to "
                    "test the viewer";
  }
  const auto dir = output_dir("view_xvfb");
  const std::string scene = write_scene(dir, testing::small_beam("true"));
  const auto screenshot = dir / "screenshot.png";
  const auto result =
      shell("xvfb-run -a -s '-screen 0 640x480x24' " + std::string(FASTCOROT_EXECUTABLE) +
            " view " + scene + " --frames 4 --size 400x300 --screenshot " + screenshot.string());
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("4 frames"), std::string::npos) << result.output;
  const Image image = read_png(screenshot);
  EXPECT_EQ(image.width, 400);
  EXPECT_EQ(image.height, 300);
  EXPECT_GT(colours(image), 200u);
  // The right half (clear of the panel) shows the scene, not only the background.
  std::set<std::array<std::uint8_t, 3>> right;
  for (int y = 0; y < image.height; ++y) {
    for (int x = image.width / 2; x < image.width; ++x) right.insert(image.pixel(x, y));
  }
  EXPECT_GT(right.size(), 50u);
}

TEST(View, WithoutADisplayExitsWith2AndSaysWhatToDo) {
  const auto dir = output_dir("view_no_display");
  const std::string scene = write_scene(dir, testing::small_beam());
  const auto result = shell("env -u DISPLAY -u WAYLAND_DISPLAY " +
                            std::string(FASTCOROT_EXECUTABLE) + " view " + scene + " --frames 1");
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("xvfb-run"), std::string::npos) << result.output;
  EXPECT_EQ(run_fastcorot("view /nonexistent.scn").status, 2);
  EXPECT_EQ(run_fastcorot("view " + scene + " --size 5x5").status, 2);
}

#else

TEST(View, WithoutTheViewerInTheBuildIsOneClearLine) {
  const auto dir = output_dir("view_not_built");
  const std::string scene = write_scene(dir, testing::small_beam());
  const auto result = shell(std::string(FASTCOROT_EXECUTABLE) + " view " + scene + " --frames 1");
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("built without the viewer"), std::string::npos) << result.output;
}

#endif

}  // namespace
}  // namespace fastcorot
