#include "linear_solver_builders.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/minres_solver.h"
#include "fastcorot/sim/precomputed_linear_solver.h"
#include "fastcorot/sim/ssor_preconditioner.h"
#include "fastcorot/sim/warp_preconditioner.h"

namespace fastcorot::scene_detail {

namespace {

bool is_direct_solver(const Component& c) { return c.type() == "EigenSimplicialLDLT"; }

bool names_rotation_finder(const Component& c) {
  return c.type() == "TetrahedronFEMForceField" || c.type() == "HexahedronFEMForceField";
}

bool has_rotation_finder(const std::vector<GraphNode*>& nodes) {
  for (const GraphNode* node : nodes) {
    for (const auto& c : node->components) {
      if (names_rotation_finder(*c)) return true;
    }
  }
  return false;
}

// The RotationMatrixSystem of a WarpPreconditioner: its linearSystem link, else the first in its
// node (SOFA makes one with the defaults when there is none).
Component* rotation_matrix_system(SceneData& data, Component& warp) {
  if (warp.has("linearSystem")) {
    Component& system = data.resolve_object(*warp.node, warp.object->attributes.at("linearSystem"), warp);
    if (system.type() != "RotationMatrixSystem") {
      throw make_error(warp.where(), ": linearSystem must link a RotationMatrixSystem, not ", system.where());
    }
    return &system;
  }
  for (Component* c : warp.node->of_category("linearsystem")) {
    if (c->type() == "RotationMatrixSystem") return c;
  }
  return nullptr;
}

std::shared_ptr<PreconditioningSolver<double>> build_warp(SceneData& data, std::vector<std::string>& info, Component& warp,
                                                          const std::vector<GraphNode*>& nodes) {
  // The direct solver it wraps: its linearSolver link, else the first linear solver of its node.
  Component* direct = nullptr;
  if (warp.has("linearSolver")) {
    direct = &data.resolve_object(*warp.node, warp.object->attributes.at("linearSolver"), warp);
  } else {
    const auto local = warp.node->of_category("linearsolver");
    if (!local.empty()) direct = local.front();
  }
  if (!direct) throw make_error(warp.where(), ": linearSolver: no linear solver linked or in its node");
  if (!is_direct_solver(*direct)) {
    throw make_error(warp.where(), ": linearSolver must link a sparse direct solver (SparseLDLSolver, "
                     "EigenSimplicialLDLT, ...), not ", direct->where());
  }
  for (const char* deprecated : {"update_step", "useRotationFinder"}) {
    if (warp.has(deprecated)) {
      info.push_back(warp.where() + ": " + deprecated + " has no effect (SOFA moved it to RotationMatrixSystem: "
                     "assemblingRate, rotationFinder)");
    }
  }
  WarpPreconditioner<double>::Parameters p;
  if (Component* system = rotation_matrix_system(data, warp)) {
    p.assembling_rate = data.whole_number(*system, "assemblingRate", 1);
    if (p.assembling_rate < 1) {
      throw make_error(system->where(), ": assemblingRate = ", p.assembling_rate, ": must be at least 1");
    }
    if (system->has("rotationFinder")) {
      Component& finder = data.resolve_object(*system->node, system->object->attributes.at("rotationFinder"), *system);
      if (!names_rotation_finder(finder)) {
        throw make_error(system->where(), ": rotationFinder must link a TetrahedronFEMForceField or "
                         "HexahedronFEMForceField, not ", finder.where());
      }
    }
    if (system->has("mainSystem")) {
      data.resolve_object(*system->node, system->object->attributes.at("mainSystem"), *system);
    }
    if (p.assembling_rate > 1 && !has_rotation_finder(nodes)) {
      info.push_back(system->where() + ": no TetrahedronFEMForceField or HexahedronFEMForceField reports rotations: "
                     "R is the identity between assemblies");
    }
  }
  return std::make_shared<WarpPreconditioner<double>>(p);
}

}  // namespace

std::unique_ptr<LinearSolver<double>> build_minres(SceneData& data, Component& c, Index points) {
  MinResSolver<double>::Parameters p;
  p.iterations = data.whole_number(c, "iterations", p.iterations);
  p.tolerance = data.real(c, "tolerance", p.tolerance);
  try {
    return std::make_unique<MinResSolver<double>>(p, points);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

std::unique_ptr<LinearSolver<double>> build_precomputed_linear_solver(SceneData& data, std::vector<std::string>& info,
                                                                      Component& c) {
  if (data.boolean(c, "use_file", true)) {
    info.push_back(c.where() + ": use_file: no file of the inverse is read or written (the first step's matrix "
                   "is factorised once, in memory)");
  }
  data.boolean(c, "jmjt_twostep", true);  // constraint corrections only: checked, no effect here
  return std::make_unique<PrecomputedLinearSolver<double>>();
}

std::shared_ptr<PreconditioningSolver<double>> build_preconditioning_solver(SceneData& data, std::vector<std::string>& info,
                                                                            Component& preconditioner,
                                                                            const std::vector<GraphNode*>& nodes) {
  if (preconditioner.type() == "WarpPreconditioner") return build_warp(data, info, preconditioner, nodes);
  SSORPreconditioner<double>::Parameters p;
  p.omega = data.real(preconditioner, "omega", 1.0);
  // SOFA's block form (3x3 blocks) leaves out the final 2 - omega scaling.
  p.scale_by_two_minus_omega = data.text(preconditioner, "template", "").find("Mat3x3") == std::string::npos;
  try {
    return std::make_shared<SSORPreconditioner<double>>(p);
  } catch (const Error& error) {
    throw error_at(preconditioner.where(), error);
  }
}

void report_matrix_images(const std::vector<GraphNode*>& nodes, std::vector<std::string>& info) {
  for (const GraphNode* node : nodes) {
    for (const auto& c : node->components) {
      if (c->type() == "GlobalSystemMatrixImage") {
        info.push_back(c->where() + ": an image of the system matrix for SOFA's GUI: nothing to draw here");
      }
    }
  }
}

}  // namespace fastcorot::scene_detail
