// SOFA's collision model components (TriangleCollisionModel, LineCollisionModel,
// PointCollisionModel, SphereCollisionModel) read into CollisionModel's: their flags and
// distances, their elements from the topology SOFA's context gives them, and the points they sit on
// (a body's own, a state mapped from it, a rigid body's centres, or a still MechanicalObject).
// Internal to src/scene (collision_builder.cpp builds the pipeline from them); design in
// docs/collision.md.
#pragma once

#include "fastcorot/collision/collision_model.h"
#include "fastcorot/collision/element_intersection.h"
#include "fastcorot/sim/simulation.h"
#include "lagrangian_builder.h"
#include "scene_data.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// Why the scene's collisions cannot be simulated (thrown inside the collision builders, turned into
// one warning per collision component).
struct NotSimulated {
  std::string reason;
};

class CollisionModelReader {
 public:
  // `method` decides the neighbourhood data a model needs (NewProximity's ownership flags,
  // LocalMinDistance's cones).
  CollisionModelReader(SceneData& data, Simulation<double>& simulation, const LocateState& locate,
                       IntersectionMethod method);

  // The model component c. Throws NotSimulated for what fastcorot does not simulate yet and
  // fastcorot::Error for bad input (a negative distance, an element naming a missing point).
  CollisionModel<double> model(Component& c);

 private:
  // The triangles, quads and edges SOFA's container gives a model: its lists, and where it has no
  // edges, those it makes from its cells.
  struct TopologyElements {
    std::vector<Triangle> triangles;
    std::vector<std::array<Index, 4>> quads;
    std::vector<Edge> edges;
  };
  TopologyElements elements(Component& topology);
  // LocalMinDistance's neighbourhood topology for model m: the triangles and edges of its topology
  // (the line model's own edge list), and whether a point model's filter applies (SOFA finds a
  // LineCollisionModel in the node or above).
  void cone_topology(Component& c, Component& topology, CollisionModel<double>& m);
  // SOFA's context topology: the model's `topology` link, else the nearest topology container of
  // its node or above (a TriangleSetTopologyContainer included).
  Component* topology_of(Component& c);
  // SOFA's context state: the first MechanicalObject of the node or of the nearest ancestor.
  Component& state_of(Component& c);
  // The points of `state` (shared by every model on it), for the model component `user`.
  std::shared_ptr<CollisionPoints<double>> points_of(Component& state, Component& user);

  SceneData& data_;
  Simulation<double>& simulation_;
  const LocateState& locate_;
  IntersectionMethod method_;
  std::map<const Component*, std::shared_ptr<CollisionPoints<double>>> points_;
};

}  // namespace fastcorot::scene_detail
