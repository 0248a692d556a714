// The masses of a scene: UniformMass (totalMass shared out, or vertexMass), DiagonalMass and
// MeshMatrixMass on tetrahedra (SOFA's lumped and consistent linear-tetrahedron masses, following
// the mesh when it is cut) or on a grid's hexahedra (hexahedron_builders.h), from massDensity or
// scaled to totalMass. Internal to src/scene (scene_builder.cpp); errors name the component.
#pragma once

#include "fastcorot/sim/mass.h"
#include "fastcorot/sim/mechanical_state.h"
#include "scene_data.h"

#include <functional>
#include <memory>

namespace fastcorot::scene_detail {

// `tetrahedra` gives the component's tetrahedral mesh (the one its force fields share), asked only
// for DiagonalMass and MeshMatrixMass without hexahedra.
Mass<double> build_mass(SceneData& data, Component& c, const Points<double>& rest,
                        const std::function<std::shared_ptr<TetMesh>()>& tetrahedra);

}  // namespace fastcorot::scene_detail
