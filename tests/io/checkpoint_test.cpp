// Checkpoints (include/fastcorot/io/checkpoint.h): a run stopped at step K and resumed from its
// checkpoint continues bitwise as the uninterrupted run; a damaged, foreign, other-version or
// other-scene checkpoint is refused with a message naming what is wrong, and changes nothing.
#include "fastcorot/io/checkpoint.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"
#include "support/deformations.h"

#include "support/file_bytes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace fastcorot {
namespace {

namespace fs = std::filesystem;
using testing::flatten;

// Two objects under two kinds of solver: a CG one (with a constant force and a stopping tolerance
// of 1, so that only the first solve of the CG instance iterates: the solve count it carries
// changes the trajectory) and a direct one with the polar method.
struct SceneText {
  std::string cg_name = "cg";
  std::string grid_n = "3 3 3";
  std::string grid_max = "1 1 2";
  std::string young = "2000";
  std::string dt = "0.01";
  std::string cg_tolerance = "1e-10";
  std::string solver;  // replaces the CGLinearSolver when set
};

std::string scene_text(const SceneText& s) {
  return R"(<Node name="root" dt=")" + s.dt + R"(" gravity="0 0 -9.81">
  <Node name=")" +
         s.cg_name + R"(">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    )" + (s.solver.empty() ? R"(<CGLinearSolver iterations="30" tolerance=")" + s.cg_tolerance + R"(" threshold="1e-20"/>)"
                           : s.solver) +
         R"(
    <RegularGridTopology name="grid" n=")" +
         s.grid_n + R"(" min="0 0 0" max=")" + s.grid_max + R"("/>
    <MechanicalObject/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets"/>
    <DiagonalMass massDensity="100"/>
    <FastTetrahedralCorotationalForceField youngModulus=")" +
         s.young + R"(" poissonRatio="0.3" method="large"/>
    <FixedProjectiveConstraint indices="0 1 2"/>
    <ConstantForceField indices="26" force="5 0 0"/>
  </Node>
  <Node name="direct">
    <EulerImplicitSolver rayleighStiffness="0.05"/>
    <EigenSimplicialLDLT/>
    <RegularGridTopology name="grid" n="3 2 4" min="3 0 0" max="4 1 3"/>
    <MechanicalObject velocity="0 1 0"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets"/>
    <UniformMass totalMass="2"/>
    <FastTetrahedralCorotationalForceField youngModulus="800" poissonRatio="0.4" method="polar"/>
    <FixedProjectiveConstraint indices="0 1"/>
  </Node>
</Node>)";
}

Simulation<double> build(const SceneText& s = {}) {
  return build_scene(parse_scene_text(scene_text(s), "checkpoint_test.scn")).simulation;
}

fs::path folder() {
  const fs::path dir = fs::temp_directory_path() / ("fastcorot_checkpoint_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

void run_to(Simulation<double>& simulation, long step) {
  while (simulation.steps_done() < step) simulation.step();
}

void expect_same_state(const Simulation<double>& a, const Simulation<double>& b) {
  ASSERT_EQ(a.objects.size(), b.objects.size());
  EXPECT_EQ(a.steps_done(), b.steps_done());
  EXPECT_EQ(a.time(), b.time());
  for (std::size_t o = 0; o < a.objects.size(); ++o) {
    // Exact equality of every double: bitwise for finite values.
    EXPECT_EQ(flatten(a.objects[o].system.state.position),
              flatten(b.objects[o].system.state.position))
        << o;
    EXPECT_EQ(flatten(a.objects[o].system.state.velocity),
              flatten(b.objects[o].system.state.velocity))
        << o;
  }
}

// The message of the Error restore_checkpoint throws; checks that the simulation was left alone.
std::string refusal(const fs::path& path, const SceneText& s = {}) {
  Simulation<double> simulation = build(s);
  const Simulation<double> untouched = build(s);
  try {
    restore_checkpoint(path, simulation);
  } catch (const Error& error) {
    expect_same_state(simulation, untouched);
    return error.what();
  }
  ADD_FAILURE() << path << " was accepted";
  return {};
}

fs::path checkpoint_at(long step, const std::string& name, const SceneText& s = {}) {
  Simulation<double> simulation = build(s);
  run_to(simulation, step);
  const fs::path path = folder() / name;
  write_checkpoint(path, simulation, "checkpoint_test.scn");
  return path;
}

TEST(Checkpoint, AResumedRunIsBitwiseTheUninterruptedOne) {
  for (const long k : {0L, 1L, 7L}) {
    Simulation<double> uninterrupted = build();
    run_to(uninterrupted, 15);
    const fs::path path = checkpoint_at(k, "resume.ckpt");
    Simulation<double> resumed = build();
    restore_checkpoint(path, resumed);
    EXPECT_EQ(resumed.steps_done(), k);
    run_to(resumed, 15);
    expect_same_state(resumed, uninterrupted);
    // The objects moved, so the comparison means something.
    EXPECT_NE(flatten(resumed.objects[0].system.state.position),
              flatten(build().objects[0].system.state.position));
  }
}

// Runs the scene to step `last` uninterrupted and, from a checkpoint after step `at`, resumed: the
// same bits. Then again from the checkpoint with the linear solver's carried state spoilt by
// `forget`, which must leave the uninterrupted trajectory (so the carried state is what matters).
void expect_carried_state_matters(const SceneText& s, long at, long last, const std::string& name,
                                  const std::function<void(Simulation<double>&)>& forget) {
  Simulation<double> uninterrupted = build(s);
  run_to(uninterrupted, last);
  const fs::path path = checkpoint_at(at, name, s);
  Simulation<double> resumed = build(s);
  restore_checkpoint(path, resumed);
  run_to(resumed, last);
  expect_same_state(resumed, uninterrupted);
  Simulation<double> forgetful = build(s);
  restore_checkpoint(path, forgetful);
  forget(forgetful);
  run_to(forgetful, last);
  EXPECT_NE(flatten(forgetful.objects[0].system.state.position),
            flatten(uninterrupted.objects[0].system.state.position));
}

TEST(Checkpoint, TheCarriedSolverStateIsWhatMakesItBitwise) {
  // With tolerance 1, the CG iterates only on the first solve of its instance; a resumed run that
  // forgot the solve count would iterate once more and leave the uninterrupted trajectory.
  SceneText s;
  s.cg_tolerance = "1";
  expect_carried_state_matters(s, 3, 6, "carried.ckpt", [](Simulation<double>& forgetful) {
    forgetful.objects[0].linear_solver->restore_carried_state({0});
  });
}

TEST(Checkpoint, APreconditionedSolverResumesFromItsPreviousSolutionAndBlocks) {
  // PCGLinearSolver starts each solve from the previous one's solution and, with update_step 2,
  // keeps its block-Jacobi preconditioner for two solves: both travel in the checkpoint.
  SceneText s;
  s.solver = R"(<PCGLinearSolver iterations="4" tolerance="1e-30" preconditioner="@P" update_step="2"/>
    <BlockJacobiPreconditioner name="P"/>)";
  expect_carried_state_matters(s, 3, 6, "pcg.ckpt", [](Simulation<double>& forgetful) {
    // The previous solution and the blocks zeroed.
    auto state = forgetful.objects[0].linear_solver->carried_state();
    std::fill(state.begin() + 1, state.end(), 0);
    forgetful.objects[0].linear_solver->restore_carried_state(state);
  });
}

TEST(Checkpoint, ASparseDirectPreconditionerResumesFromTheMatrixItFactorised) {
  // With update_step 3 the factorisation of step 3's matrix serves steps 4 and 5: the checkpoint
  // after step 4 carries that matrix, and the resumed run factorises it again, to the same bits.
  SceneText s;
  s.solver = R"(<PCGLinearSolver iterations="3" tolerance="1e-30" preconditioner="@L" update_step="3"/>
    <SparseLDLSolver name="L"/>)";
  expect_carried_state_matters(s, 4, 7, "pcg_ldl.ckpt", [&](Simulation<double>& forgetful) {
    // A solver starting afresh at step 4 (factorising step 4's matrix, from a zero start).
    Simulation<double> fresh = build(s);
    forgetful.objects[0].linear_solver = std::move(fresh.objects[0].linear_solver);
  });
}

TEST(Checkpoint, EveryFlippedByteIsRefused) {
  const std::string good = testing::read_file_bytes(checkpoint_at(4, "flip_source.ckpt"));
  const fs::path path = folder() / "flipped.ckpt";
  ASSERT_GT(good.size(), 1000u);
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ 0xff);
    testing::write_file_bytes(path, bad);
    const std::string message = refusal(path);
    EXPECT_NE(message.find(path.string()), std::string::npos) << "byte " << i << ": " << message;
    if (i >= 24 && i < good.size() - 8) {
      EXPECT_NE(message.find("corrupt checkpoint"), std::string::npos)
          << "byte " << i << ": " << message;
    }
  }
}

TEST(Checkpoint, TruncatedFilesAreRefused) {
  const std::string good = testing::read_file_bytes(checkpoint_at(2, "truncate_source.ckpt"));
  const fs::path path = folder() / "truncated.ckpt";
  for (const std::size_t size :
       {std::size_t(0), std::size_t(3), std::size_t(8), std::size_t(23), std::size_t(24),
        good.size() / 2, good.size() - 8, good.size() - 1}) {
    testing::write_file_bytes(path, good.substr(0, size));
    const std::string message = refusal(path);
    EXPECT_NE(message.find("truncated"), std::string::npos) << size << " bytes: " << message;
  }
}

TEST(Checkpoint, OtherFormatVersionsAndOtherFilesAreRefusedAsSuch) {
  std::string bytes = testing::read_file_bytes(checkpoint_at(2, "version_source.ckpt"));
  const fs::path path = folder() / "version.ckpt";
  bytes[8] = 3;  // the u32 version at offset 8, little-endian
  testing::write_file_bytes(path, bytes);
  EXPECT_NE(refusal(path).find("checkpoint format version 3; this fastcorot reads versions 1 and 2 only"),
            std::string::npos)
      << refusal(path);
  testing::write_file_bytes(path, "<?xml version=\"1.0\"?>\n<VTKFile/>\n");
  EXPECT_NE(refusal(path).find("not a fastcorot checkpoint"), std::string::npos) << refusal(path);
  EXPECT_NE(refusal(folder() / "does_not_exist.ckpt").find("cannot open"), std::string::npos);
}

TEST(Checkpoint, ACheckpointOfAnotherSceneIsRefusedNamingTheDifference) {
  const fs::path path = checkpoint_at(3, "scene.ckpt");
  SceneText renamed;
  renamed.cg_name = "beam";
  EXPECT_NE(
      refusal(path, renamed).find("object 0 is \"root/cg\"; in this scene it is \"root/beam\""),
      std::string::npos)
      << refusal(path, renamed);
  SceneText finer;
  finer.grid_n = "4 3 3";  // 36 vertices instead of 27
  EXPECT_NE(refusal(path, finer).find("root/cg has 27 vertices; in this scene it has 36"),
            std::string::npos)
      << refusal(path, finer);
  SceneText longer;
  longer.grid_max = "1 1 3";
  EXPECT_NE(refusal(path, longer).find("other rest positions"), std::string::npos)
      << refusal(path, longer);
  SceneText stiffer;
  stiffer.young = "3000";
  EXPECT_NE(refusal(path, stiffer).find("another model"), std::string::npos)
      << refusal(path, stiffer);
  SceneText finer_time;
  finer_time.dt = "0.005";
  EXPECT_NE(refusal(path, finer_time).find("dt = 0.01"), std::string::npos)
      << refusal(path, finer_time);
  // Every refusal says which scene the checkpoint was made for.
  EXPECT_NE(refusal(path, stiffer).find("written for scene \"checkpoint_test.scn\""),
            std::string::npos);
}

// A version-1 file (before rigid bodies: no orientation count after each object) still resumes: the
// version-2 file of the same run with those counts taken out, its header and checksum redone.
TEST(Checkpoint, AVersionOneCheckpointStillResumes) {
  std::string bytes = testing::read_file_bytes(checkpoint_at(4, "version_two.ckpt"));
  // Each object's rigid count (u64 zero) ends its record: before the next object's path (a u32
  // length, then "root/direct") and before the checksum.
  const std::size_t second = bytes.find("root/direct");
  ASSERT_NE(second, std::string::npos);
  const std::size_t end = bytes.size() - 8;
  ASSERT_EQ(bytes.substr(end - 8, 8), std::string(8, '\0'));
  ASSERT_EQ(bytes.substr(second - 12, 8), std::string(8, '\0'));
  bytes.erase(end - 8, 8);
  bytes.erase(second - 12, 8);
  bytes[8] = 1;
  const std::uint64_t size = bytes.size();
  for (int i = 0; i < 8; ++i) bytes[16 + static_cast<std::size_t>(i)] = static_cast<char>((size >> (8 * i)) & 0xff);
  const std::uint64_t sum = fnv1a64(bytes.data(), bytes.size() - 8);
  for (int i = 0; i < 8; ++i) bytes[bytes.size() - 8 + static_cast<std::size_t>(i)] = static_cast<char>((sum >> (8 * i)) & 0xff);
  const fs::path path = folder() / "version_one.ckpt";
  testing::write_file_bytes(path, bytes);
  Simulation<double> uninterrupted = build();
  run_to(uninterrupted, 9);
  Simulation<double> resumed = build();
  restore_checkpoint(path, resumed);
  EXPECT_EQ(resumed.steps_done(), 4);
  run_to(resumed, 9);
  expect_same_state(resumed, uninterrupted);
}

TEST(Checkpoint, TheFileStartsWithTheDocumentedHeader) {
  const std::string bytes = testing::read_file_bytes(checkpoint_at(1, "header.ckpt"));
  ASSERT_GE(bytes.size(), 32u);
  EXPECT_EQ(bytes.substr(0, 8), "FCOROTCK");
  EXPECT_EQ(bytes.substr(8, 4), std::string("\x02\x00\x00\x00", 4));   // version 2
  EXPECT_EQ(bytes.substr(12, 4), std::string("\x08\x00\x00\x00", 4));  // 8-byte reals
  std::uint64_t size = 0;
  for (int i = 0; i < 8; ++i)
    size |= std::uint64_t(static_cast<unsigned char>(bytes[16 + i])) << (8 * i);
  EXPECT_EQ(size, bytes.size());
  // FNV-1a 64 of "a" is 0xaf63dc4c8601ec8c (the published test vector).
  EXPECT_EQ(fnv1a64("a", 1), 0xaf63dc4c8601ec8cull);
}

}  // namespace
}  // namespace fastcorot
