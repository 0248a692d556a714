// Collision detection and penalty contact: SOFA's pipeline with MinProximityIntersection and the
// PenalityContactForceField response (built by collision_builder.cpp; docs/collision.md). The other
// intersection methods, sphere and tetrahedron models are not in this table: a scene with one is
// loaded with its collisions ignored, warned.
#include "component_families.h"

namespace fastcorot::scene_detail {

namespace {

std::vector<AttributeSpec> model_attributes() {
  return {{"active", "bool", "true", "false: the model takes no part"},
          {"moving", "bool", "true", "false: its tree is built once (an obstacle)"},
          {"simulated", "bool", "true", "false: an obstacle (two obstacles never collide)"},
          {"selfCollision", "bool", "false", "must be false: self-collision is not simulated yet"},
          {"contactDistance", "real", "0", "added to the intersection's alarm and contact distances"},
          {"proximity", "real", "0", "SOFA's alias of contactDistance"},
          {"contactStiffness", "real", "10", "k of the penalty: k₁ k₂ / d per contact"},
          {"contactFriction", "real", "0", "accepted (the penalty response ignores it, as SOFA)"},
          {"contactResponse", "string", "", "must be empty or PenalityContactForceField"},
          {"group", "indices", "", "group numbers: two models sharing one never collide"},
          {"topology", "link", "", "the topology its elements come from (default: the nearest one)"},
          {"mstate", "link", "", "accepted: the node's MechanicalObject is used"},
          {"color", "string", "", "accepted (display)"},
          {"template", "string", "", "accepted (Vec3d)"}};
}

}  // namespace

std::vector<ComponentSpec> collision_components() {
  auto triangle = model_attributes();
  triangle.push_back({"bothSide", "bool", "false", "accepted (MinProximity ignores it)"});
  triangle.push_back({"computeNormals", "bool", "true", "accepted"});
  return {
      {"CollisionPipeline", "collision",
       "SOFA's collision pipeline: at each step's start, contacts found at the current positions with the scene's intersection method, and their responses for the step. Simulated here with MinProximityIntersection and the PenalityContactForceField response under the default animation loop, between a simulated body and an obstacle (or two models of one body); otherwise the scene's collisions are ignored with a warning saying why.",
       {{"depth", "int", "6", "accepted (fastcorot's tree has its own depth)"},
        {"verbose", "bool", "false", "accepted"},
        {"draw", "bool", "false", "accepted"}},
       {"DefaultPipeline"}},
      {"BruteForceBroadPhase", "collision", "The broad phase: every model paired with every earlier one it can collide with (at least one simulated, not of one node, no group in common).",
       {{"box", "string", "", "accepted"}}},
      {"BVHNarrowPhase", "collision", "The narrow phase: bounding-volume trees of the models' elements, every element pair whose boxes are within the alarm distance handed to the intersection's rule.", {}, {"BruteForceDetection"}},
      {"MinProximityIntersection", "collision",
       "SOFA's MinProximityIntersection: Point–Point, Line–Point (clamped to the segment), Line–Line and Triangle–Point (strictly inside) within alarmDistance + the models' contactDistance; outputs at distance − (contactDistance + the models' contactDistance).",
       {{"alarmDistance", "real", "1", "pairs farther apart are not contacts"},
        {"contactDistance", "real", "0.5", "the distance the response keeps"},
        {"usePointPoint", "bool", "true", "Point–Point pairs"},
        {"useLinePoint", "bool", "true", "Line–Point pairs"},
        {"useLineLine", "bool", "true", "Line–Line pairs"},
        {"useSphereTriangle", "bool", "true", "accepted (no spheres here)"},
        {"useSurfaceNormals", "bool", "false", "Triangle–Point outputs take the triangle's unit normal"}}},
      {"CollisionResponse", "collision",
       "The contact manager: each model pair's outputs become a PenalityContactForceField (one contact per id: the closest), k = k₁ k₂ / d, pen = d − (y₂ − y₁)·n, force k pen n when pen > 0, implicit in the body's step.",
       {{"response", "string", "PenalityContactForceField", "must be PenalityContactForceField here"},
        {"responseParams", "string", "", "accepted (the penalty response takes none)"},
        {"mu", "real", "", "accepted (friction is not part of the penalty response)"}},
       {"DefaultContactManager"}},
      {"TriangleCollisionModel", "collision", "The triangles of the node's topology (quads split as SOFA) on the node's MechanicalObject.", triangle, {"TriangleModel"}},
      {"LineCollisionModel", "collision", "The edges of the node's topology (from its triangles when it lists none) on the node's MechanicalObject.", model_attributes(), {"LineModel"}},
      {"PointCollisionModel", "collision", "Every point of the node's MechanicalObject.", model_attributes(), {"PointModel"}},
  };
}

}  // namespace fastcorot::scene_detail
