// `fastcorot run` on long runs: --checkpoint-every and --resume give byte-identical output files;
// damaged or foreign checkpoints are refused; a diverging run stops naming the step, time, object
// and vertex; output files are never left half-written, even when the program is killed while
// writing one (FASTCOROT_FAULT, include/fastcorot/io/atomic_file.h).
#include "support/sofa_reference.h"

#include "fastcorot/io/mesh_readers.h"

#include "support/command.h"

#include "support/file_bytes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace fastcorot {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::CommandResult;
using testing::run_fastcorot;

fs::path fresh_dir(const std::string& name) {
  const auto dir = fs::path(FASTCOROT_TEST_OUTPUT_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Every file directly in `dir`, by name, with its bytes.
std::map<std::string, std::string> files_in(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file())
      files[entry.path().filename().string()] = testing::read_file_bytes(entry.path());
  }
  return files;
}

CommandResult run_with_fault(const std::string& fault, const std::string& arguments) {
  return testing::shell("FASTCOROT_FAULT=" + fault + " " + FASTCOROT_EXECUTABLE + " " + arguments);
}

const std::string kFourBeams = testing::sofa_reference_path("four_beams.scn");

// Every .vtu reads back whole, every .pvd is complete and lists only files that exist, and no
// temporary is left except those named in `partial_allowed` (at most that many).
void expect_outputs_valid(const fs::path& dir, std::size_t partial_allowed) {
  std::size_t partial = 0, vtu = 0;
  for (const auto& [name, bytes] : files_in(dir)) {
    if (name.find(".partial-") != std::string::npos) {
      ++partial;
      continue;
    }
    if (name.ends_with(".vtu")) {
      ++vtu;
      EXPECT_NO_THROW(read_vtu(dir / name)) << name;
    } else if (name.ends_with(".pvd")) {
      EXPECT_TRUE(bytes.ends_with("</VTKFile>\n")) << name;
      for (std::size_t at = bytes.find("file=\""); at != std::string::npos;
           at = bytes.find("file=\"", at + 1)) {
        const std::string listed = bytes.substr(at + 6, bytes.find('"', at + 6) - at - 6);
        EXPECT_TRUE(fs::exists(dir / listed)) << name << " lists " << listed;
      }
    }
  }
  EXPECT_GT(vtu, 0u);
  EXPECT_LE(partial, partial_allowed);
}

TEST(RunCheckpoint, AResumedRunWritesTheSameFilesByteForByte) {
  const fs::path whole = fresh_dir("checkpoint_whole"), split = fresh_dir("checkpoint_split");
  const std::string outputs = " --vtu --every 3 --quiet --dump-steps 0,3,5,8";
  CommandResult result =
      run_fastcorot("run " + kFourBeams + " --steps 10 --out " + whole.string() + outputs +
                    " --dump-state " + (whole / "state.json").string());
  ASSERT_EQ(result.status, 0) << result.output;
  // Stop at step 5 with checkpoints every 2 steps (the last at step 4), then resume from step 4.
  const std::string checkpoint = (split / "run.ckpt").string();
  result = run_fastcorot("run " + kFourBeams + " --steps 5 --checkpoint-every 2 --checkpoint " +
                         checkpoint + " --out " + split.string() + outputs + " --dump-state " +
                         (split / "first.json").string());
  ASSERT_EQ(result.status, 0) << result.output;
  result =
      run_fastcorot("run " + kFourBeams + " --steps 10 --resume " + checkpoint + " --out " +
                    split.string() + outputs + " --dump-state " + (split / "second.json").string());
  ASSERT_EQ(result.status, 0) << result.output;

  const auto expected = files_in(whole), got = files_in(split);
  std::size_t compared = 0;
  for (const auto& [name, bytes] : expected) {
    if (name == "state.json") continue;
    ASSERT_TRUE(got.count(name)) << name;
    EXPECT_TRUE(got.at(name) == bytes) << name << " differs";
    ++compared;
  }
  EXPECT_EQ(compared, 4u * 5u + 4u);  // frames 0, 3, 6, 9, 10 and one .pvd per beam
  // The dumps: steps 0, 3 (and the last, 5) from the first part, 5 and 8 and 10 from the second.
  const json all = json::parse(testing::read_file_bytes(whole / "state.json"));
  const json first = json::parse(testing::read_file_bytes(split / "first.json"));
  const json second = json::parse(testing::read_file_bytes(split / "second.json"));
  for (const char* step : {"0", "3", "5"})
    EXPECT_EQ(first["steps"][step], all["steps"][step]) << step;
  for (const char* step : {"5", "8", "10"})
    EXPECT_EQ(second["steps"][step], all["steps"][step]) << step;
  EXPECT_FALSE(second["steps"].contains("3"));
}

TEST(RunCheckpoint, DamagedOrForeignCheckpointsAreRefusedWithExitStatus2) {
  const fs::path dir = fresh_dir("checkpoint_refused");
  const std::string checkpoint = (dir / "good.ckpt").string();
  ASSERT_EQ(run_fastcorot("run " + kFourBeams +
                          " --steps 2 --quiet --checkpoint-every 2 --checkpoint " + checkpoint)
                .status,
            0);
  const std::string good = testing::read_file_bytes(checkpoint);
  auto refused = [&](const std::string& bytes, const std::string& scene,
                     const std::string& expected) {
    const fs::path path = dir / "bad.ckpt";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    const CommandResult result =
        run_fastcorot("run " + scene + " --steps 4 --quiet --resume " + path.string());
    EXPECT_EQ(result.status, 2) << result.output;
    EXPECT_NE(result.output.find(path.string()), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
  };
  std::string flipped = good;
  flipped[good.size() / 2] = static_cast<char>(flipped[good.size() / 2] ^ 0x10);
  refused(flipped, kFourBeams, "corrupt checkpoint");
  refused(good.substr(0, good.size() - 100), kFourBeams, "truncated checkpoint");
  std::string version = good;
  version[8] = 7;
  refused(version, kFourBeams, "format version 7");
  refused(good, "",
          "written for scene \"" + kFourBeams + "\"");  // the built-in beam: another scene
  refused("hello", kFourBeams, "not a fastcorot checkpoint");
  // A checkpoint past the requested last step.
  const CommandResult early =
      run_fastcorot("run " + kFourBeams + " --steps 1 --quiet --resume " + checkpoint);
  EXPECT_EQ(early.status, 2) << early.output;
  EXPECT_NE(early.output.find("at step 2, past --steps 1"), std::string::npos) << early.output;
  EXPECT_EQ(run_fastcorot("run --checkpoint-every -2").status, 2);
}

TEST(RunCheckpoint, AKilledCheckpointWriteLeavesThePreviousCheckpointToResumeFrom) {
  const fs::path dir = fresh_dir("checkpoint_killed");
  const std::string checkpoint = (dir / "run.ckpt").string();
  const std::string whole_dump = (dir / "whole.json").string(),
                    resumed_dump = (dir / "resumed.json").string();
  ASSERT_EQ(run_fastcorot("run " + kFourBeams + " --steps 6 --quiet --dump-steps 6 --dump-state " +
                          whole_dump)
                .status,
            0);
  // The only files written are the checkpoints at steps 2, 4, 6: the second write is killed
  // halfway.
  const CommandResult killed = run_with_fault(
      "write-kill:2",
      "run " + kFourBeams + " --steps 6 --quiet --checkpoint-every 2 --checkpoint " + checkpoint);
  EXPECT_NE(killed.status, 0) << killed.output;
  ASSERT_TRUE(fs::exists(checkpoint));
  const CommandResult resumed =
      run_fastcorot("run " + kFourBeams + " --steps 6 --quiet --resume " + checkpoint +
                    " --dump-steps 2,6 --dump-state " + resumed_dump);
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  const json whole = json::parse(testing::read_file_bytes(whole_dump)),
             again = json::parse(testing::read_file_bytes(resumed_dump));
  EXPECT_TRUE(
      again["steps"].contains("2"));  // it resumed from step 2, the last complete checkpoint
  EXPECT_EQ(again["steps"]["6"], whole["steps"]["6"]);
}

TEST(RunCheckpoint, AKilledOrFailedFrameWriteLeavesOnlyCompleteFiles) {
  for (const int at : {2, 6, 11}) {
    const fs::path dir = fresh_dir("killed_" + std::to_string(at));
    const CommandResult killed =
        run_with_fault("write-kill:" + std::to_string(at),
                       "run " + kFourBeams + " --steps 3 --vtu --quiet --out " + dir.string());
    EXPECT_NE(killed.status, 0) << killed.output;
    expect_outputs_valid(dir, 1);
    bool any_partial = false;
    for (const auto& [name, bytes] : files_in(dir))
      any_partial |= name.find(".partial-") != std::string::npos;
    EXPECT_TRUE(any_partial) << "the injected kill did not happen during a write";
  }
  const fs::path dir = fresh_dir("failed_write");
  const CommandResult failed = run_with_fault(
      "write-error:9", "run " + kFourBeams + " --steps 3 --vtu --quiet --out " + dir.string());
  EXPECT_EQ(failed.status, 2) << failed.output;
  EXPECT_NE(failed.output.find("injected fault"), std::string::npos) << failed.output;
  expect_outputs_valid(dir, 0);
  EXPECT_EQ(run_with_fault("write-sometimes",
                           "run --steps 1 --quiet --dump-state " + (dir / "x.json").string())
                .status,
            2);
}

// A free block pushed by an enormous constant force: it accelerates at 1e9 m/s² and leaves
// 1e6 scene sizes behind within a few steps (x_n = a h² n (n + 1) / 2 = 1e5 n (n + 1) / 2 m).
const char* kRunaway = R"(<Node name="root" dt="0.01" gravity="0 0 0">
  <Node name="blob">
    <EulerImplicitSolver/>
    <EigenSimplicialLDLT/>
    <RegularGridTopology name="grid" n="3 3 3" min="0 0 0" max="1 1 1"/>
    <MechanicalObject/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets"/>
    <UniformMass totalMass="27"/>
    <FastTetrahedralCorotationalForceField youngModulus="1000"/>
    <ConstantForceField force="0 0 1e9"/>
  </Node>
</Node>)";

TEST(RunCheckpoint, AnExplodingRunStopsNamingStepTimeObjectAndVertexAndKeepsItsFiles) {
  const fs::path dir = fresh_dir("runaway");
  const fs::path scene = dir / "runaway.scn";
  std::ofstream(scene) << kRunaway;
  const fs::path out = dir / "out";
  const CommandResult result =
      run_fastcorot("run " + scene.string() + " --steps 20 --vtu --quiet --out " + out.string() +
                    " --dump-state " + (dir / "state.json").string() + " --dump-steps 0,1,2,3");
  EXPECT_EQ(result.status, 2) << result.output;
  // Scene size sqrt(3): the bound 1.73e6 m is passed at step 6 (x_6 = 2.1e6 m, x_5 = 1.5e6 m).
  EXPECT_NE(result.output.find("diverged at step 6 (t = 0.06"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("root/blob vertex "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("divergence bound"), std::string::npos) << result.output;
  expect_outputs_valid(out, 0);
  EXPECT_TRUE(fs::exists(out / "root_blob_5.vtu"));
  EXPECT_FALSE(fs::exists(out / "root_blob_6.vtu"));
  EXPECT_TRUE(json::parse(testing::read_file_bytes(dir / "state.json"))["steps"].contains("3"));
  // Without the bound the same run goes on (the state is still finite after 8 steps).
  const CommandResult unbounded =
      run_fastcorot("run " + scene.string() + " --steps 8 --quiet --divergence-factor 0");
  EXPECT_EQ(unbounded.status, 0) << unbounded.output;
}

}  // namespace
}  // namespace fastcorot
