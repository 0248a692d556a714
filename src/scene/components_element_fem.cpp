// SOFA master's element FEM family: CorotationalFEMForceField, LinearSmallStrainFEMForceField,
// FEMMass and NodalMassDensity (docs/element-fem.md).
#include "component_families.h"

namespace fastcorot::scene_detail {

namespace {

std::vector<AttributeSpec> element_force_field_attributes(bool corotational) {
  std::vector<AttributeSpec> attributes = {
      {"youngModulus", "reals", "5000", "E > 0, one value or one per element"},
      {"poissonRatio", "reals", "0.45", "nu in [0, 0.5), one value or one per element"},
      {"topology", "link", "", "the topology of tetrahedra or hexahedra (default: the node's)"},
      {"computeForceStrategy", "string", "sequenced",
       "sequenced or parallel (SOFA's element loop; here the elements always run on the simulation's threads, "
       "with the same results)"},
      {"computeForceDerivStrategy", "string", "sequenced", "sequenced or parallel, as computeForceStrategy"},
      {"rayleighStiffness", "real", "0", "the force field's own stiffness-proportional damping"},
      {"elementStiffness", "string", "", "SOFA's output (the element matrices); accepted, not read"},
      {"elementSpace", "real", "0.125", "display option, accepted"}};
  if (corotational) {
    attributes.push_back({"rotationMethod", "string", "triangle / hexahedron",
                          "triangle (tetrahedra's default: frame of corners 0, 1, 2), hexahedron (hexahedra's default: "
                          "frame of the mean edges), polar, stable_polar or identity"});
  }
  return attributes;
}

}  // namespace

std::vector<ComponentSpec> element_fem_components() {
  return {
      {"CorotationalFEMForceField", "forcefield",
       "SOFA master's corotational linear element, templates Vec3,Tetrahedron and Vec3,Hexahedron: K of the rest shape "
       "by SOFA's quadrature, element rotation from the corners, forces R K (R^T (x - c) - (x0 - c0)) about the "
       "centroids (docs/element-fem.md).",
       element_force_field_attributes(true)},
      {"LinearSmallStrainFEMForceField", "forcefield",
       "SOFA master's linear small-strain element, templates Vec3,Tetrahedron and Vec3,Hexahedron: forces K (x - x0) "
       "(docs/element-fem.md).",
       element_force_field_attributes(false)},
      {"FEMMass", "mass",
       "SOFA master's finite-element mass, templates Vec3,Tetrahedron and Vec3,Hexahedron: the consistent matrix "
       "sum_q w rho(q) |det J| N N^T with the element's own quadrature (one point for tetrahedra: rho V / 16 in each "
       "entry; 2x2x2 Gauss points for hexahedra), never lumped; gravity through it.",
       {{"nodalMassDensity", "link", "", "the NodalMassDensity (default: the first in its node or above)"},
        {"topology", "link", "", "the topology of tetrahedra or hexahedra (default: the node's)"}}},
      {"NodalMassDensity", "property",
       "SOFA master's mass density per node, read by FEMMass: node i has property[i], or the last value when the list "
       "is shorter.",
       {{"property", "reals", "1", "densities (one value, or one per node)"}}},
  };
}

}  // namespace fastcorot::scene_detail
