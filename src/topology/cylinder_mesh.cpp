#include "fastcorot/topology/cylinder_mesh.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <numbers>

namespace fastcorot {

CylinderMesh generate_cylinder(double radius, double height, const Vec3<double>& origin, Index circumferential,
                               Index radial, Index layers) {
  if (circumferential < 3 || radial < 1 || layers < 2) {
    throw make_error("GenerateCylinder: resolutions (", circumferential, ", ", radial, ", ", layers,
                     "): need at least 3 around, 1 across and 2 along");
  }
  if (!(radius > 0) || !std::isfinite(radius) || !(height > 0) || !std::isfinite(height) || !origin.allFinite()) {
    throw make_error("GenerateCylinder: radius ", radius, " and height ", height, " must be finite and > 0 (and origin finite)");
  }
  CylinderMesh mesh;
  const std::size_t theta = static_cast<std::size_t>(circumferential), rings = static_cast<std::size_t>(radial),
                    z_count = static_cast<std::size_t>(layers);
  for (std::size_t i = 0; i < z_count; ++i) {
    const double z = static_cast<double>(i) * height / static_cast<double>(z_count - 1);
    mesh.points.push_back(Vec3<double>(0, 0, z) + origin);
    for (std::size_t j = 1; j <= rings; ++j) {
      const double r = static_cast<double>(j) * radius / static_cast<double>(rings);
      for (std::size_t k = 0; k < theta; ++k) {
        const double angle = static_cast<double>(k) * 2 * std::numbers::pi / static_cast<double>(theta);
        mesh.points.push_back(Vec3<double>(r * std::cos(angle), r * std::sin(angle), z) + origin);
      }
    }
  }
  const Index layer = static_cast<Index>(theta * rings + 1);
  for (Index i = 1; i < layers; ++i) {
    Index centre = i * layer;
    Index previous = circumferential;
    for (Index k = 1; k <= circumferential; ++k) {
      // The prism between the axis and the first ring, in 3 tetrahedra.
      const Index p0 = centre, p1 = centre + previous, p2 = centre + k, p3 = p0 - layer, p4 = p1 - layer, p5 = p2 - layer;
      mesh.tetrahedra.push_back({p1, p0, p2, p3});
      mesh.tetrahedra.push_back({p1, p2, p4, p3});
      mesh.tetrahedra.push_back({p3, p4, p5, p2});
      previous = k;
    }
    for (Index j = 1; j < radial; ++j) {
      previous = circumferential;
      for (Index k = 1; k <= circumferential; ++k) {
        // The hexahedron between rings j and j + 1, in 6 tetrahedra.
        const Index h0 = centre + k, h1 = centre + previous, h2 = centre + k + circumferential,
                    h3 = centre + previous + circumferential;
        const Index h4 = h0 - layer, h5 = h1 - layer, h6 = h2 - layer, h7 = h3 - layer;
        mesh.tetrahedra.push_back({h0, h5, h4, h7});
        mesh.tetrahedra.push_back({h0, h1, h5, h3});
        mesh.tetrahedra.push_back({h5, h0, h3, h7});
        mesh.tetrahedra.push_back({h0, h3, h7, h2});
        mesh.tetrahedra.push_back({h7, h0, h2, h4});
        mesh.tetrahedra.push_back({h6, h7, h2, h4});
        previous = k;
      }
      centre += circumferential;
    }
  }
  return mesh;
}

}  // namespace fastcorot
