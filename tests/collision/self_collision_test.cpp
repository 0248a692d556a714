// SOFA's self-collision pruning (collision/self_collision.h) on a hand-made strip: points 0..5 in two
// rows, triangles (0 1 3) (0 3 2) (2 3 5) (2 5 4), its edges; each rule's cases written out from
// SOFA's canCollideWithElement (Point, Line, Triangle models), not from the code under test.
#include "fastcorot/collision/self_collision.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using V = Vec3<double>;

struct Strip {
  std::vector<CollisionModel<double>> models;  // triangles, lines, points, a second point model, another node's points
  Strip() {
    auto points = std::make_shared<CollisionPoints<double>>(
        CollisionPoints<double>::still({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0), V(0, 2, 0), V(1, 2, 0)}));
    const std::vector<Edge> edges = {{0, 1}, {1, 3}, {3, 0}, {3, 2}, {2, 0}, {3, 5}, {5, 2}, {5, 4}, {4, 2}};
    const auto topology = std::make_shared<const SelfCollisionTopology>(self_collision_topology(6, edges));
    CollisionModel<double> t, l, p, q, other;
    for (auto* m : {&t, &l, &p, &q}) {
      m->node = "root/strip";
      m->self_collision = true;
      m->points = points;
    }
    t.kind = CollisionElements::triangles;
    t.triangles = {{0, 1, 3}, {0, 3, 2}, {2, 3, 5}, {2, 5, 4}};
    l.kind = CollisionElements::lines;
    l.edges = edges;
    l.self_topology = topology;
    p.kind = CollisionElements::points;
    p.self_topology = topology;
    p.node_point_model = true;
    q.kind = CollisionElements::points;  // a second PointCollisionModel of the node
    q.self_topology = topology;
    other = p;
    other.node = "root/other";
    models = {t, l, p, q, other};
  }
  bool can(std::size_t a, Index e1, std::size_t b, Index e2) const { return can_collide_elements<double>(models, a, e1, b, e2); }
};

constexpr std::size_t T = 0, L = 1, P = 2, Q = 3, OTHER = 4;

TEST(SelfCollision, TrianglesSkipTheirOwnVerticesOfTheNodesPointModel) {
  Strip s;
  EXPECT_FALSE(s.can(T, 0, P, 3));  // vertex of triangle (0 1 3)
  EXPECT_TRUE(s.can(T, 0, P, 4));
  EXPECT_TRUE(s.can(T, 0, Q, 3)) << "only the node's first point model is pruned";
  EXPECT_TRUE(s.can(T, 0, OTHER, 3)) << "another node: never pruned";
  s.models[T].self_collision = false;
  EXPECT_TRUE(s.can(T, 0, P, 3)) << "a model without selfCollision prunes nothing";
}

TEST(SelfCollision, SegmentsSkipNeighboursThroughTheirEndsEdges) {
  const Strip s;
  EXPECT_FALSE(s.can(L, 0, L, 3)) << "(0 1) and (3 2): edge (1 3) joins them";
  EXPECT_FALSE(s.can(L, 0, L, 1)) << "shared end 1";
  EXPECT_TRUE(s.can(L, 0, L, 7)) << "(0 1) and (5 4): nothing around their ends in common";
  // Against the node's point model: not its ends, nor the ends of the edges around its ends.
  EXPECT_FALSE(s.can(L, 0, P, 1));
  EXPECT_FALSE(s.can(L, 0, P, 2)) << "end of edge (2 0) around 0";
  EXPECT_TRUE(s.can(L, 0, P, 4));
  EXPECT_TRUE(s.can(L, 0, P, 5));
  // A point model asks the segment model (SOFA's delegation, elements swapped).
  EXPECT_FALSE(s.can(P, 2, L, 0));
  EXPECT_TRUE(s.can(P, 4, L, 0));
  // A second point model: each asks the other once, then neither prunes.
  EXPECT_TRUE(s.can(L, 0, Q, 1));
  EXPECT_TRUE(s.can(Q, 1, L, 0));
}

TEST(SelfCollision, PointsOfOneModelOnlyFromTheLargerIndexAndNotNearby) {
  const Strip s;
  EXPECT_FALSE(s.can(P, 1, P, 4)) << "i <= j";
  EXPECT_FALSE(s.can(P, 4, P, 4));
  EXPECT_FALSE(s.can(P, 5, P, 2)) << "neighbours (edge 5 2)";
  EXPECT_FALSE(s.can(P, 4, P, 0)) << "a common neighbour (2)";
  EXPECT_TRUE(s.can(P, 4, P, 1)) << "4's neighbours {5, 2} and 1's {0, 3}: none shared (two edges apart is not near)";
}

TEST(SelfCollision, ACornerOnlyTouchingIsSkippedBeyondSofa) {
  const Strip s;
  EXPECT_TRUE(elements_touch(s.models[T], 0, s.models[T], 1)) << "(0 1 3) and (0 3 2) share 0 and 3";
  EXPECT_FALSE(elements_touch(s.models[T], 0, s.models[T], 3)) << "(0 1 3) and (2 5 4)";
  EXPECT_TRUE(elements_touch(s.models[T], 3, s.models[L], 7));
  EXPECT_FALSE(elements_touch(s.models[L], 0, s.models[L], 7)) << "segments alone: SOFA's rules decide";
  EXPECT_THROW(self_collision_topology(3, std::vector<Edge>{{0, 3}}), Error);
}

}  // namespace
}  // namespace fastcorot
