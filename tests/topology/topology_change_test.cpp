// Randomized checks of TetMesh's incremental topological changes (topology_change.h): after every
// removal or addition, the mesh must equal one built from scratch from its tetrahedra and edge list
// (edges of each tetrahedron, orientations, vertex -> tetrahedron and vertex -> edge adjacency,
// tetrahedra per edge), every edge must be used by some tetrahedron, and the TopologyChange must
// describe exactly what happened: replaying its moves on a copy of the old arrays gives the new
// ones, and the isolated / reconnected points are those that lost or gained their last tetrahedron.
#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tet_mesh.h"
#include "fastcorot/topology/topology_change.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

TetMesh grid_mesh() {
  RegularGrid grid;
  grid.n = {6, 4, 3};
  grid.min = Vec3<double>(0, 0, 0);
  grid.max = Vec3<double>(5, 3, 2);
  return TetMesh(grid.num_points(), grid_tetrahedra(grid, true));
}

template <class T>
std::vector<T> copy(std::span<const T> values) {
  return {values.begin(), values.end()};
}

// Every derived table of `mesh` against a mesh rebuilt from its tetrahedra and edges.
void expect_same_as_rebuilt(const TetMesh& mesh) {
  const TetMesh fresh(mesh.num_points(), copy(mesh.tetrahedra()), copy(mesh.edges()));
  for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
    ASSERT_EQ(mesh.edges_of_tetrahedron(t), fresh.edges_of_tetrahedron(t)) << "tetrahedron " << t;
    for (int e = 0; e < 6; ++e) {
      ASSERT_EQ(mesh.edge_follows_mesh_edge(t, e), fresh.edge_follows_mesh_edge(t, e)) << "tetrahedron " << t;
    }
  }
  for (Index v = 0; v < mesh.num_points(); ++v) {
    ASSERT_EQ(copy(mesh.tetrahedra_around_vertex(v)), copy(fresh.tetrahedra_around_vertex(v))) << "vertex " << v;
    ASSERT_EQ(copy(mesh.edges_around_vertex(v)), copy(fresh.edges_around_vertex(v))) << "vertex " << v;
  }
  for (Index e = 0; e < mesh.num_edges(); ++e) {
    ASSERT_EQ(mesh.tetrahedra_around_edge_count(e), fresh.tetrahedra_around_edge_count(e)) << "edge " << e;
    ASSERT_GT(mesh.tetrahedra_around_edge_count(e), 0) << "edge " << e << " is used by no tetrahedron";
    const Edge& edge = mesh.edges()[static_cast<std::size_t>(e)];
    ASSERT_EQ(mesh.edge_between(edge[1], edge[0]), e);
  }
}

std::vector<bool> connected_points(const TetMesh& mesh) {
  std::vector<bool> connected(static_cast<std::size_t>(mesh.num_points()), false);
  for (const Tetrahedron& tet : mesh.tetrahedra()) {
    for (Index v : tet) connected[static_cast<std::size_t>(v)] = true;
  }
  return connected;
}

TEST(TopologyChange, RandomRemovalsAndAdditionsKeepEveryInvariant) {
  TetMesh mesh = grid_mesh();
  const std::vector<Tetrahedron> all = copy(mesh.tetrahedra());
  std::vector<Tetrahedron> removed_pool;  // tetrahedra removed so far, to add back
  std::mt19937 rng(8);
  for (int round = 0; round < 60; ++round) {
    const std::vector<Tetrahedron> tets_before = copy(mesh.tetrahedra());
    const std::vector<Edge> edges_before = copy(mesh.edges());
    const std::vector<bool> connected_before = connected_points(mesh);
    TopologyChange change;
    const bool add = !removed_pool.empty() && (rng() % 3 == 0 || mesh.num_tetrahedra() < 20);
    if (add) {
      std::shuffle(removed_pool.begin(), removed_pool.end(), rng);
      const std::size_t count = 1 + rng() % std::min<std::size_t>(removed_pool.size(), 12);
      const std::vector<Tetrahedron> back(removed_pool.end() - static_cast<std::ptrdiff_t>(count), removed_pool.end());
      removed_pool.resize(removed_pool.size() - count);
      change = mesh.add_tetrahedra(back);
      std::vector<Tetrahedron> expected = tets_before;
      expected.insert(expected.end(), back.begin(), back.end());
      ASSERT_EQ(copy(mesh.tetrahedra()), expected);
      ASSERT_EQ(change.first_added_tetrahedron, static_cast<Index>(tets_before.size()));
      ASSERT_EQ(change.num_added_tetrahedra, static_cast<Index>(count));
      ASSERT_EQ(change.first_added_edge, static_cast<Index>(edges_before.size()));
      ASSERT_EQ(mesh.num_edges(), change.first_added_edge + change.num_added_edges);
      ASSERT_TRUE(std::equal(edges_before.begin(), edges_before.end(), mesh.edges().begin()));
    } else {
      std::vector<Index> indices(tets_before.size());
      std::iota(indices.begin(), indices.end(), Index(0));
      std::shuffle(indices.begin(), indices.end(), rng);
      indices.resize(std::min<std::size_t>(indices.size(), 1 + rng() % 15));
      for (Index t : indices) removed_pool.push_back(tets_before[static_cast<std::size_t>(t)]);
      change = mesh.remove_tetrahedra(indices);
      // Replaying the moves on the old arrays gives the new ones.
      std::vector<Tetrahedron> replayed = tets_before;
      apply_moves(replayed, std::span<const IndexMove>(change.tetrahedron_moves));
      ASSERT_EQ(replayed, copy(mesh.tetrahedra()));
      std::vector<Edge> replayed_edges = edges_before;
      apply_moves(replayed_edges, std::span<const IndexMove>(change.edge_moves));
      ASSERT_EQ(replayed_edges, copy(mesh.edges()));
      for (std::size_t k = 0; k < change.removed_tetrahedra.size(); ++k) {
        ASSERT_EQ(change.removed_tetrahedron_vertices[k], tets_before[static_cast<std::size_t>(change.removed_tetrahedra[k])]);
      }
      for (std::size_t k = 0; k < change.removed_edges.size(); ++k) {
        ASSERT_EQ(change.removed_edge_vertices[k], edges_before[static_cast<std::size_t>(change.removed_edges[k])]);
      }
      // The index maps agree with the arrays.
      const std::vector<Index> map = old_to_new(static_cast<Index>(tets_before.size()), change.tetrahedron_moves);
      const IndexRenumbering renumber(change.removed_tetrahedra, change.tetrahedron_moves);
      for (std::size_t t = 0; t < tets_before.size(); ++t) {
        ASSERT_EQ(renumber(static_cast<Index>(t)), map[t]);
        const bool gone = std::find(indices.begin(), indices.end(), static_cast<Index>(t)) != indices.end();
        if (gone) {
          ASSERT_EQ(map[t], -1);
        } else {
          ASSERT_EQ(mesh.tetrahedron(map[t]), tets_before[t]);
        }
      }
    }
    expect_same_as_rebuilt(mesh);
    // Points that lost or gained their last tetrahedron are exactly the ones reported.
    const std::vector<bool> connected_after = connected_points(mesh);
    std::vector<Index> lost, gained;
    for (Index v = 0; v < mesh.num_points(); ++v) {
      if (connected_before[static_cast<std::size_t>(v)] && !connected_after[static_cast<std::size_t>(v)]) lost.push_back(v);
      if (!connected_before[static_cast<std::size_t>(v)] && connected_after[static_cast<std::size_t>(v)]) gained.push_back(v);
    }
    ASSERT_EQ(change.isolated_points, lost) << "round " << round;
    ASSERT_EQ(change.reconnected_points, gained) << "round " << round;
  }
  // Everything added back: the same set of tetrahedra as at the start.
  mesh.add_tetrahedra(removed_pool);
  std::vector<Tetrahedron> now = copy(mesh.tetrahedra()), start = all;
  std::sort(now.begin(), now.end());
  std::sort(start.begin(), start.end());
  EXPECT_EQ(now, start);
  expect_same_as_rebuilt(mesh);
}

TEST(TopologyChange, AddTetrahedraRejectsBadIndicesAndChangesNothing) {
  TetMesh mesh = grid_mesh();
  const Index n = mesh.num_tetrahedra(), e = mesh.num_edges();
  const std::vector<Tetrahedron> bad = {{0, 1, 7, 8}, {0, 1, 2, 1000}};
  EXPECT_THROW(mesh.add_tetrahedra(bad), Error);
  EXPECT_EQ(mesh.num_tetrahedra(), n);
  EXPECT_EQ(mesh.num_edges(), e);
  expect_same_as_rebuilt(mesh);
}

}  // namespace
}  // namespace fastcorot
