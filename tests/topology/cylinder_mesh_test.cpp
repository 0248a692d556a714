// GenerateCylinder's mesh: counts and the first elements as SOFA's loops make them, worked out by
// hand, and the volume of the prism over the inscribed polygon.
#include "fastcorot/topology/cylinder_mesh.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace fastcorot {
namespace {

TEST(CylinderMesh, SofasPointsAndTetrahedra) {
  const CylinderMesh mesh = generate_cylinder(0.5, 2.0, {1, 0, 0}, 4, 2, 3);
  // (4 x 2 + 1) points per layer, 3 layers; 3 x 4 x 2 prism tetrahedra and 6 x 1 x 4 x 2 others.
  ASSERT_EQ(mesh.points.size(), 27u);
  ASSERT_EQ(mesh.tetrahedra.size(), 24u + 48u);
  EXPECT_EQ(mesh.points[0], Vec3<double>(1, 0, 0));
  EXPECT_NEAR((mesh.points[2] - Vec3<double>(1, 0.25, 0)).norm(), 0, 1e-15);  // ring 1, k = 1: r 0.25, 90 degrees
  EXPECT_NEAR((mesh.points[5] - Vec3<double>(1.5, 0, 0)).norm(), 0, 1e-15);   // ring 2, k = 0
  EXPECT_EQ(mesh.points[9], Vec3<double>(1, 0, 1));                           // layer 1's centre
  // Layer 1's first prism: centre 9, ring points 9 + 4 (previous k) and 9 + 1, and the three below.
  EXPECT_EQ(mesh.tetrahedra[0], (Tetrahedron{13, 9, 10, 0}));
  EXPECT_EQ(mesh.tetrahedra[1], (Tetrahedron{13, 10, 4, 0}));
  EXPECT_EQ(mesh.tetrahedra[2], (Tetrahedron{0, 4, 1, 10}));
  // Its first hexahedron: h0 = 10, h1 = 13, h2 = 14, h3 = 17 and the four 9 below.
  EXPECT_EQ(mesh.tetrahedra[12], (Tetrahedron{10, 4, 1, 8}));
  double volume = 0;
  for (const auto& t : mesh.tetrahedra) {
    const auto& a = mesh.points[static_cast<std::size_t>(t[0])];
    const double v = (mesh.points[static_cast<std::size_t>(t[1])] - a)
                         .dot((mesh.points[static_cast<std::size_t>(t[2])] - a).cross(mesh.points[static_cast<std::size_t>(t[3])] - a)) / 6;
    EXPECT_GT(std::abs(v), 1e-6);
    volume += std::abs(v);
  }
  EXPECT_NEAR(volume, 4.0 / 2 * 0.25 * std::sin(2 * std::numbers::pi / 4) * 2.0, 1e-12);
}

TEST(CylinderMesh, BadResolutionsAndSizesAreRefused) {
  EXPECT_THROW(generate_cylinder(0.5, 1, {0, 0, 0}, 2, 1, 2), Error);
  EXPECT_THROW(generate_cylinder(0.5, 1, {0, 0, 0}, 3, 1, 1), Error);
  EXPECT_THROW(generate_cylinder(0, 1, {0, 0, 0}, 3, 1, 2), Error);
  EXPECT_THROW(generate_cylinder(0.5, std::nan(""), {0, 0, 0}, 3, 1, 2), Error);
}

}  // namespace
}  // namespace fastcorot
