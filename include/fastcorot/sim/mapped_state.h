// How outputs name and show every MechanicalObject of a scene, as SOFA's scene holds them:
// StateRange, a simulated MechanicalObject's range of points in its object's state (several when
// one solver integrates several MechanicalObjects as one system); MappedState, a MechanicalObject
// of a mapped child node (collision spheres or points, markers) whose positions and velocities
// follow the object's through a linear mapping (x_m = J x, v_m = J v, as SOFA's mappings apply
// them at the end of a step). Output only: nothing written on a mapped state acts on the object
// (mechanics in mapped nodes are refused by the scene builder).
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/sim/visual_surface.h"

#include <string>
#include <vector>

namespace fastcorot {

struct StateRange {
  std::string node;  // node path from the root, names joined by '/'
  std::string name;  // the MechanicalObject's name (its type when the scene names none)
  Index offset = 0;  // first point in the object's state
  Index size = 0;
};

struct MappedState {
  std::string node;
  std::string name;
  std::string mapping;  // "BarycentricMapping (tetrahedra)", ... for messages and docs
  PointMapping<double> map;
};

// One MechanicalObject's positions and velocities at the current step.
struct StateSnapshot {
  std::string node;
  std::string name;
  bool mapped = false;
  std::vector<Vec3<double>> position;
  std::vector<Vec3<double>> velocity;

  // "node path/object name": how dumps key the state.
  std::string key() const { return node + "/" + name; }
};

template <class Real>
struct SimulatedObject;

// Every MechanicalObject of `object`: its simulated states in scene order, then its mapped ones.
std::vector<StateSnapshot> state_snapshots(const SimulatedObject<double>& object);

}  // namespace fastcorot
