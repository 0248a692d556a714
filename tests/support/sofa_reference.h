// Loads SOFA's own outputs for the deformed single tetrahedron (tests/data/sofa_reference, copied
// from shared/sofa-reference: SOFA master 2a278d891f, double precision).
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

namespace fastcorot::testing {

struct SofaSingleTetCase {
  nlohmann::json raw;
  std::vector<Vec3<double>> rest, x, dx, force, dforce;
  std::vector<Tetrahedron> tetrahedra;
  std::vector<Edge> edges;
  Eigen::MatrixXd stiffness;  // 12×12, row = 3·vertex + axis
};

inline std::string sofa_reference_path(const std::string& file) {
  return std::string(FASTCOROT_SOFA_REFERENCE_DIR) + "/" + file;
}

inline std::vector<Vec3<double>> json_points(const nlohmann::json& list) {
  std::vector<Vec3<double>> points;
  for (const auto& p : list) points.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  return points;
}

// A trajectory SOFA dumped (sofaContactRun, tests/data/sofa_reference/*_trajectory.json).
inline nlohmann::json load_sofa_trajectory(const std::string& file) {
  std::ifstream in(sofa_reference_path(file));
  return nlohmann::json::parse(in);
}

// The dumped steps (the keys of reference["steps"]) in numeric order.
inline std::vector<long> dumped_steps(const nlohmann::json& reference) {
  std::vector<long> steps;
  for (const auto& item : reference["steps"].items()) steps.push_back(std::stol(item.key()));
  std::sort(steps.begin(), steps.end());
  return steps;
}

// The largest distance between x and SOFA's points, and SOFA's largest displacement from `rest`.
struct TrajectoryDifference {
  double difference = 0, displacement = 0;
};
inline TrajectoryDifference compare_points(const std::vector<Vec3<double>>& x, const std::vector<Vec3<double>>& expected,
                                           const std::vector<Vec3<double>>& rest) {
  TrajectoryDifference d;
  for (std::size_t i = 0; i < expected.size() && i < x.size(); ++i) {
    d.difference = std::max(d.difference, (x[i] - expected[i]).norm());
    d.displacement = std::max(d.displacement, (expected[i] - rest[i]).norm());
  }
  return d;
}

inline SofaSingleTetCase load_sofa_single_tet(const std::string& method) {
  std::ifstream in(sofa_reference_path("single_tet_" + method + ".json"));
  SofaSingleTetCase c;
  c.raw = nlohmann::json::parse(in);
  c.rest = json_points(c.raw["rest"]);
  c.x = json_points(c.raw["x"]);
  c.dx = json_points(c.raw["dx"]);
  c.force = json_points(c.raw["force"]);
  c.dforce = json_points(c.raw["dforce"]);
  for (const auto& t : c.raw["tetrahedra"]) c.tetrahedra.push_back(t.get<Tetrahedron>());
  for (const auto& e : c.raw["edges"]) c.edges.push_back(e.get<Edge>());
  const auto& k = c.raw["K"];
  c.stiffness.resize(static_cast<Eigen::Index>(k.size()), static_cast<Eigen::Index>(k.size()));
  for (std::size_t i = 0; i < k.size(); ++i) {
    for (std::size_t j = 0; j < k.size(); ++j) {
      c.stiffness(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = k[i][j].get<double>();
    }
  }
  return c;
}

}  // namespace fastcorot::testing
