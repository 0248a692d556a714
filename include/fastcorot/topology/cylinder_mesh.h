// SOFA's GenerateCylinder (linear tetrahedra): a cylinder of the given radius and height along z
// from `origin`, with res_height layers of points, each a centre point then res_radial rings of
// res_circumferential points; the layers joined by 3 tetrahedra per triangular prism around the
// axis and 6 per hexahedron between rings, in SOFA's point and tetrahedron order.
#pragma once

#include "fastcorot/core/types.h"

#include <vector>

namespace fastcorot {

struct CylinderMesh {
  std::vector<Vec3<double>> points;
  std::vector<Tetrahedron> tetrahedra;
};

// Throws fastcorot::Error for a resolution below (3, 1, 2) or a radius or height that is not
// finite and > 0.
CylinderMesh generate_cylinder(double radius, double height, const Vec3<double>& origin, Index circumferential,
                               Index radial, Index layers);

}  // namespace fastcorot
