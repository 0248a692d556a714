// SOFA's PrecomputedConstraintCorrection in a scene (its bwdInit): the object's compliance read from
// SOFA's cache file or computed and written there (constraint/precomputed_constraint_correction.h,
// docs/constraints.md). Internal to src/scene (lagrangian_builder.cpp).
#pragma once

#include "fastcorot/constraint/constraint_corrections.h"
#include "lagrangian_builder.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// The correction of component `c` for the simulated object at `where`; throws fastcorot::Error for
// what cannot be precomputed (rigid states, one of several MechanicalObjects under a solver, an ODE
// solver without SOFA's integration factors, rotations without a rotation finder, C too big) or a
// cache file of the wrong size. Reports in `info` where C came from. `lcp`: the loop's constraint
// solver is an LCPConstraintSolver (SOFA's rotations then turn the response, otherwise nothing).
std::unique_ptr<ConstraintCorrection<double>> build_precomputed_correction(SceneData& data, std::vector<std::string>& info,
                                                                           Component& c, Simulation<double>& simulation,
                                                                           const StateLocation& where, bool lcp);

}  // namespace fastcorot::scene_detail
