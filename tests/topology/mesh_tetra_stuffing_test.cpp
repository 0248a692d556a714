// SOFA's MeshTetraStuffing (src/topology/mesh_tetra_stuffing.cpp). Expected values come from a
// hand application of SOFA's lattice rule (MeshTetraStuffing.cpp, master 2a278d891f) to a lattice
// so coarse that one point is inside, and from properties any valid stuffing has: positive
// volumes, a conforming mesh with a closed boundary, points in the box, the enclosed volume
// (computed from the surface by the divergence theorem).
#include "fastcorot/topology/mesh_tetra_stuffing.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

namespace fastcorot {
namespace {

using Point = Vec3<double>;

struct Surface {
  std::vector<Point> points;
  std::vector<Triangle> triangles;
};

// The box [low, high] as 12 triangles with outward normals.
Surface box_surface(const Point& low, const Point& high) {
  Surface s;
  for (int k = 0; k < 8; ++k) {
    s.points.push_back({(k & 1) ? high.x() : low.x(), (k & 2) ? high.y() : low.y(), (k & 4) ? high.z() : low.z()});
  }
  // Each face as a quad a b c d counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    s.triangles.push_back({f[0], f[1], f[2]});
    s.triangles.push_back({f[0], f[2], f[3]});
  }
  return s;
}

// An icosahedron subdivided `levels` times, its points on the sphere of radius r about `centre`.
Surface sphere_surface(double r, const Point& centre, int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Point> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                          {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<Triangle> t = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& q : p) q.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<Index, Index>, Index> middle;
    const auto mid = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      if (auto it = middle.find(key); it != middle.end()) return it->second;
      p.push_back((p[static_cast<std::size_t>(a)] + p[static_cast<std::size_t>(b)]).normalized());
      return middle[key] = static_cast<Index>(p.size() - 1);
    };
    std::vector<Triangle> finer;
    for (const auto& f : t) {
      const Index ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    t = finer;
  }
  for (auto& q : p) q = centre + r * q;
  return {p, t};
}

// Volume enclosed by a closed outward surface: sum of a · (b × c) / 6.
double enclosed_volume(const Surface& s) {
  double v = 0;
  for (const auto& f : s.triangles) {
    v += s.points[static_cast<std::size_t>(f[0])].dot(
             s.points[static_cast<std::size_t>(f[1])].cross(s.points[static_cast<std::size_t>(f[2])])) / 6;
  }
  return v;
}

double signed_volume(const TetraStuffing& m, const Tetrahedron& t) {
  const auto& p = m.points;
  const Point a = p[static_cast<std::size_t>(t[0])];
  return (p[static_cast<std::size_t>(t[1])] - a).dot((p[static_cast<std::size_t>(t[2])] - a).cross(p[static_cast<std::size_t>(t[3])] - a)) / 6;
}

// Conforming: each face used by at most two tetrahedra, with opposite orientations; the faces used
// once (the boundary) form a closed surface: each of their edges in exactly two of them.
void expect_conforming_and_closed(const TetraStuffing& m) {
  std::map<std::array<Index, 3>, std::vector<bool>> faces;  // sorted face -> orientation parities
  for (const auto& t : m.tetrahedra) {
    const int opposite[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};  // outward faces
    for (const auto& f : opposite) {
      std::array<Index, 3> face = {t[static_cast<std::size_t>(f[0])], t[static_cast<std::size_t>(f[1])],
                                   t[static_cast<std::size_t>(f[2])]};
      // Parity of the permutation that sorts the face.
      bool parity = false;
      for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j) parity ^= face[static_cast<std::size_t>(i)] > face[static_cast<std::size_t>(j)];
      std::sort(face.begin(), face.end());
      faces[face].push_back(parity);
    }
  }
  std::map<std::pair<Index, Index>, int> boundary_edges;
  for (const auto& [face, parities] : faces) {
    ASSERT_LE(parities.size(), 2u) << "face " << face[0] << " " << face[1] << " " << face[2];
    if (parities.size() == 2) {
      EXPECT_NE(parities[0], parities[1]) << "face " << face[0] << " " << face[1] << " " << face[2];
    } else {
      for (int i = 0; i < 3; ++i) ++boundary_edges[std::minmax(face[static_cast<std::size_t>(i)], face[static_cast<std::size_t>((i + 1) % 3)])];
    }
  }
  for (const auto& [edge, count] : boundary_edges) EXPECT_EQ(count, 2) << "edge " << edge.first << " " << edge.second;
}

TEST(MeshTetraStuffing, OneInsidePointGivesTheTwentyFourLatticeTetrahedraAroundIt) {
  // A unit cube and a box (vbbox) a little larger, off-centre so that no lattice line runs along a
  // face diagonal. size = -1: the cell is the box's largest extent, s = 1.0368, and the first grid
  // has c0 = -(int(0.5) + 2) = -2 .. c1 = 2: 5 x 5 x 5 points, the second 6 x 6 x 6 from index 125.
  // Only the first grid's centre (index 2 + 5 (2 + 5 * 2) = 62, the box's centre) is inside: its
  // neighbours are s away, the second grid's points s / 2 > 0.502 away on each axis. Its tetrahedra
  // are the 4 around each of its 6 long edges: 24, of volume s^3 / 12 each, over 15 points.
  const Surface cube = box_surface({0, 0, 0}, {1, 1, 1});
  TetraStuffingOptions options;
  options.bbox = {Point(-0.0137, -0.0211, -0.0173), Point(1.0119, 1.0231, 1.0157)};
  options.size = -1;
  const TetraStuffing m = stuff_tetrahedra(cube.points, cube.triangles, {}, options);
  const double s = 1.0231 + 0.0211;
  EXPECT_DOUBLE_EQ(m.cell_size, s);
  ASSERT_EQ(m.tetrahedra.size(), 24u);
  ASSERT_EQ(m.points.size(), 15u);
  // Points kept, in lattice order: first grid 37, 57, 61, 62 (the centre), 63, 67, 87; second grid
  // 125 + x + 6 (y + 6 z) for x, y, z in {2, 3}. The first tetrahedron is the one SOFA makes first:
  // at point 62, around its edge to 61 (x - 1), with the second grid's points ph = 125 + 86 and
  // ph + 6: (62, 61, ph + 6, ph), positive as it stands (hand: a = (-1, 0, 0), b = (-1/2, 1/2, -1/2),
  // c = (-1/2, -1/2, -1/2), a . (b x c) = 1/2); renumbered (3, 2, 9, 7).
  EXPECT_EQ(m.tetrahedra[0], (Tetrahedron{3, 2, 9, 7}));
  const Point centre = (options.bbox[0] + options.bbox[1]) / 2;
  EXPECT_LT((m.points[3] - centre).norm(), 1e-12);
  EXPECT_LT((m.points[2] - (centre - Point(s, 0, 0))).norm(), 1e-12);
  EXPECT_LT((m.points[7] - (centre - Point(s, s, s) / 2)).norm(), 1e-12);
  double volume = 0;
  for (const auto& t : m.tetrahedra) {
    EXPECT_NEAR(signed_volume(m, t), s * s * s / 12, 1e-12);
    volume += signed_volume(m, t);
  }
  EXPECT_NEAR(volume, 2 * s * s * s, 1e-11);
  expect_conforming_and_closed(m);
}

TEST(MeshTetraStuffing, SplitAndSnappedSphereFillsItsVolumeWithPositiveConformingTetrahedra) {
  const Surface sphere = sphere_surface(1.0, {0.1, -0.2, 0.05}, 3);
  const double enclosed = enclosed_volume(sphere);
  EXPECT_NEAR(enclosed, 4 * std::numbers::pi / 3, 0.03 * 4);  // the polyhedron is a little smaller
  TetraStuffingOptions options;
  options.size = -10;
  options.snap_points = true;
  options.split_tetrahedra = true;
  const TetraStuffing m = stuff_tetrahedra(sphere.points, sphere.triangles, {}, options);
  ASSERT_GT(m.tetrahedra.size(), 100u);
  double volume = 0;
  for (const auto& t : m.tetrahedra) {
    const double v = signed_volume(m, t);
    EXPECT_GT(v, 0);
    volume += v;
  }
  // The tetrahedra end at the surface (cut points on it, snapped points on it): the volume is the
  // enclosed one but for the curved surface between crossings, well under 2% at 10 cells across.
  EXPECT_NEAR(volume, enclosed, 0.02 * enclosed);
  // Every point in the surface's box (the cut and snapped points are on the surface).
  const Point low = Point(0.1, -0.2, 0.05) - Point::Ones(), high = Point(0.1, -0.2, 0.05) + Point::Ones();
  for (const auto& p : m.points) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(p[k], low[k] - 1e-9);
      EXPECT_LE(p[k], high[k] + 1e-9);
    }
  }
  expect_conforming_and_closed(m);
}

TEST(MeshTetraStuffing, WholeLatticeTetrahedraCoverTheSurfaceWithoutSplitting) {
  // Without cutting, every lattice tetrahedron with a point inside is kept whole: the mesh covers
  // the solid, reaching at most one cell beyond it.
  const Surface sphere = sphere_surface(1.0, {0, 0, 0}, 2);
  TetraStuffingOptions options;
  options.size = 0.3;
  const TetraStuffing m = stuff_tetrahedra(sphere.points, sphere.triangles, {}, options);
  double volume = 0;
  for (const auto& t : m.tetrahedra) {
    EXPECT_NEAR(signed_volume(m, t), 0.3 * 0.3 * 0.3 / 12, 1e-12);  // the lattice's tetrahedra as they are
    volume += signed_volume(m, t);
  }
  EXPECT_GT(volume, enclosed_volume(sphere));
  for (const auto& p : m.points) EXPECT_LT(p.norm(), 1.0 + 0.3 + 1e-9);
  expect_conforming_and_closed(m);
}

TEST(MeshTetraStuffing, QuadsCountAsTwoTriangles) {
  // The cube as 6 quads gives what its 12 triangles give (a b c d -> a b c, a c d).
  const Surface cube = box_surface({0, 0, 0}, {1, 1, 1});
  std::vector<std::array<Index, 4>> quads;
  for (std::size_t f = 0; f < 6; ++f) {
    quads.push_back({cube.triangles[2 * f][0], cube.triangles[2 * f][1], cube.triangles[2 * f][2],
                     cube.triangles[2 * f + 1][2]});
  }
  TetraStuffingOptions options;
  options.size = -4;
  options.split_tetrahedra = true;
  const TetraStuffing a = stuff_tetrahedra(cube.points, cube.triangles, {}, options);
  const TetraStuffing b = stuff_tetrahedra(cube.points, {}, quads, options);
  EXPECT_EQ(a.tetrahedra, b.tetrahedra);
  EXPECT_EQ(a.points, b.points);
}

TEST(MeshTetraStuffing, TrianglesBeyondSofasOctreeCubeAreNotSeen) {
  // SOFA's TriangleOctree spans [-800, 800]^3 and leaves out triangles reaching beyond it: a cube
  // at 1000 has no crossings, no point inside, no tetrahedra; the same cube at 700 has some.
  TetraStuffingOptions options;
  options.size = -4;
  const Surface far = box_surface({1000, 1000, 1000}, {1001, 1001, 1001});
  EXPECT_TRUE(stuff_tetrahedra(far.points, far.triangles, {}, options).tetrahedra.empty());
  const Surface near = box_surface({700, 700, 700}, {701, 701, 701});
  EXPECT_FALSE(stuff_tetrahedra(near.points, near.triangles, {}, options).tetrahedra.empty());
}

TEST(MeshTetraStuffing, BadInputIsAnErrorNamingWhatIsWrong) {
  const Surface cube = box_surface({0, 0, 0}, {1, 1, 1});
  const auto message = [](auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { stuff_tetrahedra({}, cube.triangles, {}, {}); }).find("empty input surface"), std::string::npos);
  EXPECT_NE(message([&] { stuff_tetrahedra(cube.points, {}, {}, {}); }).find("empty input surface"), std::string::npos);
  EXPECT_NE(message([&] { stuff_tetrahedra(cube.points, {{0, 1, 8}}, {}, {}); }).find("point 8 of 8"), std::string::npos);
  TetraStuffingOptions zero;
  zero.size = 0;
  EXPECT_NE(message([&] { stuff_tetrahedra(cube.points, cube.triangles, {}, zero); }).find("size 0"), std::string::npos);
  TetraStuffingOptions tiny;
  tiny.size = 1e-5;
  EXPECT_NE(message([&] { stuff_tetrahedra(cube.points, cube.triangles, {}, tiny); }).find("lattice points"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
