// Replays every input the fuzzers found (tests/data/fuzz/TARGET/, docs/robustness.md "Fuzzing") through the
// very function the fuzz target runs (fuzz/fuzz_targets.h): each must be read or refused with a
// fastcorot::Error, nothing else escaping. The fuzzers themselves run by hand (scripts/fuzz).
#include "fuzz_targets.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

namespace fastcorot {
namespace {

namespace fs = std::filesystem;

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Replays the inputs of one target; returns how many there were.
int replay(const std::string& target, const std::function<void(std::string_view)>& run) {
  int count = 0;
  const fs::path folder = fs::path(FASTCOROT_TEST_DATA_DIR) / "fuzz" / target;
  if (!fs::is_directory(folder)) return 0;  // no finding for this target (git keeps no empty folder)
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
    SCOPED_TRACE(entry.path().string());
    const std::string bytes = file_bytes(entry.path());
    EXPECT_NO_THROW(run(bytes));
    ++count;
  }
  return count;
}

TEST(FuzzRegression, SceneInputs) {
  replay("scene", [](std::string_view text) { fuzz::scene(text, FASTCOROT_EXAMPLES_DIR); });
}

TEST(FuzzRegression, GmshInputs) { replay("gmsh", fuzz::gmsh); }

TEST(FuzzRegression, VtkLegacyInputs) { replay("vtk_legacy", fuzz::vtk_legacy); }

TEST(FuzzRegression, VtuInputs) { replay("vtu", fuzz::vtu); }

TEST(FuzzRegression, ProbeJsonInputs) { EXPECT_GE(replay("probe_json", fuzz::probe_json), 1); }

// The first finding: nlohmann::json reports a number beyond double's range as out_of_range, not
// parse_error, and it escaped as an unknown exception.
TEST(FuzzRegression, NumberTooLargeIsMalformedJson) {
  try {
    cli::parse_json("{\"points\": [[7, 154E77777]]}", "case.json");
    FAIL() << "expected fastcorot::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("case.json: malformed JSON"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fastcorot
