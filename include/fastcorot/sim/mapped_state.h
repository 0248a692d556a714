// How outputs name and show every MechanicalObject of a scene, as SOFA's scene holds them:
// StateRange, a simulated MechanicalObject's range of points in its object's state (several when
// one solver integrates several MechanicalObjects as one system); MappedState, a MechanicalObject
// of a mapped child node (collision spheres or points, markers) whose positions and velocities
// follow the object's through a linear mapping (x_m = J x, v_m = J v, as SOFA's mappings apply
// them at the end of a step), or follow its rigid bodies (RigidMapping), or follow a
// SubsetMultiMapping's points. Output only: mechanics
// on mapped states are folded into the object by the scene builder (docs/mechanical-graph.md).
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/rigid_points.h"
#include "fastcorot/sim/visual_surface.h"

#include <optional>
#include <string>
#include <vector>

namespace fastcorot {

struct StateRange {
  std::string node;  // node path from the root, names joined by '/'
  std::string name;  // the MechanicalObject's name (its type when the scene names none)
  Index offset = 0;  // first point in the object's state
  Index size = 0;
  bool rigid = false;  // a Rigid3 state: its blocks are the system's rigids (two per rigid)
};

struct MappedState {
  std::string node;
  std::string name;
  std::string mapping;  // "BarycentricMapping (tetrahedra)", ... for messages and docs
  PointMapping<double> map;
  std::optional<RigidPoints<double>> rigid;  // under a RigidMapping (map is then unused)
  // Below a SubsetMultiMapping, or below points that several rigids carry: map reads the points
  // `through` gives (VisualSurface::through, through_offset).
  std::shared_ptr<const MechanicalMapping<double>> through;
  Index through_offset = 0;
  // Coordinates per point: 3, or 1 for a Vec1 state (DistanceMapping's extensions, their value in
  // x; `through` is then the DistanceMapping and `map` the identity).
  int coordinates = 3;
  // The constraint forces on the state, which its mapping's geometric stiffness reads (a Vec1
  // state's; null otherwise): shared with the Lagrangian constraints on it
  // (ConstraintPoints::constraint_force).
  std::shared_ptr<std::vector<Vec3<double>>> constraint_force;
  // SOFA's applyRestPosition on its mapping: its rest positions are the mapping's image of the
  // parent's (else its own: zero for a Vec1 state).
  bool apply_rest_position = false;
  std::size_t size() const { return rigid ? rigid->size() : map.size(); }
};

// One MechanicalObject's positions and velocities at the current step. A Rigid3 state has its
// positions in `rigid_position` (7 numbers per rigid, SOFA's "x y z qx qy qz qw") and its
// velocities in `rigid_velocity` (6 per rigid, "vx vy vz wx wy wz"); position and velocity are
// then the centres and the linear velocities.
struct StateSnapshot {
  std::string node;
  std::string name;
  bool mapped = false;
  std::vector<Vec3<double>> position;
  std::vector<Vec3<double>> velocity;
  bool rigid = false;
  std::vector<double> rigid_position;
  std::vector<double> rigid_velocity;
  int coordinates = 3;  // 1 for a Vec1 state: its values are the x of `position` and `velocity`

  // "node path/object name": how dumps key the state.
  std::string key() const { return node + "/" + name; }
};

template <class Real>
struct SimulatedObject;

// Every MechanicalObject of `object`: its simulated states in scene order, then its mapped ones.
std::vector<StateSnapshot> state_snapshots(const SimulatedObject<double>& object);

}  // namespace fastcorot
