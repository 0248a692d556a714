// Carrying a running simulation's state into the same scene built again after it grew or shrank
// between steps: SofaPython3 scripts add nodes while the scene runs (a controller creating a
// falling sphere, then calling its node's init()), which fastcorot meets by building the scene
// tree again and carrying over what evolved. Design: docs/python.md ("Nodes added while running").
#pragma once

#include "fastcorot/sim/simulation.h"

#include <string>
#include <vector>

namespace fastcorot {

struct CarriedState {
  std::vector<std::string> carried;  // the objects whose state was carried (node paths)
  std::vector<std::string> fresh;    // the objects new in the rebuilt scene, starting from it
  std::vector<std::string> notes;    // what evolved and could not be carried (warnings to print)
};

// Carries `from`'s state into `to`, freshly built from the same scene tree grown or pruned: the
// step counter and dt, and for each object of `to` with the node path of an object of
// `from`: positions, velocities, its solvers' carried state and its rigid bodies' orientations.
// Objects only in `to` start from the scene; objects only in `from` are dropped. Throws
// fastcorot::Error naming the object when one with the same path has other points, rest
// positions or elements (it was cut while running: its state cannot be carried). What cannot be
// carried and only affects later steps slightly (a FreeMotionAnimationLoop's last impulses, its
// warm start) is listed in `notes`.
CarriedState carry_state(const Simulation<double>& from, Simulation<double>& to);

}  // namespace fastcorot
