// `fastcorot probe` against SOFA's single-tetrahedron outputs, in-process and through the
// executable, and its handling of bad input (clear message, exit status 2).
#include "probe_command.h"

#include "fastcorot/core/error.h"
#include "support/sofa_reference.h"

#include "support/command.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fastcorot {
namespace {

using nlohmann::json;

json probe_case_from_sofa(const testing::SofaSingleTetCase& c) {
  return {{"points", c.raw["rest"]},         {"tetrahedra", c.raw["tetrahedra"]},
          {"youngModulus", c.raw["youngModulus"]}, {"poissonRatio", c.raw["poissonRatio"]},
          {"method", c.raw["method"]},       {"x", c.raw["x"]},
          {"dx", c.raw["dx"]},               {"kFactor", 1}};
}

double max_abs(const json& a) {
  double m = 0;
  for (const auto& row : a) {
    for (const auto& v : row) m = std::max(m, std::abs(v.get<double>()));
  }
  return m;
}

double max_diff(const json& a, const json& b) {
  double m = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (std::size_t j = 0; j < b[i].size(); ++j) m = std::max(m, std::abs(a[i][j].get<double>() - b[i][j].get<double>()));
  }
  return m;
}

void expect_matches_sofa(const json& out, const testing::SofaSingleTetCase& c) {
  EXPECT_LT(max_diff(out["force"], c.raw["force"]), 1e-9 * max_abs(c.raw["force"]));
  EXPECT_LT(max_diff(out["dforce"], c.raw["dforce"]), 1e-9 * max_abs(c.raw["dforce"]));
  ASSERT_EQ(out["stiffness"]["size"].get<int>(), 12);
  json dense = json::array();
  for (int i = 0; i < 12; ++i) dense.push_back(std::vector<double>(12, 0.0));
  for (const auto& t : out["stiffness"]["triplets"]) {
    dense[t[0].get<std::size_t>()][t[1].get<std::size_t>()] = dense[t[0].get<std::size_t>()][t[1].get<std::size_t>()].get<double>() + t[2].get<double>();
  }
  EXPECT_LT(max_diff(dense, c.raw["K"]), 1e-9 * max_abs(c.raw["K"]));
  EXPECT_EQ(out["edges"], c.raw["edges"]);
  ASSERT_EQ(out["restVolume"].size(), 1u);
  EXPECT_NEAR(out["restVolume"][0].get<double>(), 1.0 / 6.0, 1e-15);
  ASSERT_EQ(out["rotations"].size(), 1u);
  EXPECT_EQ(out["rotations"][0].size(), 3u);
  EXPECT_TRUE(out["energy"].is_number());
  EXPECT_GT(out["energy"].get<double>(), 0.0);
}

class ProbeSofa : public ::testing::TestWithParam<std::string> {};

TEST_P(ProbeSofa, InProcessMatchesSofa) {
  const auto c = testing::load_sofa_single_tet(GetParam());
  expect_matches_sofa(cli::probe(probe_case_from_sofa(c), "case"), c);
}

using testing::CommandResult;
using testing::run_fastcorot;

std::string write_case(const std::string& name, const std::string& text) {
  std::filesystem::create_directories(FASTCOROT_TEST_OUTPUT_DIR);
  const std::string path = std::string(FASTCOROT_TEST_OUTPUT_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST_P(ProbeSofa, ExecutableRoundTripMatchesSofa) {
  const auto c = testing::load_sofa_single_tet(GetParam());
  const std::string input = write_case("probe_" + GetParam() + ".json", probe_case_from_sofa(c).dump());
  const std::string output = std::string(FASTCOROT_TEST_OUTPUT_DIR) + "/probe_" + GetParam() + "_out.json";
  std::filesystem::remove(output);
  const CommandResult to_file = run_fastcorot("probe " + input + " -o " + output);
  ASSERT_EQ(to_file.status, 0) << to_file.output;
  std::ifstream in(output);
  expect_matches_sofa(json::parse(in), c);
  const CommandResult to_stdout = run_fastcorot("probe " + input);
  ASSERT_EQ(to_stdout.status, 0) << to_stdout.output;
  expect_matches_sofa(json::parse(to_stdout.output), c);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, ProbeSofa, ::testing::Values("qr", "polar", "polar2", "none"));

TEST(Probe, DefaultsAreSofasAndXDefaultsToPoints) {
  const json input = {{"points", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {"tetrahedra", {{0, 1, 2, 3}}}};
  const json out = cli::probe(input, "case");
  for (const auto& f : out["force"]) {
    for (const auto& v : f) EXPECT_EQ(v.get<double>(), 0.0);
  }
  EXPECT_FALSE(out.contains("dforce"));
  EXPECT_EQ(out["energy"].get<double>(), 0.0);
  // E = 5000, nu = 0.45 (SOFA's defaults): vertex block D_3 of the unit tetrahedron in order
  // (0,1,2,3) has s_0 = (-1,-1,-1), so K(0,0) = -((lambda + mu) + 3 mu) / 6.
  const double mu = 5000 / 2.9, lambda = 5000 * 0.45 / (1.45 * 0.1);
  for (const auto& t : out["stiffness"]["triplets"]) {
    if (t[0] == 0 && t[1] == 0) {
      EXPECT_NEAR(t[2].get<double>(), -(lambda + 4 * mu) / 6, 1e-9);
    }
  }
}

TEST(Probe, ExplicitEdgesChangeNothingButTheEdgeList) {
  const auto c = testing::load_sofa_single_tet("qr");
  json input = probe_case_from_sofa(c);
  input["edges"] = {{3, 2}, {0, 1}, {2, 1}, {3, 1}, {0, 2}, {3, 0}};
  const json out = cli::probe(input, "case");
  json same_edges = out;
  same_edges["edges"] = c.raw["edges"];
  expect_matches_sofa(same_edges, c);
  EXPECT_EQ(out["edges"], input["edges"]);
}

TEST(Probe, BadInputGivesAClearMessageAndStatus2) {
  const std::string tet = R"("points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "tetrahedra": [[0,1,2,3]])";
  const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> all = [&] {
    std::vector<std::pair<std::string, std::pair<std::string, std::string>>> list;
    list.push_back({"malformed", {"{\"points\": [[0,0,0]", "malformed JSON"}});
    list.push_back({"not_object", {"[1, 2]", "JSON object"}});
    list.push_back({"missing_points", {R"({"tetrahedra": [[0,1,2,3]]})", "missing key \"points\""}});
    list.push_back({"missing_tetrahedra", {R"({"points": [[0,0,0]]})", "missing key \"tetrahedra\""}});
    list.push_back({"short_point", {R"({"points": [[0,0,0],[1,0]], "tetrahedra": []})", "\"points\"[1]"}});
    list.push_back({"string_coordinate", {R"({"points": [[0,0,"a"]], "tetrahedra": []})", "expected a number"}});
    list.push_back({"short_tet", {R"({"points": [[0,0,0]], "tetrahedra": [[0,1,2]]})", "\"tetrahedra\"[0]"}});
    list.push_back({"negative_index", {R"({"points": [[0,0,0]], "tetrahedra": [[0,1,2,-1]]})", "non-negative"}});
    list.push_back({"index_out_of_range", {R"({"points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "tetrahedra": [[0,1,2,4]]})", "out of range"}});
    list.push_back({"repeated_vertex", {R"({"points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "tetrahedra": [[0,1,2,2]]})", "repeats"}});
    list.push_back({"degenerate", {R"({"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]], "tetrahedra": [[0,1,2,3]]})", "tetrahedron 0"}});
    list.push_back({"empty", {R"({"points": [[0,0,0]], "tetrahedra": []})", "no tetrahedra"}});
    list.push_back({"bad_method", {"{" + tet + R"(, "method": "svd"})", "method = \"svd\""}});
    list.push_back({"bad_young", {"{" + tet + R"(, "youngModulus": -1})", "youngModulus = -1"}});
    list.push_back({"bad_poisson", {"{" + tet + R"(, "poissonRatio": 0.5})", "poissonRatio = 0.5"}});
    list.push_back({"young_list_length", {"{" + tet + R"(, "youngModulus": [1, 2]})", "youngModulus: 2 values"}});
    list.push_back({"x_wrong_count", {"{" + tet + R"(, "x": [[0,0,0]]})", "\"x\" has 1 points"}});
    list.push_back({"dx_wrong_shape", {"{" + tet + R"(, "dx": 3})", "\"dx\""}});
    list.push_back({"kfactor_string", {"{" + tet + R"(, "kFactor": "one"})", "\"kFactor\""}});
    list.push_back({"unknown_key", {"{" + tet + R"(, "youngModulu": 3})", "unknown key \"youngModulu\""}});
    list.push_back({"missing_edge", {"{" + tet + R"(, "edges": [[0,1],[0,2],[0,3],[1,2],[1,3]]})", "missing from the edge list"}});
    return list;
  }();
  for (const auto& [name, body] : all) {
    const std::string path = write_case("bad_" + name + ".json", body.first);
    const CommandResult result = run_fastcorot("probe " + path);
    EXPECT_EQ(result.status, 2) << name << ": " << result.output;
    EXPECT_NE(result.output.find(body.second), std::string::npos) << name << ": " << result.output;
    EXPECT_NE(result.output.find(path), std::string::npos) << name << " does not name the file: " << result.output;
  }
}

TEST(Probe, MissingFileAndBadCommandLineExitWith2) {
  const CommandResult missing = run_fastcorot("probe /nonexistent/case.json");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("/nonexistent/case.json: cannot open"), std::string::npos) << missing.output;
  EXPECT_EQ(run_fastcorot("probe").status, 2);
  EXPECT_EQ(run_fastcorot("frobnicate").status, 2);
  const CommandResult unwritable = run_fastcorot("probe " + write_case("ok.json", R"({"points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "tetrahedra": [[0,1,2,3]]})") +
                             " -o /nonexistent/dir/out.json");
  EXPECT_EQ(unwritable.status, 2);
  EXPECT_NE(unwritable.output.find("cannot open for writing"), std::string::npos) << unwritable.output;
}

}  // namespace
}  // namespace fastcorot
