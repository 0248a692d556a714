// Builders of the linear solvers and preconditioning solvers that solver_builder.cpp hands on:
// MinResLinearSolver, PrecomputedLinearSolver, and a PCGLinearSolver's SSORPreconditioner or
// WarpPreconditioner (with its RotationMatrixSystem and direct solver). Internal to src/scene.
#pragma once

#include "fastcorot/sim/linear_solver.h"
#include "fastcorot/sim/preconditioning_solver.h"
#include "scene_data.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// Throw fastcorot::Error naming the component and the attribute at fault.
std::unique_ptr<LinearSolver<double>> build_minres(SceneData& data, Component& c, Index points);
std::unique_ptr<LinearSolver<double>> build_precomputed_linear_solver(SceneData& data, std::vector<std::string>& info,
                                                                      Component& c);
// `preconditioner` is an SSORPreconditioner or a WarpPreconditioner; `nodes` those of the solver.
std::shared_ptr<PreconditioningSolver<double>> build_preconditioning_solver(SceneData& data, std::vector<std::string>& info,
                                                                            Component& preconditioner,
                                                                            const std::vector<GraphNode*>& nodes);
// One info line per GlobalSystemMatrixImage in `nodes` (an image of the matrix for SOFA's GUI).
void report_matrix_images(const std::vector<GraphNode*>& nodes, std::vector<std::string>& info);

}  // namespace fastcorot::scene_detail
