#include "probe_command.h"

#include "json_io.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/corotational_force_field.h"

#include <set>

namespace fastcorot::cli {

namespace {

const std::set<std::string> kKeys = {"points", "tetrahedra", "youngModulus", "poissonRatio", "method",
                                     "x",      "dx",         "kFactor",      "edges"};

std::string accepted_keys() {
  std::string list;
  for (const auto& key : kKeys) list += (list.empty() ? "" : ", ") + key;
  return list;
}

const json& require(const json& input, const std::string& key) {
  if (!input.contains(key)) throw make_error("missing key \"", key, "\"");
  return input.at(key);
}

std::vector<Vec3<double>> read_positions(const json& input, const std::string& key, std::size_t count) {
  auto positions = read_points(input.at(key), "\"" + key + "\"");
  if (positions.size() != count) {
    throw make_error("\"", key, "\" has ", positions.size(), " points; \"points\" has ", count);
  }
  return positions;
}

json evaluate(const json& input) {
  if (!input.is_object()) throw make_error("expected a JSON object at the top level");
  for (const auto& [key, value] : input.items()) {
    if (!kKeys.contains(key)) {
      throw make_error("unknown key \"", key, "\"; accepted keys: ", accepted_keys());
    }
  }
  const auto points = read_points(require(input, "points"), "\"points\"");
  auto tetrahedra = read_tetrahedra(require(input, "tetrahedra"), "\"tetrahedra\"");
  const auto num_points = static_cast<Index>(points.size());

  CorotationalForceField<double>::Parameters parameters;
  if (input.contains("youngModulus")) {
    parameters.young_modulus = read_number_or_list(input["youngModulus"], "\"youngModulus\"");
  }
  if (input.contains("poissonRatio")) {
    parameters.poisson_ratio = read_number_or_list(input["poissonRatio"], "\"poissonRatio\"");
  }
  if (input.contains("method")) {
    if (!input["method"].is_string()) {
      throw make_error("\"method\": expected a string, got ", input["method"].dump());
    }
    parameters.method = parse_rotation_method(input["method"].get<std::string>());
  }
  const double k_factor = input.contains("kFactor") ? read_number(input["kFactor"], "\"kFactor\"") : 1.0;
  const auto x = input.contains("x") ? read_positions(input, "x", points.size()) : points;

  const auto mesh = input.contains("edges")
                        ? std::make_shared<TetMesh>(num_points, std::move(tetrahedra),
                                                    read_edges(input["edges"], "\"edges\""))
                        : std::make_shared<TetMesh>(num_points, std::move(tetrahedra));
  CorotationalForceField<double> field(mesh, points, parameters);

  std::vector<Vec3<double>> force(points.size(), Vec3<double>::Zero());
  field.add_force(x, force);

  json output;
  output["force"] = points_to_json(force);
  if (input.contains("dx")) {
    const auto dx = read_positions(input, "dx", points.size());
    std::vector<Vec3<double>> dforce(points.size(), Vec3<double>::Zero());
    field.add_dforce(dx, dforce, k_factor);
    output["dforce"] = points_to_json(dforce);
  }
  output["energy"] = field.potential_energy(x);

  Eigen::SparseMatrix<double, Eigen::RowMajor> stiffness = field.stiffness_matrix(k_factor);
  json triplets = json::array();
  for (Eigen::Index row = 0; row < stiffness.outerSize(); ++row) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(stiffness, row); it; ++it) {
      triplets.push_back({it.row(), it.col(), it.value()});
    }
  }
  output["stiffness"] = {{"size", stiffness.rows()}, {"triplets", std::move(triplets)}};

  json rotations = json::array();
  for (const auto& r : field.rotations()) {
    rotations.push_back({{r(0, 0), r(0, 1), r(0, 2)}, {r(1, 0), r(1, 1), r(1, 2)}, {r(2, 0), r(2, 1), r(2, 2)}});
  }
  output["rotations"] = std::move(rotations);
  json edges = json::array();
  for (const auto& e : mesh->edges()) edges.push_back({e[0], e[1]});
  output["edges"] = std::move(edges);
  output["restVolume"] = field.rest_volumes();
  return output;
}

}  // namespace

json probe(const json& input, const std::string& source) {
  try {
    return evaluate(input);
  } catch (const Error& error) {
    throw make_error(source, ": ", error.what());
  }
}

void probe_file(const std::string& case_path, const std::string& output_path) {
  const json input = read_json_file(case_path);
  write_text(probe(input, case_path).dump(), output_path);
}

}  // namespace fastcorot::cli
