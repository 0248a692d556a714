// Collision detection and contact: SOFA's pipeline, its intersection methods (MinProximity,
// NewProximity, LocalMinDistance, Discrete), point, line, triangle and sphere models, and the
// PenalityContactForceField and FrictionContactConstraint responses (built by collision_builder.cpp;
// docs/collision.md). Tetrahedron and ray models are not in this table: a scene with one is loaded
// with its collisions ignored, warned.
#include "component_families.h"

namespace fastcorot::scene_detail {

namespace {

std::vector<AttributeSpec> model_attributes() {
  return {{"active", "bool", "true", "false: the model takes no part"},
          {"moving", "bool", "true", "false: its tree is built once (an obstacle)"},
          {"simulated", "bool", "true", "false: an obstacle (two obstacles never collide)"},
          {"selfCollision", "bool", "false", "collide with the models of its node (both with it) and with itself, SOFA's neighbour pruning applied"},
          {"contactDistance", "real", "0", "added to the intersection's alarm and contact distances"},
          {"proximity", "real", "0", "SOFA's alias of contactDistance"},
          {"contactStiffness", "real", "10", "k of the penalty: k₁ k₂ / d per contact"},
          {"contactFriction", "real", "0", "damping of StickContactForceField's springs (cf₁ + cf₂); the other responses ignore it, as SOFA"},
          {"contactResponse", "string", "", "the response of the pairs it is in (Name?param=value&...): RuleBasedContactManager takes it first; CollisionResponse when the other model has none or the same"},
          {"bothSide", "bool", "false", "LocalMinDistance: the cone filters accept both sides"},
          {"group", "indices", "", "group numbers: two models sharing one never collide"},
          {"topology", "link", "", "the topology its elements come from (default: the nearest one)"},
          {"mstate", "link", "", "accepted: the node's MechanicalObject is used"},
          {"color", "string", "", "accepted (display)"},
          {"template", "string", "", "accepted: the node's MechanicalObject decides (Vec3d; Rigid3d for spheres)"}};
}

}  // namespace

std::vector<ComponentSpec> collision_components() {
  auto triangle = model_attributes();
  triangle.push_back({"computeNormals", "bool", "true", "accepted"});
  auto sphere = model_attributes();
  sphere.push_back({"radius", "real", "1", "the radius of the spheres listRadius does not give"});
  sphere.push_back({"listRadius", "reals", "", "one radius per point"});
  const std::vector<AttributeSpec> proximity = {{"alarmDistance", "real", "1", "pairs farther apart are not contacts"},
                                                {"contactDistance", "real", "0.5", "the distance the response keeps"}};
  auto min_proximity = proximity;
  min_proximity.insert(min_proximity.end(), {{"usePointPoint", "bool", "true", "Point–Point (and Sphere–Point) pairs"},
                                             {"useLinePoint", "bool", "true", "Line–Point (and Line–Sphere) pairs"},
                                             {"useLineLine", "bool", "true", "Line–Line pairs"},
                                             {"useSphereTriangle", "bool", "true", "Triangle–Sphere pairs"},
                                             {"useSurfaceNormals", "bool", "false", "Triangle–Point outputs take the triangle's unit normal"}});
  auto local_min = proximity;
  local_min.insert(local_min.end(), {{"usePointPoint", "bool", "true", "Point–Point (and Sphere–Point) pairs"},
                                     {"useLinePoint", "bool", "true", "Line–Point (and Line–Sphere) pairs"},
                                     {"useLineLine", "bool", "true", "Line–Line pairs"},
                                     {"useSphereTriangle", "bool", "true", "Triangle–Sphere pairs"},
                                     {"filterIntersection", "bool", "true", "the cone filters (false: every pair within the alarm distance)"},
                                     {"angleCone", "real", "0", "the cones' widening"},
                                     {"coneFactor", "real", "0.5", "the edge cones' factor"},
                                     {"useLMDFilters", "bool", "false", "true: no cone filter (SOFA's LMDFilter components are not read)"}});
  auto new_proximity = proximity;
  new_proximity.push_back({"useLineLine", "bool", "false", "edge–edge pairs (Line–Line, and between triangles' edges)"});
  const std::vector<AttributeSpec> response = {
      {"response", "string", "PenalityContactForceField", "PenalityContactForceField, StickContactForceField, FrictionContactConstraint, AugmentedLagrangianResponseConstraint or StickContactConstraint"},
      {"responseParams", "string", "", "the Lagrangian response's data as name=value joined by &: mu (FrictionContactConstraint 0.8, AugmentedLagrangianResponseConstraint 0), tol (0: the solver's), epsilon (AugmentedLagrangianResponseConstraint's penalty factor, 0)"},
      {"mu", "real", "", "accepted (friction is not part of the penalty response)"}};
  auto rule_based = response;
  rule_based.insert(rule_based.end(),
                    {{"rules", "string", "", "ordered rules, three words each: model 1, model 2 (a name, a group number or *), response"},
                     {"variables", "string", "", "names of further attributes whose values replace $name$ in the rules' responses"}});
  return {
      {"CollisionPipeline", "collision",
       "SOFA's collision pipeline: at each step's start, contacts found at the current positions with the scene's intersection method, and their responses for the step. Simulated here with MinProximityIntersection, NewProximityIntersection, LocalMinDistance or DiscreteIntersection and the PenalityContactForceField response (implicit in a body's step, or explicit between two bodies' solvers), StickContactForceField, or FrictionContactConstraint, AugmentedLagrangianResponseConstraint or StickContactConstraint under FreeMotionAnimationLoop; what is not (tetrahedron models, moving obstacles, grid and volume topologies as surfaces) is ignored with a warning saying why.",
       {{"depth", "int", "6", "SOFA's tree depth: 6 is followed; another value is warned (it orders exactly tied contacts only)"},
        {"verbose", "bool", "false", "accepted"},
        {"draw", "bool", "false", "accepted"}},
       {"DefaultPipeline"}},
      {"CompositeCollisionPipeline", "collision",
       "SOFA's CompositeCollisionPipeline: the SubCollisionPipelines it links, each run in turn at every step's start (its detection, then its responses), their contacts and figures summed. Instead of a CollisionPipeline (not beside one).",
       {{"subCollisionPipelines", "links", "", "the SubCollisionPipelines, in the order they run"},
        {"parallelDetection", "bool", "false", "accepted: each sub-pipeline's detection runs on the simulation's threads, with the same results for any count"}}},
      {"SubCollisionPipeline", "collision",
       "SOFA's SubCollisionPipeline (under a CompositeCollisionPipeline): a pipeline of its own for the collision models it links, with its own broad and narrow phases, intersection method and contact manager; a response between two simulated models is placed at its node (SOFA's scene context). Without one of its links it does nothing, warned as in SOFA.",
       {{"collisionModels", "links", "", "its collision models, in broad-phase order"},
        {"intersectionMethod", "link", "", "its intersection method"},
        {"contactManager", "link", "", "its CollisionResponse or RuleBasedContactManager"},
        {"broadPhaseDetection", "link", "", "its broad phase"},
        {"narrowPhaseDetection", "link", "", "its narrow phase"},
        {"depth", "int", "6", "SOFA's tree depth: 6 is followed; another value is warned"}}},
      {"BruteForceBroadPhase", "collision", "The broad phase: every model paired with every earlier one it can collide with (at least one simulated, not of one node, no group in common).",
       {{"box", "string", "", "accepted"}},
       {"ParallelBruteForceBroadPhase"}},
      {"BVHNarrowPhase", "collision", "The narrow phase: bounding-volume trees of the models' elements, every element pair whose boxes are within the alarm distance handed to the intersection's rule (on the simulation's threads, with the same contacts for any count: also for SOFA's ParallelBVHNarrowPhase).", {}, {"BruteForceDetection", "ParallelBVHNarrowPhase"}},
      {"MinProximityIntersection", "collision",
       "SOFA's MinProximityIntersection: Point–Point, Line–Point (clamped to the segment), Line–Line, Triangle–Point (strictly inside) and the sphere pairs within alarmDistance + the models' contactDistance; outputs at distance − (contactDistance + the models' contactDistance).",
       min_proximity},
      {"NewProximityIntersection", "collision",
       "SOFA's NewProximityIntersection: MinProximity's pairs with closest points clamped onto edges and corners (reported by the triangle that owns them), plus Triangle–Line and Triangle–Triangle (each triangle's vertices against the other; with useLineLine, edges against edges).",
       new_proximity},
      {"LocalMinDistance", "collision",
       "SOFA's LocalMinDistance: MinProximity's pairs with its own thresholds, each side's cone filter (the triangles' and edges' normals around a point or edge) rejecting pairs seen from behind.",
       local_min},
      {"DiscreteIntersection", "collision",
       "SOFA's DiscreteIntersection: overlapping spheres (Sphere–Sphere), no alarm or contact distance.", {}},
      {"CollisionResponse", "collision",
       "The contact manager: each model pair's outputs become a PenalityContactForceField (one contact per id: the closest), k = k₁ k₂ / d, pen = d − (y₂ − y₁)·n, force k pen n when pen > 0, implicit in the body's step; or StickContactForceField springs (one per id, at rest when made: ks₁ + ks₂ on y₂ − y₁ − R, damping cf₁ + cf₂; made again at every step that finds the pair, kept while a step finds nothing); or, under FreeMotionAnimationLoop, a FrictionContactConstraint (a UnilateralLagrangianConstraint: a normal row per contact, with two tangent rows in Coulomb's disk when mu > 0), an AugmentedLagrangianResponseConstraint (the same rows; with friction its blocks move the impulses by epsilon times the violations, SOFA's augmented Lagrangian resolution) or a StickContactConstraint (a BilateralLagrangianConstraint: three rows per contact holding its two points at their offset when found, made again at every step that finds the pair, kept while a step finds nothing).",
       response,
       {"DefaultContactManager"}},
      {"RuleBasedContactManager", "collision",
       "SOFA's RuleBasedContactManager: a CollisionResponse whose response a model pair may take from ordered rules: the first rule whose two words match the pair (either way round; a model's name, a group number or *) gives its response, the manager's `response` otherwise; a model's own contactResponse first. $name$ in a rule's response is the value of the variable `name` (declared in `variables`, given as an attribute). Pairs may take different responses (penalty and stick springs under the default loop; the Lagrangian ones, each with its own parameters, under FreeMotionAnimationLoop).",
       rule_based, {}, "variables"},
      {"TriangleCollisionModel", "collision", "The triangles of the node's topology (quads split as SOFA) on the node's MechanicalObject.", triangle, {"TriangleModel"}},
      {"LineCollisionModel", "collision", "The edges of the node's topology (from its triangles when it lists none) on the node's MechanicalObject.", model_attributes(), {"LineModel"}},
      {"PointCollisionModel", "collision", "Every point of the node's MechanicalObject.", model_attributes(), {"PointModel"}},
      {"SphereCollisionModel", "collision", "A sphere at every point of the node's MechanicalObject, or at every rigid body of a Rigid3d one (SOFA's RigidSphereModel: its contacts at the surface point, carried by the rigid, the radius also added to the contact distance as SOFA does), its radius from listRadius or radius. LocalMinDistance has no rule for rigid spheres, as in SOFA.", sphere, {"SphereModel"}},
  };
}

}  // namespace fastcorot::scene_detail
