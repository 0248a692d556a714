// Force fields beyond the two tetrahedral FEM ones, built from their SOFA components:
// MeshSpringForceField (the springs of a mesh), and the loads of SOFA's MechanicalLoad that act on
// points (and ConstantForceField). Internal to src/scene (scene_builder.cpp); errors name the component.
#pragma once

#include "fastcorot/fem/force_field.h"
#include "fastcorot/fem/spring_force_field.h"
#include "fastcorot/sim/mechanical_system.h"
#include "scene_data.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// Whether MeshSpringForceField c makes any spring: one of its per-kind stiffnesses or dampings
// (linesStiffness, ..., cubesStiffness) is not zero. Its `stiffness` and `damping` set every kind's
// that the scene does not write (SOFA declares them as aliases of each).
bool makes_mesh_springs(SceneData& data, Component& c);

// MeshSpringForceField over `mesh` (a tetrahedral topology: its edges, triangles and tetrahedra),
// rest lengths from `rest`.
std::shared_ptr<ForceField<double>> build_mesh_springs(SceneData& data, Component& c, std::shared_ptr<const TetMesh> mesh,
                                                       std::span<const Vec3<double>> rest);
// The same over the element lists of another topology (a grid's or hexahedral container's lines,
// quads and hexahedra); the field's mesh is the points alone.
std::shared_ptr<ForceField<double>> build_mesh_springs(SceneData& data, Component& c, SpringTopology topology,
                                                       std::span<const Vec3<double>> rest);

// PlaneForceField or ConicalForceField on the points of the object whose mesh is `mesh`.
std::shared_ptr<ForceField<double>> build_penalty_force_field(SceneData& data, Component& c, std::shared_ptr<const TetMesh> mesh);

bool is_penalty_force_field(std::string_view type);

// TrianglePressureForceField as the constant forces it is (pressure x rest area / 3 on each vertex
// of each listed triangle), from the rest positions.
ConstantForce<double> build_triangle_pressure(SceneData& data, Component& c, std::span<const Vec3<double>> rest);
// QuadPressureForceField likewise: pressure x rest area (triangles 0 1 2 and 0 2 3) / 4 on each
// vertex of each listed quad of its topology.
ConstantForce<double> build_quad_pressure(SceneData& data, Component& c, std::span<const Vec3<double>> rest);

// ConstantForceField's forces on a state of `size` points: `forces` (one per index), or `force` on
// each, or `totalForce` shared out; indices default to every point (indexFromEnd counts from the
// last). Without any force, an info line and no load.
// ConstantForceField's points (or rigids) among `size`: `indices`, every one when empty, counted
// from the end with indexFromEnd; throws naming c for one out of range.
std::vector<Index> constant_force_indices(SceneData& data, Component& c, Index size);
ConstantForce<double> build_constant_force(SceneData& data, std::vector<std::string>& info, Component& c, Index size);

}  // namespace fastcorot::scene_detail
