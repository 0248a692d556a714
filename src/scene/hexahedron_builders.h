// The hexahedral pieces of a scene: HexahedronFEMForceField and the masses (DiagonalMass,
// MeshMatrixMass) on a topology of hexahedra (a grid topology or a HexahedronSetTopologyContainer
// without tetrahedra). Internal to src/scene (scene_builder.cpp); errors
// name the component.
#pragma once

#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/sim/mass.h"
#include "scene_data.h"

#include <memory>
#include <span>
#include <vector>

namespace fastcorot::scene_detail {

// RegularGridTopology, CylinderGridTopology and SphereGridTopology: their cells are the regular grid's.
bool is_grid_topology(std::string_view type);

// The hexahedra of a topology component: a grid's cells in SOFA's order (x fastest, corners as
// grid_cell_corners) or a HexahedronSetTopologyContainer's hexahedra (checked: 8 indices each,
// within its points); empty for any other topology.
std::vector<Hexahedron> topology_hexahedra(SceneData& data, Component& topology);

// The tetrahedra TetrahedronFEMForceField makes from a topology of hexahedra alone (its init):
// a grid's as tetrahedron_fem_grid_tetrahedra, other hexahedra as split_hexahedra(2 x 1, mirrored,
// plain table), as SOFA does.
std::vector<Tetrahedron> tetrahedron_fem_tetrahedra(SceneData& data, Component& topology);

// The hexahedra of c's topology (its `topology` link, else its node's): topology_hexahedra, empty
// when the topology has tetrahedra.
std::vector<Hexahedron> hexahedra_of(SceneData& data, Component& c);

std::shared_ptr<HexahedronFEMForceField<double>> build_hexahedron_fem(SceneData& data, Component& c,
                                                                       std::span<const Vec3<double>> rest);

// DiagonalMass (each hexahedron's mass, density x volume, in eighths on its corners) or MeshMatrixMass
// (SOFA's: density x volume / 20 on each corner, / 40 on each of the twelve edges) on `hexahedra`,
// from massDensity or scaled to totalMass.
Mass<double> build_hexahedron_mass(SceneData& data, Component& c, std::span<const Hexahedron> hexahedra,
                                   std::span<const Vec3<double>> rest);

}  // namespace fastcorot::scene_detail
