// Mechanics in mapped nodes (SOFA's mechanical mappings): an object built for the MechanicalObject
// of a mapped child node, folded into the simulated object above it. Internal to src/scene
// (scene_builder.cpp); design in docs/mechanical-graph.md.
#pragma once

#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/mapping/point_mapping.h"
#include "fastcorot/mapping/rigid_points.h"
#include "fastcorot/sim/simulation.h"
#include "subset_multi_mapping_builder.h"

#include <functional>
#include <memory>
#include <string>

namespace fastcorot::scene_detail {

// A mapped state with mechanics (`mapped`, its mapping onto tetrahedra): throws fastcorot::Error
// naming `where` and the point when a point lies outside every tetrahedron by more than the size
// of the one it is extrapolated from (a barycentric coordinate below -1). SOFA extrapolates such
// points silently; forces there would be carried up with weights beyond the mesh. Points near the
// surface, inside or slightly outside (as surfaces drawn over coarse meshes are), pass.
void check_mapped_points_inside(const MappedState& mapped, const std::string& where);

// Makes `child` (built on the mapped state y = J x of `parent`'s points) act on `parent`: its force
// fields through Jᵀ (MappedForceField), its mass as Jᵀ M J (weighing Jᵀ m g), its constant loads as
// Jᵀ f; its visual models and mapped states follow the chain. `where` names the mapped node in
// errors. Throws fastcorot::Error for what a mapped node cannot hold here: projective constraints,
// scripted topological changes.
void fold_mapped_object(SimulatedObject<double>& child, const PointMapping<double>& map, SimulatedObject<double>& parent,
                        const std::string& where);

// The same for a mapped node under a RigidMapping (`points` carried by the parent's rigids): its
// force fields act through the RigidMapping's Jᵀ; visual models and mapped states below it follow
// when each of their points lies on one rigid. Its lumped mass joins the parent's RigidMappedMass
// (recomputed each step). Throws fastcorot::Error for a mass matrix on the carried points,
// projective constraints, scripted changes.
void fold_rigid_mapped_object(SimulatedObject<double>& child, const RigidPoints<double>& points, SimulatedObject<double>& parent,
                              const std::string& where);

// The same for the child of a SubsetMultiMapping whose points mix points carried by rigid bodies and
// other points (`make` gives its mapping onto the parent's blocks, one per field): force fields and
// constant loads act through that mapping's Jᵀ; visual models and mapped states below it read its
// points (`through`). Throws fastcorot::Error for projective constraints and scripted changes on it.
// Its mass first goes up through fold_multi_mapped_mass.
void fold_multi_mapped_object(SimulatedObject<double>& child, const std::function<std::unique_ptr<MechanicalMapping<double>>()>& make,
                              SimulatedObject<double>& parent, const std::string& where);

// The lumped mass of such a child, point by point: Jᵀ M J onto the parent's points for the points of
// linear inputs, carried by the rigids (RigidMappedMass) for the others; the child keeps it (clear
// it before folding the rest). Throws fastcorot::Error for a mass matrix that is not lumped.
void fold_multi_mapped_mass(const SimulatedObject<double>& child, const SubsetMultiMappingInputs& inputs,
                            SimulatedObject<double>& parent, const std::string& where);

}  // namespace fastcorot::scene_detail
