// The pieces of SOFA master's element FEM family in a scene: CorotationalFEMForceField and
// LinearSmallStrainFEMForceField (element_fem_force_field.h) and FEMMass with its
// NodalMassDensity (finite_element.h), on tetrahedra (template Vec3,Tetrahedron: any tetrahedral
// topology) or hexahedra (Vec3,Hexahedron: a grid's cells). Internal to src/scene
// (scene_builder.cpp, mass_builders.cpp); errors name the component and the attribute.
#pragma once

#include "fastcorot/fem/force_field.h"
#include "fastcorot/sim/mass.h"
#include "scene_data.h"

#include <functional>
#include <memory>
#include <span>
#include <string_view>

namespace fastcorot::scene_detail {

bool is_element_fem(std::string_view type);

// The element of c's template: 4 (Vec3,Tetrahedron) or 8 (Vec3,Hexahedron). Throws
// fastcorot::Error naming c for a missing template or one SOFA has and fastcorot does not.
int element_template_nodes(SceneData& data, Component& c);

// A CorotationalFEMForceField or LinearSmallStrainFEMForceField on c's topology: the tetrahedra of
// `tetrahedra()` or the hexahedra of its grid. `drawn` receives the tetrahedral mesh it reports.
std::shared_ptr<ForceField<double>> build_element_fem(SceneData& data, Component& c, std::span<const Vec3<double>> rest,
                                                      const std::function<std::shared_ptr<TetMesh>()>& tetrahedra,
                                                      std::shared_ptr<TetMesh>& drawn);

// FEMMass: the consistent mass matrix assembled from the element mass matrices of c's topology,
// with the densities of its NodalMassDensity (the `nodalMassDensity` link, else the first one in
// its node or above).
Mass<double> build_fem_mass(SceneData& data, Component& c, std::span<const Vec3<double>> rest,
                            const std::function<std::shared_ptr<TetMesh>()>& tetrahedra);

}  // namespace fastcorot::scene_detail
