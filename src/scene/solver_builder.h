// An object's ODE solver and linear solver, built from their SOFA components: EulerImplicitSolver
// or StaticSolver (with its NewtonRaphsonSolver), and the linear solver SOFA would pick for it (its
// linearSolver link, else the first one) with what it links to: preconditioners and SOFA master's
// linear systems. Internal to src/scene (scene_builder.cpp).
#pragma once

#include "fastcorot/sim/linear_solver.h"
#include "fastcorot/sim/ode_solver.h"
#include "scene_data.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

struct BuiltSolvers {
  std::unique_ptr<OdeSolver<double>> ode;
  std::unique_ptr<LinearSolver<double>> linear;
};

// `nodes`: the solver's node and the nodes below it that take part in the mechanics, in scene
// order; `points`: the size of the object's state. Throws fastcorot::Error naming the component at
// fault; adds info lines (such as linear solvers left unused) to `info`.
BuiltSolvers build_solvers(SceneData& data, std::vector<std::string>& info, Component& integrator,
                           const std::vector<GraphNode*>& nodes, Index points);

}  // namespace fastcorot::scene_detail
