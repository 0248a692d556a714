// BarycentricMapping: SOFA's choice of tetrahedron (containing, deepest inside, else nearest centre
// among the grid's candidates) and the property every linear mapping has: any affine motion of the
// mesh moves every mapped point, inside or outside the mesh, by that affine motion.
#include "fastcorot/mapping/barycentric_mapping.h"

#include "fastcorot/core/error.h"
#include "support/deformations.h"

#include <gtest/gtest.h>

#include <random>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

// Two tetrahedra sharing the face (1, 2, 3), and a 3×3×3-point grid of 48 tetrahedra.
const Points kTwoRest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
const TetMesh kTwo(5, {{0, 1, 2, 3}, {1, 2, 3, 4}});

TEST(BarycentricMapping, APointInsideGetsItsTetrahedronAndCoordinates) {
  const Points points = {{0.1, 0.2, 0.3}, {0.6, 0.6, 0.6}};
  const auto mapping = map_onto_tetrahedra<double>(kTwo, kTwoRest, points);
  ASSERT_EQ(mapping.size(), 2u);
  EXPECT_EQ(mapping.tetrahedron[0], 0);
  // In the unit corner tetrahedron the coordinates along its edges are the point itself.
  EXPECT_LT((mapping.coordinates[0] - Vec3<double>(0.1, 0.2, 0.3)).norm(), 1e-15);
  EXPECT_EQ(mapping.tetrahedron[1], 1);
  Points out(2);
  mapping.apply(kTwo, kTwoRest, out);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_LT((out[i] - points[i]).norm(), 1e-14);
}

TEST(BarycentricMapping, OnASharedFaceTheDeepestWinsAndOutsideTheNearestCentre) {
  // On the shared face both tetrahedra give distance 0: the first one met keeps it (strict <).
  const Points on_face = {{1.0 / 3, 1.0 / 3, 1.0 / 3}};
  EXPECT_EQ(map_onto_tetrahedra<double>(kTwo, kTwoRest, on_face).tetrahedron[0], 0);
  // Outside both: the nearer centre, (0.25 0.25 0.25) against (0.5 0.5 0.5).
  const Points outside = {{-0.3, -0.2, -0.1}, {1.4, 1.3, 1.2}};
  const auto mapping = map_onto_tetrahedra<double>(kTwo, kTwoRest, outside);
  EXPECT_EQ(mapping.tetrahedron[0], 0);
  EXPECT_EQ(mapping.tetrahedron[1], 1);
  Points out(2);
  mapping.apply(kTwo, kTwoRest, out);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_LT((out[i] - outside[i]).norm(), 1e-14);  // extrapolated exactly
}

TEST(BarycentricMapping, AffineMotionsOfTheMeshMoveEveryMappedPointAffinely) {
  // A grid of 2×2×2 cells, 6 tetrahedra each, and points inside, on faces and outside.
  Points rest;
  for (int z = 0; z < 3; ++z) {
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < 3; ++x) rest.emplace_back(x, y, z);
    }
  }
  const auto at = [](int x, int y, int z) { return static_cast<Index>(x + 3 * y + 9 * z); };
  std::vector<Tetrahedron> tets;
  for (int z = 0; z < 2; ++z) {
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 2; ++x) {
        const Index c[8] = {at(x, y, z),         at(x + 1, y, z),         at(x + 1, y + 1, z),     at(x, y + 1, z),
                            at(x, y, z + 1),     at(x + 1, y, z + 1),     at(x + 1, y + 1, z + 1), at(x, y + 1, z + 1)};
        for (const auto& k : {std::array{0, 5, 1, 6}, std::array{0, 1, 3, 6}, std::array{1, 3, 6, 2},
                              std::array{6, 3, 0, 7}, std::array{6, 7, 0, 5}, std::array{7, 5, 4, 0}}) {
          tets.push_back({c[k[0]], c[k[1]], c[k[2]], c[k[3]]});
        }
      }
    }
  }
  const TetMesh mesh(27, tets);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.5, 2.5);
  Points points;
  for (int i = 0; i < 200; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  points.emplace_back(1, 1, 1);  // a vertex
  points.emplace_back(0.5, 1, 1);  // on an edge
  const auto mapping = map_onto_tetrahedra<double>(mesh, rest, points);
  Mat3<double> a;
  a << 1.2, 0.1, -0.3, 0.05, 0.9, 0.2, -0.1, 0.3, 1.1;
  const Vec3<double> b(3, -1, 2);
  Points moved;
  for (const auto& p : rest) moved.push_back(a * p + b);
  Points out(points.size());
  mapping.apply(mesh, moved, out);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_LT((out[i] - (a * points[i] + b)).norm(), 1e-12) << "point " << i;
    // Inside the mesh ([0, 2]^3), every coordinate is a true barycentric one.
    if ((points[i].array() >= 0).all() && (points[i].array() <= 2).all()) {
      const Vec3<double>& f = mapping.coordinates[i];
      EXPECT_GE(f.minCoeff(), -1e-12) << "point " << i;
      EXPECT_LE(f.sum(), 1 + 1e-12) << "point " << i;
    }
  }
}

TEST(BarycentricMapping, ExhaustiveSearchAgreesInsideAndPicksTheNearestCentreOutside) {
  // SOFA's MeshTopology mapper tries every tetrahedron: the same choice for points inside, the
  // globally nearest centre outside.
  const Points points = {{0.1, 0.2, 0.3}, {0.6, 0.6, 0.6}, {3, 3, 3}, {-2, 0.1, 0.1}};
  const auto grid = map_onto_tetrahedra<double>(kTwo, kTwoRest, points);
  const auto every = map_onto_tetrahedra<double>(kTwo, kTwoRest, points, TetrahedronSearch::exhaustive);
  EXPECT_EQ(every.tetrahedron[0], grid.tetrahedron[0]);
  EXPECT_EQ(every.tetrahedron[1], grid.tetrahedron[1]);
  EXPECT_EQ(every.tetrahedron[2], 1);  // centre (0.5 0.5 0.5) is nearer than (0.25 0.25 0.25)
  EXPECT_EQ(every.tetrahedron[3], 0);
}

TEST(BarycentricMapping, BadInputIsAnError) {
  const TetMesh empty(4, {});
  EXPECT_THROW(map_onto_tetrahedra<double>(empty, Points(4, Vec3<double>::Zero()), Points{{0, 0, 0}}), Error);
  EXPECT_THROW(map_onto_tetrahedra<double>(kTwo, kTwoRest, Points{{std::nan(""), 0, 0}}), Error);
  const auto mapping = map_onto_tetrahedra<double>(kTwo, kTwoRest, Points{{0.1, 0.1, 0.1}});
  Points wrong(2);
  EXPECT_THROW(mapping.apply(kTwo, kTwoRest, wrong), Error);
}

}  // namespace
}  // namespace fastcorot
