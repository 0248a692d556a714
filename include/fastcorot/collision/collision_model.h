// SOFA's collision models (Sofa/Component/Collision/Geometry: PointCollisionModel,
// LineCollisionModel, TriangleCollisionModel) over the points of a MechanicalObject: CollisionPoints
// says where those points come from (a simulated object's own blocks, a state mapped from one, or
// a MechanicalObject no solver moves), CollisionModel holds a model's elements, flags and tree.
// Design: docs/collision.md (§2.1, §4).
#pragma once

#include "fastcorot/collision/aabb_tree.h"
#include "fastcorot/collision/local_min_distance.h"
#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/sim/simulation.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot {

struct SelfCollisionTopology;

template <class Real>
class CollisionPoints {
 public:
  // Blocks `blocks` of simulated object `object`.
  static CollisionPoints own(std::size_t object, std::vector<Index> blocks);
  // The points `mapping` gives from simulated object `object`'s blocks.
  static CollisionPoints mapped(std::size_t object, std::shared_ptr<MechanicalMapping<Real>> mapping);
  // Points that nothing moves (an obstacle: a MechanicalObject no ODE solver integrates).
  static CollisionPoints still(std::vector<Vec3<Real>> points);
  // The centres of simulated object `object`'s rigid bodies, given by their linear blocks (the
  // angular block follows each): SOFA's RigidSphereModel.
  static CollisionPoints rigid(std::size_t object, std::vector<Index> linear_blocks);

  bool is_still() const { return still_; }
  bool is_rigid() const { return rigid_; }
  std::size_t object() const { return object_; }
  std::size_t size() const { return x_.size(); }
  const std::vector<Vec3<Real>>& positions() const { return x_; }
  // The positions at the objects' current state (a nonlinear mapping records its J there).
  void update(std::span<const SimulatedObject<Real>> objects);
  // out += weight × J's row blocks of point i on the object's blocks (nothing for still points).
  void add_row_blocks(std::size_t i, Real weight, std::vector<std::pair<Index, Mat3<Real>>>& out) const;
  // Rigid centres only: out += J's row blocks of the point at offset r (world frame) from centre i,
  // carried by its rigid as SOFA's RigidContactMapper carries a contact point: I on the linear
  // block, −[r]× on the angular one.
  void add_rigid_point_blocks(std::size_t i, const Vec3<Real>& r, std::vector<std::pair<Index, Mat3<Real>>>& out) const;

 private:
  std::size_t object_ = 0;
  bool still_ = false;
  bool rigid_ = false;
  std::vector<Index> blocks_;
  std::shared_ptr<MechanicalMapping<Real>> mapping_;
  std::vector<Vec3<Real>> x_;
  mutable std::vector<std::pair<Index, Mat3<Real>>> scratch_;
  std::size_t checked_size_ = std::size_t(-1);  // the object's point count update last checked the reach against
};

// SOFA's PointCollisionModel, LineCollisionModel, TriangleCollisionModel, SphereCollisionModel
// (a sphere per point, or per rigid body on a Rigid3 state: points->is_rigid()).
enum class CollisionElements { points, lines, triangles, spheres };

template <class Real>
struct CollisionModel {
  std::string where;  // the component, for messages
  std::string node;   // its node's path: two models of one node collide only with selfCollision
  CollisionElements kind = CollisionElements::points;
  bool simulated = true;
  bool moving = true;
  bool self_collision = false;
  // Self-collision (collision/self_collision.h): the model's neighbourhoods (null: no topology),
  // and whether it is its node's first PointCollisionModel (SOFA's mpoints / m_pointModels).
  std::shared_ptr<const SelfCollisionTopology> self_topology;
  bool node_point_model = false;
  std::vector<int> groups;  // two models sharing a group never collide
  Real contact_distance = 0;
  Real contact_stiffness = 10;
  Real contact_friction = 0;  // StickContactForceField's damping (cf₁ + cf₂); other responses ignore it
  std::shared_ptr<CollisionPoints<Real>> points;  // shared by the models of one node
  std::vector<Edge> edges;                        // lines
  std::vector<Triangle> triangles;                // triangles
  std::vector<Real> radii;                        // spheres: one per point
  // NewProximityIntersection: SOFA's ownership flags of the triangles (new_proximity.h).
  std::vector<int> triangle_flags;
  // LocalMinDistance: the topology its cone filters read (the node's triangles and edges), whether
  // a point model's filter applies (a LineCollisionModel in its node or above), bothSide; the
  // neighbourhood at the points' positions (update_neighbourhood).
  std::shared_ptr<const LocalMinDistanceTopology> cone_topology;
  bool point_filter = false;
  bool both_side = false;
  LocalMinDistanceNeighbourhood<Real> neighbourhood;

  // Elements: the points, the edges or the triangles.
  std::size_t size() const;
  // The elements' boxes at the points' positions, widened by contact_distance, into the tree (built
  // the first time, then refitted; a model that does not move keeps its first tree). Returns the
  // number of elements with no extent (a triangle without area, a segment without length).
  int update_tree();
  // LocalMinDistance's neighbourhood at the points' positions (nothing without cone_topology; a
  // model that does not move keeps its first one).
  void update_neighbourhood();
  const AabbTree<Real>& tree() const { return tree_; }

 private:
  AabbTree<Real> tree_;
  bool built_ = false;
  bool neighbourhood_built_ = false;
  std::vector<Aabb<Real>> boxes_;
  std::vector<char> degenerate_;
};

// Whether SOFA's broad phase pairs the two (distinct) models: at least one simulated; of one node only
// when both have selfCollision; else no group in common.
template <class Real>
bool can_collide(const CollisionModel<Real>& a, const CollisionModel<Real>& b);

}  // namespace fastcorot
