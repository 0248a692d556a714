// CollisionStage<Real>: what SOFA's collision pipeline adds to a time step. Before any object
// moves, the stage finds the contacts at the positions the step starts from and turns them into
// responses the objects then feel (a penalty force field's contacts for this step). The stage
// itself lives in the collision layer (include/fastcorot/collision/, design: docs/collision.md);
// Simulation only calls it.
#pragma once

#include "fastcorot/core/types.h"

#include <span>
#include <string>

namespace fastcorot {

template <class Real>
struct SimulatedObject;

// What the collision part of one step did, for summaries and --json.
struct CollisionReport {
  int contacts = 0;              // detection outputs kept by the responses (after merging)
  int model_pairs = 0;           // collision-model pairs the broad phase kept
  long element_pairs = 0;        // element pairs whose boxes passed (the pair rules' calls)
  int degenerate_elements = 0;   // triangles or segments with no extent, skipped (SOFA makes NaN)
  double detection_seconds = 0;  // trees, broad and narrow phases
  // Beyond SOFA, after the step (end_step): contacts between points, segments and triangles whose
  // points ended the step on the wrong side of each other along the contact's normal (the point
  // crossed the surface: deeper than the contact distance allows), the deepest crossing, and the
  // models of that contact.
  int crossed = 0;
  double deepest_crossing = 0;
  std::string crossed_models;
};

// One contact of the last detection, for drawing and outputs: the points on the two elements (the
// first model's, then the second's) and the unit normal from the first to the second.
template <class Real>
struct DetectedContact {
  Vec3<Real> point[2];
  Vec3<Real> normal;
};

template <class Real>
class CollisionStage {
 public:
  virtual ~CollisionStage() = default;
  // At the start of a step (after scripted topological changes, before any integration): detection
  // on the objects' current positions and the responses for this step. `time` is the step's start.
  virtual CollisionReport begin_step(std::span<SimulatedObject<Real>> objects, Real dt, double time) = 0;
  // The contacts the last begin_step kept (after each response merged its outputs), in solve order.
  virtual std::span<const DetectedContact<Real>> contacts() const = 0;
  // After every object's step: the crossing figures of `report` (the one begin_step returned).
  virtual void end_step(std::span<SimulatedObject<Real>> /*objects*/, CollisionReport& /*report*/) {}
  // Threads for the next begin_step (the simulation's): results are bitwise the same for any count.
  virtual void set_threads(int /*threads*/) {}
};

}  // namespace fastcorot
