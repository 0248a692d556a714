// The families of SOFA components in the one declarative table (component_table.h): each family's
// entries are written in its own file (components_<family>.cpp), so that adding a component
// touches that file only. Internal to src/scene.
#pragma once

#include "fastcorot/scene/component_table.h"

#include <vector>

namespace fastcorot::scene_detail {

// States, topologies, topological mappings, volume-mesh loaders and the cutting script: where the points and tetrahedra come from.
std::vector<ComponentSpec> topology_components();
// Surface loaders, visual models and the mappings that carry them on the tetrahedra.
std::vector<ComponentSpec> visual_components();
// Force fields, loads and masses.
std::vector<ComponentSpec> mechanics_components();
// Projective constraints.
std::vector<ComponentSpec> constraint_components();
// Constraint-based animation: FreeMotionAnimationLoop, constraint solvers, corrections, Lagrangian constraints.
std::vector<ComponentSpec> lagrangian_components();
// SoftRobots' constraints (softrobots_builder.cpp): CableConstraint, SurfacePressureConstraint.
std::vector<ComponentSpec> softrobots_components();
// Engines: generated meshes and regions of interest.
std::vector<ComponentSpec> engine_components();
// ODE solvers, linear solvers, preconditioners and the linear systems SOFA links them to.
std::vector<ComponentSpec> solver_components();
// SOFA master's element FEM family: its force fields, FEMMass and NodalMassDensity.
std::vector<ComponentSpec> element_fem_components();
// Collision detection and penalty contact: the pipeline, MinProximityIntersection, the models.
std::vector<ComponentSpec> collision_components();

}  // namespace fastcorot::scene_detail
