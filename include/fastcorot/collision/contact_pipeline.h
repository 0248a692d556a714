// ContactPipeline<Real>: SOFA's collision pipeline (CollisionPipeline, BruteForceBroadPhase,
// BVHNarrowPhase, CollisionResponse) with MinProximityIntersection and the PenalityContactForceField
// response, as a CollisionStage: at each step's start every model's points and tree are updated;
// the broad phase pairs the models in scene order (each with every earlier one it can collide with,
// their root boxes within the alarm distance); the narrow phase hands every element pair whose
// boxes pass to MinProximity's rule (collision/intersections.h), in SOFA's order (model pairs in
// broad-phase order, element pairs in BVHNarrowPhase's traversal of SOFA's trees, aabb_tree.h), so
// results do not depend on threads; each model
// pair's outputs are merged by id (the smallest value kept, the first on ties) and become contacts of
// the penalty force field of the object they act on: implicit, in that object's step (SOFA's
// placement when its response node is under the body's solver; the scene builder checks that).
// Design: docs/collision.md.
#pragma once

#include "fastcorot/collision/collision_model.h"
#include "fastcorot/collision/element_intersection.h"
#include "fastcorot/collision/explicit_contact_forces.h"
#include "fastcorot/collision/penalty_contact_force_field.h"
#include "fastcorot/collision/stick_contact_force_field.h"
#include "fastcorot/constraint/stick_contact_constraint.h"
#include "fastcorot/constraint/unilateral_lagrangian_constraint.h"
#include "fastcorot/sim/collision_stage.h"

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
class ContactPipeline final : public CollisionStage<Real> {
 public:
  // The intersection method and its data.
  using Parameters = IntersectionSettings<Real>;
  // What each rule pair's outputs become (SOFA's contact responses).
  enum class Response {
    none,              // nothing (a FrictionContactConstraint disabled by a zero contactStiffness)
    penalty,           // PenalityContactForceField: one contact per id, the closest
    stick_springs,     // StickContactForceField: springs at rest as found, kept alive
    friction,          // FrictionContactConstraint (or AugmentedLagrangianResponseConstraint): unilateral rows
    stick_constraint,  // StickContactConstraint: bilateral rows at rest as found, kept alive
  };
  // Where the responses go. Per rule pair (rule_pairs' order): its response; for penalty and springs
  // whether it is explicit (evaluated once at the step's start into both sides' explicit_forces:
  // SOFA's placement between two bodies' solvers) or implicit (into its object's field); its
  // constraint for the Lagrangian ones (after SOFA's removal of duplicates: an output whose two
  // points' squared distances to a kept output's sum below 1e-8). Per object: its implicit penalty
  // and spring fields and its explicit forces (null where no pair needs them).
  struct Responses {
    std::vector<Response> kind;
    std::vector<char> explicit_pairs;
    std::vector<std::shared_ptr<PenaltyContactForceField<Real>>> penalties;
    std::vector<std::shared_ptr<StickContactForceField<Real>>> sticks;
    std::vector<std::shared_ptr<ExplicitContactForces<Real>>> explicit_forces;
    std::vector<std::shared_ptr<UnilateralLagrangianConstraint<Real>>> constraints;
    std::vector<std::shared_ptr<StickContactConstraint<Real>>> stick_constraints;
  };
  // Throws fastcorot::Error for a model without points, a response list of another size than the
  // rule pairs, an implicit pair joining two simulated objects, or a pair without the field or
  // constraint its response needs.
  ContactPipeline(Parameters parameters, std::vector<CollisionModel<Real>> models, Responses responses);

  CollisionReport begin_step(std::span<SimulatedObject<Real>> objects, Real dt, double time) override;
  std::span<const DetectedContact<Real>> contacts() const override { return detected_; }
  // The models' points, trees and neighbourhoods are updated one model per task, and each model
  // pair's candidate element pairs are cut into chunks whose outputs are joined in order: the same
  // contacts, in the same order, for any thread count.
  void set_threads(int threads) override { threads_ = threads; }
  // Beyond SOFA: each kept contact between points, segments and triangles measured again at the
  // step's end positions (its points placed by the weights they had on their elements); those whose
  // points crossed along the normal are counted in `report` (spheres are left out: DiscreteIntersection
  // finds them only once they overlap).
  void end_step(std::span<SimulatedObject<Real>> objects, CollisionReport& report) override;

  // The last step's contacts, per object with a penalty field (for drawing and outputs).
  const std::vector<CollisionModel<Real>>& models() const { return models_; }

  using Output = ElementOutput<Real>;
  struct ModelPair {
    std::size_t first = 0, second = 0;  // models, in the rule's order (Triangle before Point, ...)
  };
  // The model pairs the rules cover, in broad-phase order, for `models` (static: tests).
  static std::vector<ModelPair> rule_pairs(const std::vector<CollisionModel<Real>>& models, const Parameters& parameters);

 private:
  std::vector<Output> narrow_phase(const ModelPair& pair, CollisionReport& report) const;
  PenaltyContact<Real> contact(const ModelPair& pair, const Output& output) const;
  // The penalty response of one pair's outputs into its objects' lists; the friction one into its
  // constraint. Both return the contacts kept.
  int penalty_response(std::size_t k, const std::vector<Output>& outputs, std::vector<std::vector<PenaltyContact<Real>>>& contacts);
  int friction_response(std::size_t k, const std::vector<Output>& outputs);
  int stick_constraint_response(std::size_t k, const std::vector<Output>& outputs, std::span<const SimulatedObject<Real>> objects);
  // SOFA's removal of duplicates before its Lagrangian responses: an output whose two points' squared
  // distances to a kept output's sum below 1e-8 is dropped.
  static std::vector<const Output*> without_duplicates(const std::vector<Output>& outputs);
  // The output's two points as contact sides (their objects, positions and J blocks).
  void contact_sides(const ModelPair& pair, const Output& output, ContactSide<Real>& first, ContactSide<Real>& second) const;
  int stick_response(std::size_t k, const std::vector<Output>& outputs, std::span<const SimulatedObject<Real>> objects,
                     std::vector<std::vector<StickSpring<Real>>>& springs);
  // A kept output: drawn and reported (detected_), and watched for crossing (watch_).
  void record(const ModelPair& pair, const Output& output);
  // The outputs SOFA's penalty and stick responses keep: one per id (the smallest value, the first
  // on ties), in the order they were found.
  static std::vector<std::size_t> kept_by_id(const std::vector<Output>& outputs);
  // Each rule pair's objects: an implicit pair on one object only, with the field its response
  // needs, an explicit one with both sides' explicit_forces; a Lagrangian pair with its constraint.
  void check_pairs();
  // The distance a contact keeps: the method's contact distance, the models', the spheres' radii.
  Real contact_distance(const ModelPair& pair, const Output& output) const;
  // The weights of `p` (a point of element `element` of `model`) on the element's points, their J
  // row blocks into `out`; returns the weighted point (SOFA's contact mapper's position).
  Vec3<Real> add_side(const CollisionModel<Real>& model, Index element, const Vec3<Real>& p,
                      std::vector<std::pair<Index, Mat3<Real>>>& out) const;

  Parameters parameters_;
  std::vector<CollisionModel<Real>> models_;
  std::vector<ModelPair> pairs_;
  Responses responses_;
  std::vector<std::vector<StickSpring<Real>>> stick_springs_;  // per rule pair, alive from step to step
  std::vector<std::vector<StickContact<Real>>> stick_contacts_;  // per rule pair, alive from step to step
  std::vector<std::vector<Vec3<Real>>> last_positions_;       // per object, at the last step's start
  std::vector<DetectedContact<Real>> detected_;
  // A contact's two points as weights on their elements' points, for end_step.
  struct Watch {
    std::size_t model[2] = {0, 0};
    std::array<Index, 3> points[2] = {};
    std::array<Real, 3> weights[2] = {};
    int count[2] = {0, 0};
    Vec3<Real> normal = Vec3<Real>::UnitX();
  };
  std::vector<Watch> watch_;
  int threads_ = 1;
};

}  // namespace fastcorot
