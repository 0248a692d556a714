// TopologyScript: tetrahedra removed from and added to a mesh at given times, as SOFA's
// TopologicalChangeProcessor does (scene element of that name, docs/cutting.md). Simulation::step
// applies the events due at the start of each step (SOFA's AnimateBeginEvent), before integrating,
// through MechanicalSystem::remove_tetrahedra / add_tetrahedra, so that the force fields and the
// mass follow each change.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/sim/mechanical_system.h"
#include "fastcorot/topology/tet_mesh.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot {

struct TopologyEvent {
  double time = 0;
  std::vector<Index> remove;      // tetrahedron indices as numbered when the event comes
  std::vector<Tetrahedron> add;   // added after the removal
  std::string where;              // where the event was written, for messages
};

struct TopologyScript {
  std::string where;                  // the scene component, for messages
  std::shared_ptr<TetMesh> mesh;      // the topology it changes
  std::vector<TopologyEvent> events;  // in time order
  // SOFA's two rules, compared exactly as SOFA compares them with its time (Simulation::step
  // passes the time accumulated as SOFA accumulates it): timeToRemove fires once the time is past
  // it (strictly), a file's "T=" block once the time plus `shift` reaches it (to within the double
  // epsilon).
  bool strictly_after = false;
  double shift = 0;
  // Repeats each event every `interval` after it fired (timeToRemove with interval; 0: once).
  double interval = 0;
  std::size_t next = 0;  // first event not yet applied

  // Applies the events due at `time` to `system`. Throws fastcorot::Error naming the component,
  // the event and the time when an index is out of range or a tetrahedron to add is degenerate;
  // the events before it stay applied.
  template <class Real>
  void apply_due(double time, MechanicalSystem<Real>& system);
};

}  // namespace fastcorot
