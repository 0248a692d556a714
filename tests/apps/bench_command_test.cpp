// `fastcorot bench`: the figures it prints (JSON) are consistent with each other and with the scene,
// and bad options are clear errors with exit status 2. (Its speed is measured by hand, never here.)
#include "support/command.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace fastcorot {
namespace {

using nlohmann::json;
using testing::run_fastcorot;

TEST(Bench, JsonFiguresAddUpAndDescribeTheBeam) {
  const auto result = run_fastcorot("bench --beam 9x3x3 --steps 4 --warmup 1 --threads 2 --json");
  ASSERT_EQ(result.status, 0) << result.output;
  const json figures = json::parse(result.output);
  EXPECT_EQ(figures["points"], 9 * 3 * 3);
  EXPECT_EQ(figures["tetrahedra"], 6 * 8 * 2 * 2);  // 8 x 2 x 2 cells, 6 tetrahedra each (Hexa2Tetra)
  EXPECT_EQ(figures["steps"], 4);
  EXPECT_EQ(figures["threads"], 2);
  const json& ms = figures["ms_per_step"];
  double phases = 0;
  for (const char* phase : {"add_force", "stiffness_refresh", "matrix_vector", "solver_vectors", "mass_constraints",
                            "output", "other"}) {
    ASSERT_TRUE(ms.contains(phase)) << phase;
    EXPECT_GE(ms[phase].get<double>(), 0.0) << phase;
    phases += ms[phase].get<double>();
  }
  EXPECT_GE(phases, 0.999 * ms["total"].get<double>());
  EXPECT_GT(ms["add_force"].get<double>(), 0.0);
  EXPECT_GT(ms["matrix_vector"].get<double>(), 0.0);
  EXPECT_EQ(ms["output"].get<double>(), 0.0);  // nothing written without --vtu
  EXPECT_NEAR(figures["steps_per_second"].get<double>() * figures["seconds"].get<double>(), 4.0, 1e-9);
  EXPECT_GT(figures["force_field_bytes_per_tetrahedron"].get<double>(), 0.0);
  EXPECT_GT(figures["peak_memory_bytes"].get<double>(), figures["force_field_bytes"].get<double>());
  EXPECT_EQ(figures["renumbered_force_fields"], 0);  // a grid's numbering is local
  // The machine beside the figures: the build's vector instructions run on this CPU, so they are
  // among the CPU's (the sets are ordered by width).
  const std::vector<std::string> widths = {"none", "SSE2", "AVX2", "AVX-512"};
  const auto rank = [&](const json& name) {
    return std::find(widths.begin(), widths.end(), name.get<std::string>()) - widths.begin();
  };
  ASSERT_LT(rank(figures["build_vector_instructions"]), 4) << figures["build_vector_instructions"];
  ASSERT_LT(rank(figures["cpu_vector_instructions"]), 4) << figures["cpu_vector_instructions"];
  EXPECT_LE(rank(figures["build_vector_instructions"]), rank(figures["cpu_vector_instructions"]));
#if defined(__x86_64__)
  EXPECT_NE(figures["build_vector_instructions"], "none");  // x86-64 has SSE2 at least
#endif
  EXPECT_TRUE(figures["cpu"].is_string());
  // Two threads: how long a handshake between them took (positive, below the 100 ms allowed for
  // them all), or null where a busy machine (tests running side by side) left no time for one.
  const json& round_trip = figures["thread_round_trip_ns"];
  ASSERT_TRUE(round_trip.is_number() || round_trip.is_null()) << round_trip;
  if (round_trip.is_number()) {
    EXPECT_GT(round_trip.get<double>(), 0.0);
    EXPECT_LT(round_trip.get<double>(), 1e8);
  }
}

TEST(Bench, RoundTripOnlyWithThreads) {
  const auto result = run_fastcorot("bench --beam 5x2x2 --steps 2 --threads 1 --json");
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_TRUE(json::parse(result.output)["thread_round_trip_ns"].is_null());
  const auto one = run_fastcorot("bench --beam 5x2x2 --steps 2 --threads 1");
  ASSERT_EQ(one.status, 0) << one.output;
  EXPECT_EQ(one.output.find("\nthreads: "), std::string::npos) << one.output;
  const auto text = run_fastcorot("bench --beam 5x2x2 --steps 2 --threads 2");
  ASSERT_EQ(text.status, 0) << text.output;
  EXPECT_NE(text.output.find("\nthreads: "), std::string::npos) << text.output;
}

TEST(Bench, VtuFramesAreTimedAsOutput) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / "bench_vtu";
  std::filesystem::remove_all(dir);
  const auto result = run_fastcorot("bench --beam 5x2x2 --steps 3 --warmup 0 --json --vtu " + dir.string());
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_GT(json::parse(result.output)["ms_per_step"]["output"].get<double>(), 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "object0_3.vtu"));
}

TEST(Bench, TextReportNamesEveryPhase) {
  const auto result = run_fastcorot("bench --beam 5x2x2 --steps 2");
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* phase : {"steps/s", "add_force", "stiffness refresh", "matrix-vector", "solver vectors",
                            "mass/constraints", "output", "bytes per tetrahedron", "vector instructions"}) {
    EXPECT_NE(result.output.find(phase), std::string::npos) << phase << " in\n" << result.output;
  }
}

TEST(Bench, ThreadsAbsentOrZeroMeanOnePer2000PointsAtMostEveryCore) {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (const char* threads : {"", " --threads 0"}) {
    // 20 points: one thread; 6,000: three, or every core when there are fewer.
    for (const auto& [beam, expected] : {std::pair<std::string, int>{"5x2x2", 1}, {"60x10x10", std::min(cores, 3)}}) {
      const auto result = run_fastcorot("bench --beam " + beam + " --steps 1 --warmup 0 --json" + threads);
      ASSERT_EQ(result.status, 0) << result.output;
      EXPECT_EQ(json::parse(result.output)["threads"], expected) << beam << threads;
    }
  }
}

TEST(Bench, BadOptionsAreErrors) {
  for (const auto& [arguments, message] :
       std::initializer_list<std::pair<const char*, const char*>>{
           {"bench --beam 40x10", "--beam \"40x10\": expected NXxNYxNZ"},
           {"bench --beam 1x10x10", "three numbers of grid points >= 2"},
           {"bench --steps 0", "--steps 0: must be >= 1"},
           {"bench --threads -1", "--threads -1: must be >= 1 (or 0: fastcorot's choice)"},
           {"bench --beam 4x4x4 some.scn", "--beam replaces SCENE"},
           {"bench missing.scn", "missing.scn"}}) {
    const auto result = run_fastcorot(arguments);
    EXPECT_EQ(result.status, 2) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(message), std::string::npos) << arguments << "\n" << result.output;
  }
}

}  // namespace
}  // namespace fastcorot
