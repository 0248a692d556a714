// HexahedronFEMForceFieldAndMass's mass (sim/hexahedron_fem_mass.h) from its component: density and
// lumpedMass. Internal to src/scene (scene_builder.cpp); errors name the component.
#pragma once

#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/sim/mass.h"
#include "scene_data.h"

#include <span>

namespace fastcorot::scene_detail {

// The mass of HexahedronFEMForceFieldAndMass c whose force field (built from c) is `field`.
Mass<double> build_hexahedron_fem_mass(SceneData& data, Component& c, const HexahedronFEMForceField<double>& field,
                                       std::span<const Vec3<double>> rest);

}  // namespace fastcorot::scene_detail
