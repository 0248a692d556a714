// Tests of TetMesh (SOFA's TetrahedronSetTopologyContainer semantics), signed_volume and
// check_rest_volumes. Every expected table below is derived by hand in the comment beside it; the
// derived edge order of one tetrahedron is also checked against the edge list SOFA itself wrote
// (tests/data/sofa_reference/single_tet_qr.json, key "edges"). Beside the example values, a
// property check (`expect_consistent`) verifies on every mesh that each local edge maps to the mesh
// edge with the same two vertices and that the orientation bit says whether tet[k] == edge[0].
#include "fastcorot/topology/tet_mesh.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace fastcorot {
namespace {

std::string sofa_reference_dir() {
#ifdef FASTCOROT_SOFA_REFERENCE_DIR
  return FASTCOROT_SOFA_REFERENCE_DIR;
#else
  // Standalone builds: the data lie beside this file's folder (tests/topology/ → tests/data/).
  const std::string file = __FILE__;
  return file.substr(0, file.rfind("/topology/")) + "/data/sofa_reference";
#endif
}

// Runs `f`, expects it to throw fastcorot::Error and returns the message ("" when it did not throw).
template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected fastcorot::Error, nothing was thrown";
  return {};
}

// True when `message` contains every one of `parts`.
testing::AssertionResult mentions(const std::string& message,
                                  std::initializer_list<const char*> parts) {
  for (const char* part : parts) {
    if (message.find(part) == std::string::npos) {
      return testing::AssertionFailure() << "message \"" << message << "\" does not contain \""
                                         << part << "\"";
    }
  }
  return testing::AssertionSuccess();
}

std::vector<Edge> to_vector(std::span<const Edge> edges) { return {edges.begin(), edges.end()}; }
std::vector<Index> to_vector(std::span<const Index> indices) {
  return {indices.begin(), indices.end()};
}
std::vector<Tetrahedron> to_vector(std::span<const Tetrahedron> tets) {
  return {tets.begin(), tets.end()};
}

std::array<bool, 6> orientations(const TetMesh& mesh, Index t) {
  std::array<bool, 6> bits{};
  for (int e = 0; e < 6; ++e) bits[static_cast<std::size_t>(e)] = mesh.edge_follows_mesh_edge(t, e);
  return bits;
}

// Property check independent of any table: each local edge (k, l) of each tetrahedron maps to a
// mesh edge joining the same two points, the orientation bit is tet[k] == edge[0], the edges are
// distinct and non-degenerate, and the adjacency is exactly the sorted list of tetrahedra holding v.
void expect_consistent(const TetMesh& mesh) {
  std::set<std::pair<Index, Index>> undirected;
  for (const Edge& edge : mesh.edges()) {
    EXPECT_NE(edge[0], edge[1]);
    EXPECT_TRUE(undirected.insert({std::min(edge[0], edge[1]), std::max(edge[0], edge[1])}).second)
        << "edge (" << edge[0] << ", " << edge[1] << ") repeats";
  }
  for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
    const Tetrahedron& tet = mesh.tetrahedron(t);
    for (int e = 0; e < 6; ++e) {
      const Index a = tet[static_cast<std::size_t>(kTetrahedronEdges[e][0])];
      const Index b = tet[static_cast<std::size_t>(kTetrahedronEdges[e][1])];
      const Index m = mesh.edges_of_tetrahedron(t)[static_cast<std::size_t>(e)];
      ASSERT_GE(m, 0);
      ASSERT_LT(m, mesh.num_edges());
      const Edge& edge = mesh.edges()[static_cast<std::size_t>(m)];
      EXPECT_EQ(std::min(a, b), std::min(edge[0], edge[1])) << "tetrahedron " << t << " edge " << e;
      EXPECT_EQ(std::max(a, b), std::max(edge[0], edge[1])) << "tetrahedron " << t << " edge " << e;
      EXPECT_EQ(mesh.edge_follows_mesh_edge(t, e), a == edge[0])
          << "tetrahedron " << t << " edge " << e;
    }
  }
  for (Index v = 0; v < mesh.num_points(); ++v) {
    std::vector<Index> expected;
    for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
      const Tetrahedron& tet = mesh.tetrahedron(t);
      if (std::find(tet.begin(), tet.end(), v) != tet.end()) expected.push_back(t);
    }
    EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(v)), expected) << "vertex " << v;
  }
}

// ---------------------------------------------------------------------------------------------
// The meshes used below.
//
// Two tetrahedra sharing the face {1, 2, 3}: A = (0 1 2 3) and B = (4 2 1 3), on 5 points.
// Positions (for the geometric checks): p0 = (0,0,0), p1 = (1,0,0), p2 = (0,1,0), p3 = (0,0,1),
// p4 = (1,1,1); p4 lies on the far side of the plane x+y+z = 1 from p0.
//   A: dot(p1-p0, (p2-p0)×(p3-p0)) = dot(x, y×z) = 1 > 0          → positively oriented.
//   B: p2-p4 = (-1,0,-1), p1-p4 = (0,-1,-1), p3-p4 = (-1,-1,0);
//      (0,-1,-1)×(-1,-1,0) = (-1, 1, -1); dot((-1,0,-1), (-1,1,-1)) = 2 > 0 → positively oriented.
//
// Derived edges (SOFA order: tetrahedra in order, local edges (0,1)(0,2)(0,3)(1,2)(1,3)(2,3),
// a new edge stored (min, max)):
//   A (0 1 2 3): (0,1)→0 [0,1]  (0,2)→1 [0,2]  (0,3)→2 [0,3]  (1,2)→3 [1,2]  (1,3)→4 [1,3]
//                (2,3)→5 [2,3]
//   B (4 2 1 3): (4,2)→6 [2,4]  (4,1)→7 [1,4]  (4,3)→8 [3,4]  (2,1)→3  (2,3)→5  (1,3)→4
// Nine edges, each once.
const std::vector<Tetrahedron> kTwoTets = {{0, 1, 2, 3}, {4, 2, 1, 3}};
const std::vector<Edge> kTwoTetsDerivedEdges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3},
                                                {2, 3}, {2, 4}, {1, 4}, {3, 4}};

std::vector<Vec3<double>> two_tets_points() {
  return {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0),
          Vec3<double>(0, 0, 1), Vec3<double>(1, 1, 1)};
}

// The same nine edges of kTwoTets, shuffled, four of them reversed (marked *):
//   0 [3,4]  1 [2,1]*  2 [0,3]  3 [4,1]*  4 [1,3]  5 [2,0]*  6 [3,2]*  7 [0,1]  8 [2,4]
const std::vector<Edge> kTwoTetsShuffledEdges = {{3, 4}, {2, 1}, {0, 3}, {4, 1}, {1, 3},
                                                 {2, 0}, {3, 2}, {0, 1}, {2, 4}};

// ---------------------------------------------------------------------------------------------
// Derived edges.

// Ground truth from SOFA itself: tests/data/sofa_reference/single_tet_qr.json (SOFA master
// 2a278d891f), key "edges", for the tetrahedron (2,3,1,0) on 4 points:
//   [[2,3],[1,2],[0,2],[1,3],[0,3],[0,1]].
// By hand: (0,1)→(2,3) [2,3]; (0,2)→(2,1) [1,2]; (0,3)→(2,0) [0,2]; (1,2)→(3,1) [1,3];
// (1,3)→(3,0) [0,3]; (2,3)→(1,0) [0,1].
TEST(TetMeshTest, SingleTetrahedronEdgesMatchSofa) {
  const TetMesh mesh(4, {{2, 3, 1, 0}});
  const std::vector<Edge> expected = {{2, 3}, {1, 2}, {0, 2}, {1, 3}, {0, 3}, {0, 1}};
  EXPECT_EQ(to_vector(mesh.edges()), expected);

  std::ifstream file(sofa_reference_dir() + "/single_tet_qr.json");
  ASSERT_TRUE(file) << "cannot open single_tet_qr.json in " << sofa_reference_dir();
  const nlohmann::json reference = nlohmann::json::parse(file);
  const auto sofa_tets = reference.at("tetrahedra").get<std::vector<std::array<Index, 4>>>();
  const auto sofa_edges = reference.at("edges").get<std::vector<std::array<Index, 2>>>();
  const auto sofa_rest = reference.at("rest").get<std::vector<std::array<double, 3>>>();
  const TetMesh from_file(static_cast<Index>(sofa_rest.size()), sofa_tets);
  EXPECT_EQ(to_vector(from_file.edges()), sofa_edges);
  EXPECT_EQ(sofa_edges, expected);

  // Local edge e created mesh edge e. Orientation tet[k] == edge[0]:
  //   e0: 2 == 2 yes; e1: 2 vs 1; e2: 2 vs 0; e3: 3 vs 1; e4: 3 vs 0; e5: 1 vs 0 → only e0.
  const std::array<Index, 6> identity = {0, 1, 2, 3, 4, 5};
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), identity);
  EXPECT_EQ(orientations(mesh, 0), (std::array<bool, 6>{true, false, false, false, false, false}));
  expect_consistent(mesh);
}

TEST(TetMeshTest, SortedTetrahedronEdgesAllFollowTheirMeshEdges) {
  // (0 1 2 3): every local edge (k, l) has tet[k] < tet[l], so every new edge is stored as it
  // runs locally and every orientation bit is set.
  const TetMesh mesh(4, {{0, 1, 2, 3}});
  const std::vector<Edge> expected = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  EXPECT_EQ(to_vector(mesh.edges()), expected);
  EXPECT_EQ(orientations(mesh, 0), (std::array<bool, 6>{true, true, true, true, true, true}));
}

TEST(TetMeshTest, TwoTetrahedraSharingAFaceHaveNineEdgesEachOnce) {
  const TetMesh mesh(5, kTwoTets);
  EXPECT_EQ(mesh.num_points(), 5);
  EXPECT_EQ(mesh.num_tetrahedra(), 2);
  EXPECT_EQ(mesh.num_edges(), 9);
  EXPECT_EQ(to_vector(mesh.edges()), kTwoTetsDerivedEdges);
  EXPECT_EQ(to_vector(mesh.tetrahedra()), kTwoTets);

  // From the table above kTwoTets.
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{6, 7, 8, 3, 5, 4}));
  // A is sorted: all bits set. B = (4 2 1 3): e0 4 vs [2,4][0]=2 no; e1 4 vs [1,4] no;
  // e2 4 vs [3,4] no; e3 2 vs [1,2] no; e4 2 vs [2,3] yes; e5 1 vs [1,3] yes.
  EXPECT_EQ(orientations(mesh, 0), (std::array<bool, 6>{true, true, true, true, true, true}));
  EXPECT_EQ(orientations(mesh, 1), (std::array<bool, 6>{false, false, false, false, true, true}));
  expect_consistent(mesh);
}

TEST(TetMeshTest, EmptyMeshHasNoEdgesAndNoAdjacency) {
  const TetMesh mesh(3, {});
  EXPECT_EQ(mesh.num_points(), 3);
  EXPECT_EQ(mesh.num_tetrahedra(), 0);
  EXPECT_EQ(mesh.num_edges(), 0);
  for (Index v = 0; v < 3; ++v) EXPECT_TRUE(mesh.tetrahedra_around_vertex(v).empty());
  EXPECT_TRUE(mesh.boundary_triangles().empty());
}

// ---------------------------------------------------------------------------------------------
// Explicit edge lists.

TEST(TetMeshTest, ExplicitShuffledEdgesKeepTheirOrderAndOrientation) {
  const TetMesh mesh(5, kTwoTets, kTwoTetsShuffledEdges);
  EXPECT_EQ(to_vector(mesh.edges()), kTwoTetsShuffledEdges);

  // With kTwoTetsShuffledEdges (0 [3,4] 1 [2,1] 2 [0,3] 3 [4,1] 4 [1,3] 5 [2,0] 6 [3,2] 7 [0,1]
  // 8 [2,4]), orientation bit = (tet[k] == edge[0]):
  //   A (0 1 2 3): (0,1)→7 [0,1] yes; (0,2)→5 [2,0] no; (0,3)→2 [0,3] yes; (1,2)→1 [2,1] no;
  //                (1,3)→4 [1,3] yes; (2,3)→6 [3,2] no.
  //   B (4 2 1 3): (4,2)→8 [2,4] no; (4,1)→3 [4,1] yes; (4,3)→0 [3,4] no; (2,1)→1 [2,1] yes;
  //                (2,3)→6 [3,2] no; (1,3)→4 [1,3] yes.
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{7, 5, 2, 1, 4, 6}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{8, 3, 0, 1, 6, 4}));
  EXPECT_EQ(orientations(mesh, 0), (std::array<bool, 6>{true, false, true, false, true, false}));
  EXPECT_EQ(orientations(mesh, 1), (std::array<bool, 6>{false, true, false, true, false, true}));
  expect_consistent(mesh);
}

TEST(TetMeshTest, ExplicitEdgesInDerivedOrderGiveTheDerivedMesh) {
  const TetMesh derived(5, kTwoTets);
  const TetMesh explicit_edges(5, kTwoTets, kTwoTetsDerivedEdges);
  EXPECT_EQ(to_vector(explicit_edges.edges()), to_vector(derived.edges()));
  for (Index t = 0; t < 2; ++t) {
    EXPECT_EQ(explicit_edges.edges_of_tetrahedron(t), derived.edges_of_tetrahedron(t));
    EXPECT_EQ(orientations(explicit_edges, t), orientations(derived, t));
  }
}

TEST(TetMeshTest, ExplicitEdgesNotUsedByAnyTetrahedronAreKept) {
  // [0,4] joins the two apexes and belongs to no tetrahedron; SOFA keeps it.
  std::vector<Edge> edges = kTwoTetsShuffledEdges;
  edges.push_back({0, 4});
  const TetMesh mesh(5, kTwoTets, edges);
  EXPECT_EQ(mesh.num_edges(), 10);
  EXPECT_EQ(to_vector(mesh.edges()), edges);
  for (Index t = 0; t < 2; ++t) {
    for (Index m : mesh.edges_of_tetrahedron(t)) EXPECT_NE(m, 9);
  }
  expect_consistent(mesh);
}

// ---------------------------------------------------------------------------------------------
// Adjacency and boundary.

TEST(TetMeshTest, TetrahedraAroundVertex) {
  const TetMesh mesh(6, kTwoTets);  // point 5 belongs to no tetrahedron
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(0)), (std::vector<Index>{0}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(1)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(2)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(3)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(4)), (std::vector<Index>{1}));
  EXPECT_TRUE(mesh.tetrahedra_around_vertex(5).empty());
}

TEST(TetMeshTest, TetrahedraAroundVertexAreSortedWhenVertexPositionsVary) {
  // Vertex 0 sits at a different local position in each tetrahedron (3, 0, 2, 1) and vertex 5
  // skips tetrahedron 1: adjacency must still list tetrahedra in increasing order.
  const TetMesh mesh(7, {{1, 2, 3, 0}, {0, 4, 1, 2}, {6, 5, 0, 3}, {4, 0, 5, 6}});
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(0)), (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(1)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(2)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(3)), (std::vector<Index>{0, 2}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(4)), (std::vector<Index>{1, 3}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(5)), (std::vector<Index>{2, 3}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(6)), (std::vector<Index>{2, 3}));
  expect_consistent(mesh);
}

void expect_boundary_equal(const std::vector<BoundaryTriangle>& actual,
                           const std::vector<BoundaryTriangle>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_EQ(actual[i].vertices, expected[i].vertices) << "boundary triangle " << i;
    EXPECT_EQ(actual[i].tetrahedron, expected[i].tetrahedron) << "boundary triangle " << i;
    EXPECT_EQ(actual[i].face, expected[i].face) << "boundary triangle " << i;
  }
}

TEST(TetMeshTest, SingleTetrahedronHasFourBoundaryTriangles) {
  // Tetrahedron (2 3 1 0), faces kTetrahedronFaces = (1 2 3) (0 3 2) (1 3 0) (0 2 1) in local
  // indices: face 0 → (3 1 0), face 1 → (2 0 1), face 2 → (3 0 2), face 3 → (2 1 3).
  const TetMesh mesh(4, {{2, 3, 1, 0}});
  expect_boundary_equal(mesh.boundary_triangles(), {{{3, 1, 0}, 0, 0},
                                                    {{2, 0, 1}, 0, 1},
                                                    {{3, 0, 2}, 0, 2},
                                                    {{2, 1, 3}, 0, 3}});
}

TEST(TetMeshTest, TwoTetrahedraHaveSixBoundaryTrianglesWithoutTheSharedFace) {
  // The shared face {1,2,3} is face 0 of A (opposite vertex 0) and face 0 of B (opposite 4).
  //   A (0 1 2 3): face 1 (0 3 2), face 2 (1 3 0), face 3 (0 2 1).
  //   B (4 2 1 3): face 1 local (0 3 2) → (4 3 1); face 2 local (1 3 0) → (2 3 4);
  //                face 3 local (0 2 1) → (4 1 2).
  const TetMesh mesh(5, kTwoTets);
  const auto boundary = mesh.boundary_triangles();
  expect_boundary_equal(boundary, {{{0, 3, 2}, 0, 1},
                                   {{1, 3, 0}, 0, 2},
                                   {{0, 2, 1}, 0, 3},
                                   {{4, 3, 1}, 1, 1},
                                   {{2, 3, 4}, 1, 2},
                                   {{4, 1, 2}, 1, 3}});
  for (const BoundaryTriangle& tri : boundary) {
    std::set<Index> vertices(tri.vertices.begin(), tri.vertices.end());
    EXPECT_NE(vertices, (std::set<Index>{1, 2, 3})) << "the shared face is not on the boundary";
    // Each boundary triangle is kTetrahedronFaces[face] of its tetrahedron.
    const Tetrahedron& tet = mesh.tetrahedron(tri.tetrahedron);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(tri.vertices[static_cast<std::size_t>(i)],
                tet[static_cast<std::size_t>(kTetrahedronFaces[tri.face][i])]);
    }
  }
}

Vec3<double> face_normal(const std::vector<Vec3<double>>& x, const Triangle& tri) {
  const auto& a = x[static_cast<std::size_t>(tri[0])];
  const auto& b = x[static_cast<std::size_t>(tri[1])];
  const auto& c = x[static_cast<std::size_t>(tri[2])];
  return (b - a).cross(c - a);
}

TEST(TetMeshTest, FaceNormalsOfUnitTetrahedronPointOutward) {
  // Unit tetrahedron (0 1 2 3) with p0 = 0, p1 = x, p2 = y, p3 = z; positively oriented
  // (dot(x, y×z) = 1). Normals (b-a)×(c-a) by hand:
  //   face 0 (1 2 3): (-1,1,0)×(-1,0,1) = (1,1,1)   (away from p0 = origin)
  //   face 1 (0 3 2): z×y = (-1,0,0)                (away from p1 = x)
  //   face 2 (1 3 0): (-1,0,1)×(-1,0,0) = (0,-1,0)  (away from p2 = y)
  //   face 3 (0 2 1): y×x = (0,0,-1)                (away from p3 = z)
  const std::vector<Vec3<double>> x = {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0),
                                       Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1)};
  const TetMesh mesh(4, {{0, 1, 2, 3}});
  const auto boundary = mesh.boundary_triangles();
  ASSERT_EQ(boundary.size(), 4u);
  const std::array<Vec3<double>, 4> expected = {Vec3<double>(1, 1, 1), Vec3<double>(-1, 0, 0),
                                                Vec3<double>(0, -1, 0), Vec3<double>(0, 0, -1)};
  for (int f = 0; f < 4; ++f) {
    EXPECT_EQ(boundary[static_cast<std::size_t>(f)].face, f);
    EXPECT_EQ(face_normal(x, boundary[static_cast<std::size_t>(f)].vertices),
              expected[static_cast<std::size_t>(f)])
        << "face " << f;
  }
}

TEST(TetMeshTest, FaceNormalsPointAwayFromOppositeVertexOfPositiveTetrahedra) {
  const auto x = two_tets_points();
  const TetMesh mesh(5, kTwoTets);
  for (Index t = 0; t < 2; ++t) {
    const auto p = tetrahedron_points<double>(mesh.tetrahedron(t), x);
    ASSERT_GT((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])), 0) << "precondition, tet " << t;
  }
  // All faces of both tetrahedra (boundary or not): kTetrahedronFaces[f] points away from vertex f.
  for (Index t = 0; t < 2; ++t) {
    const Tetrahedron& tet = mesh.tetrahedron(t);
    for (int f = 0; f < 4; ++f) {
      Triangle tri{};
      for (int i = 0; i < 3; ++i) {
        tri[static_cast<std::size_t>(i)] = tet[static_cast<std::size_t>(kTetrahedronFaces[f][i])];
      }
      const Vec3<double> towards_opposite =
          x[static_cast<std::size_t>(tet[static_cast<std::size_t>(f)])] -
          x[static_cast<std::size_t>(tri[0])];
      EXPECT_LT(face_normal(x, tri).dot(towards_opposite), 0) << "tet " << t << " face " << f;
    }
  }
  // One by hand: B's face 2 is (2 3 4): (p3-p2)×(p4-p2) = (0,-1,1)×(1,0,1) = (-1, 1, 1);
  // its opposite vertex is p1 = (1,0,0), and (p1 - p2)·n = (1,-1,0)·(-1,1,1) = -2 < 0.
  const auto boundary = mesh.boundary_triangles();
  ASSERT_EQ(boundary.size(), 6u);
  EXPECT_EQ(boundary[4].vertices, (Triangle{2, 3, 4}));
  EXPECT_EQ(face_normal(x, boundary[4].vertices), Vec3<double>(-1, 1, 1));
}

// ---------------------------------------------------------------------------------------------
// Topology changes.

// Points 5 and 6 are added, then C = (3 5 0 4) and D = (5 6 0 3) in one call. SOFA order on top of
// the nine derived edges of kTwoTets (0 [0,1] 1 [0,2] 2 [0,3] 3 [1,2] 4 [1,3] 5 [2,3] 6 [2,4]
// 7 [1,4] 8 [3,4]):
//   C (3 5 0 4): (3,5)→9 [3,5] new; (3,0)→2; (3,4)→8; (5,0)→10 [0,5] new; (5,4)→11 [4,5] new;
//                (0,4)→12 [0,4] new.
//   D (5 6 0 3): (5,6)→13 [5,6] new; (5,0)→10; (5,3)→9; (6,0)→14 [0,6] new; (6,3)→15 [3,6] new;
//                (0,3)→2.
// Orientations (tet[k] == edge[0]):
//   C: 3==3 yes; 3 vs 0 no; 3==3 yes; 5 vs 0 no; 5 vs 4 no; 0==0 yes.
//   D: 5==5 yes; 5 vs 0 no; 5 vs 3 no; 6 vs 0 no; 6 vs 3 no; 0==0 yes.
TetMesh four_tet_mesh() {
  TetMesh mesh(5, kTwoTets);
  EXPECT_EQ(mesh.add_points(2), 5);
  const std::vector<Tetrahedron> added = {{3, 5, 0, 4}, {5, 6, 0, 3}};
  mesh.add_tetrahedra(added);
  return mesh;
}

TEST(TetMeshTest, AddTetrahedraAppendsNewEdgesInSofaOrder) {
  const TetMesh mesh = four_tet_mesh();
  EXPECT_EQ(mesh.num_points(), 7);
  EXPECT_EQ(mesh.num_tetrahedra(), 4);
  std::vector<Edge> expected = kTwoTetsDerivedEdges;
  for (Edge e : std::vector<Edge>{{3, 5}, {0, 5}, {4, 5}, {0, 4}, {5, 6}, {0, 6}, {3, 6}}) {
    expected.push_back(e);
  }
  EXPECT_EQ(to_vector(mesh.edges()), expected);
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{6, 7, 8, 3, 5, 4}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(2), (std::array<Index, 6>{9, 2, 8, 10, 11, 12}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(3), (std::array<Index, 6>{13, 10, 9, 14, 15, 2}));
  EXPECT_EQ(orientations(mesh, 2), (std::array<bool, 6>{true, false, true, false, false, true}));
  EXPECT_EQ(orientations(mesh, 3), (std::array<bool, 6>{true, false, false, false, false, true}));

  // Adjacency: 0 ∈ A, C, D; 1, 2 ∈ A, B; 3 ∈ all; 4 ∈ B, C; 5 ∈ C, D; 6 ∈ D.
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(0)), (std::vector<Index>{0, 2, 3}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(1)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(2)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(3)), (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(4)), (std::vector<Index>{1, 2}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(5)), (std::vector<Index>{2, 3}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(6)), (std::vector<Index>{3}));
  expect_consistent(mesh);
}

TEST(TetMeshTest, AddTetrahedraOneAtATimeEqualsAllAtOnce) {
  const TetMesh all_at_once = four_tet_mesh();
  TetMesh one_at_a_time(5, kTwoTets);
  one_at_a_time.add_points(1);
  one_at_a_time.add_points(1);
  const std::vector<Tetrahedron> c = {{3, 5, 0, 4}};
  const std::vector<Tetrahedron> d = {{5, 6, 0, 3}};
  one_at_a_time.add_tetrahedra(c);
  one_at_a_time.add_tetrahedra(d);
  EXPECT_EQ(to_vector(one_at_a_time.edges()), to_vector(all_at_once.edges()));
  for (Index t = 0; t < 4; ++t) {
    EXPECT_EQ(one_at_a_time.edges_of_tetrahedron(t), all_at_once.edges_of_tetrahedron(t));
    EXPECT_EQ(orientations(one_at_a_time, t), orientations(all_at_once, t));
  }
}

TEST(TetMeshTest, AddTetrahedraKeepsExplicitEdgesAndAppendsNewOnes) {
  // On the shuffled explicit list, C = (3 5 0 4) reuses (3,0) → 2 [0,3] and (3,4) → 0 [3,4]
  // and appends (3,5) → 9 [3,5], (5,0) → 10 [0,5], (5,4) → 11 [4,5], (0,4) → 12 [0,4].
  // Orientations: 3==3 yes; 3 vs 0 no; 3==3 yes; 5 vs 0 no; 5 vs 4 no; 0==0 yes.
  TetMesh mesh(5, kTwoTets, kTwoTetsShuffledEdges);
  EXPECT_EQ(mesh.add_points(1), 5);
  const std::vector<Tetrahedron> c = {{3, 5, 0, 4}};
  mesh.add_tetrahedra(c);
  std::vector<Edge> expected = kTwoTetsShuffledEdges;
  for (Edge e : std::vector<Edge>{{3, 5}, {0, 5}, {4, 5}, {0, 4}}) expected.push_back(e);
  EXPECT_EQ(to_vector(mesh.edges()), expected);
  EXPECT_EQ(mesh.edges_of_tetrahedron(2), (std::array<Index, 6>{9, 2, 0, 10, 11, 12}));
  EXPECT_EQ(orientations(mesh, 2), (std::array<bool, 6>{true, false, true, false, false, true}));
  // The existing tetrahedra are unchanged.
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{7, 5, 2, 1, 4, 6}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{8, 3, 0, 1, 6, 4}));
  expect_consistent(mesh);
}

TEST(TetMeshTest, AddTetrahedraRejectsBadTetrahedraAndLeavesTheMeshUnchanged) {
  TetMesh mesh(5, kTwoTets);
  const std::vector<Tetrahedron> bad = {{0, 1, 2, 4}, {0, 1, 2, 5}};  // 5 is out of [0, 5)
  EXPECT_TRUE(mentions(error_message([&] { mesh.add_tetrahedra(bad); }), {"tetrahedron 3", "5"}));
  EXPECT_EQ(mesh.num_tetrahedra(), 2);
  EXPECT_EQ(to_vector(mesh.edges()), kTwoTetsDerivedEdges);
  expect_consistent(mesh);
}

TEST(TetMeshTest, AddPoints) {
  TetMesh empty;
  EXPECT_EQ(empty.num_points(), 0);
  EXPECT_EQ(empty.add_points(4), 0);
  EXPECT_EQ(empty.num_points(), 4);
  for (Index v = 0; v < 4; ++v) EXPECT_TRUE(empty.tetrahedra_around_vertex(v).empty());
  const std::vector<Tetrahedron> tet = {{3, 1, 0, 2}};
  empty.add_tetrahedra(tet);
  // (3,1)→[1,3] (3,0)→[0,3] (3,2)→[2,3] (1,0)→[0,1] (1,2)→[1,2] (0,2)→[0,2].
  EXPECT_EQ(to_vector(empty.edges()),
            (std::vector<Edge>{{1, 3}, {0, 3}, {2, 3}, {0, 1}, {1, 2}, {0, 2}}));
  for (Index v = 0; v < 4; ++v) {
    EXPECT_EQ(to_vector(empty.tetrahedra_around_vertex(v)), (std::vector<Index>{0}));
  }

  TetMesh mesh(5, kTwoTets);
  EXPECT_EQ(mesh.add_points(0), 5);
  EXPECT_EQ(mesh.add_points(3), 5);
  EXPECT_EQ(mesh.num_points(), 8);
  // New points start unused; old adjacency is intact.
  for (Index v = 5; v < 8; ++v) EXPECT_TRUE(mesh.tetrahedra_around_vertex(v).empty());
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(3)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(mesh.num_edges(), 9);
  EXPECT_TRUE(mentions(error_message([&] { mesh.add_points(-2); }), {"-2"}));
  EXPECT_EQ(mesh.num_points(), 8);
}

std::vector<std::pair<Index, Index>> moves(const std::vector<IndexMove>& list) {
  std::vector<std::pair<Index, Index>> pairs;
  for (const IndexMove& m : list) pairs.emplace_back(m.from, m.to);
  return pairs;
}

TEST(TetMeshTest, RemoveOneTetrahedronBySwapWithLast) {
  // four_tet_mesh(): A (0 1 2 3), B (4 2 1 3), C (3 5 0 4), D (5 6 0 3); edges 0 [0,1] 1 [0,2]
  // 2 [0,3] 3 [1,2] 4 [1,3] 5 [2,3] 6 [2,4] 7 [1,4] 8 [3,4] 9 [3,5] 10 [0,5] 11 [4,5] 12 [0,4]
  // 13 [5,6] 14 [0,6] 15 [3,6]; C has (9 2 8 10 11 12), D (13 10 9 14 15 2).
  // Removing C (2): D, the last, takes index 2. Edges only C used: 11 and 12, taken in decreasing
  // order: 15 [3,6] moves to 12, then 14 [0,6] to 11. D's edges become (13 10 9 11 12 2).
  TetMesh mesh = four_tet_mesh();
  const std::vector<Index> remove = {2};
  const TopologyChange change = mesh.remove_tetrahedra(remove);
  EXPECT_EQ(mesh.num_points(), 7);
  EXPECT_EQ(to_vector(mesh.tetrahedra()),
            (std::vector<Tetrahedron>{{0, 1, 2, 3}, {4, 2, 1, 3}, {5, 6, 0, 3}}));
  std::vector<Edge> expected = kTwoTetsDerivedEdges;
  for (Edge e : std::vector<Edge>{{3, 5}, {0, 5}, {0, 6}, {3, 6}, {5, 6}}) expected.push_back(e);
  EXPECT_EQ(to_vector(mesh.edges()), expected);
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{6, 7, 8, 3, 5, 4}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(2), (std::array<Index, 6>{13, 10, 9, 11, 12, 2}));
  // D = (5 6 0 3): (5,6) [5,6] yes, (5,0) [0,5] no, (5,3) [3,5] no, (6,0) [0,6] no, (6,3) [3,6] no,
  // (0,3) [0,3] yes.
  EXPECT_EQ(orientations(mesh, 2), (std::array<bool, 6>{true, false, false, false, false, true}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(0)), (std::vector<Index>{0, 2}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(3)), (std::vector<Index>{0, 1, 2}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(4)), (std::vector<Index>{1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(5)), (std::vector<Index>{2}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(6)), (std::vector<Index>{2}));
  // Edges around 6: 11 [0,6], 12 [3,6], 13 [5,6]; around 4: 6 [2,4], 7 [1,4], 8 [3,4].
  EXPECT_EQ(to_vector(mesh.edges_around_vertex(6)), (std::vector<Index>{11, 12, 13}));
  EXPECT_EQ(to_vector(mesh.edges_around_vertex(4)), (std::vector<Index>{6, 7, 8}));
  EXPECT_EQ(mesh.edge_between(6, 3), 12);
  EXPECT_EQ(mesh.edge_between(0, 4), -1);
  EXPECT_EQ(mesh.tetrahedra_around_edge_count(2), 2);  // [0,3]: A and D
  EXPECT_EQ(mesh.tetrahedra_around_edge_count(3), 2);  // [1,2]: A and B

  EXPECT_EQ(change.removed_tetrahedra, (std::vector<Index>{2}));
  EXPECT_EQ(change.removed_tetrahedron_vertices, (std::vector<Tetrahedron>{{3, 5, 0, 4}}));
  EXPECT_EQ(moves(change.tetrahedron_moves), (std::vector<std::pair<Index, Index>>{{3, 2}}));
  EXPECT_EQ(change.removed_edges, (std::vector<Index>{12, 11}));
  EXPECT_EQ(change.removed_edge_vertices, (std::vector<Edge>{{0, 4}, {4, 5}}));
  EXPECT_EQ(moves(change.edge_moves), (std::vector<std::pair<Index, Index>>{{15, 12}, {14, 11}}));
  EXPECT_TRUE(change.isolated_points.empty());  // 4 keeps B, 5 keeps D
  EXPECT_EQ(change.num_added_tetrahedra, 0);
  expect_consistent(mesh);
}

TEST(TetMeshTest, RemoveTetrahedraListedInAnyOrder) {
  // Remove D (3) and A (0), listed out of order, taken as 3 then 0: D is last and goes; then C,
  // now last, takes A's index 0. Edges left unused: D's 13, 14, 15 and A's 0, 1; in decreasing
  // order 15, 14, 13 are last and go, then 12 [0,4] moves to 1 and 11 [4,5] to 0.
  TetMesh mesh = four_tet_mesh();
  const std::vector<Index> remove = {0, 3};
  const TopologyChange change = mesh.remove_tetrahedra(remove);
  EXPECT_EQ(to_vector(mesh.tetrahedra()), (std::vector<Tetrahedron>{{3, 5, 0, 4}, {4, 2, 1, 3}}));
  EXPECT_EQ(to_vector(mesh.edges()), (std::vector<Edge>{{4, 5}, {0, 4}, {0, 3}, {1, 2}, {1, 3},
                                                         {2, 3}, {2, 4}, {1, 4}, {3, 4}, {3, 5},
                                                         {0, 5}}));
  // C (9 2 8 10 11 12) → (9 2 8 10 0 1); B unchanged.
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{9, 2, 8, 10, 0, 1}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{6, 7, 8, 3, 5, 4}));
  // Orientations do not change with renumbering: C (3 5 0 4) against [3,5] [0,3] [3,4] [0,5]
  // [4,5] [0,4]: yes no yes no no yes.
  EXPECT_EQ(orientations(mesh, 0), (std::array<bool, 6>{true, false, true, false, false, true}));
  EXPECT_EQ(orientations(mesh, 1), (std::array<bool, 6>{false, false, false, false, true, true}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(0)), (std::vector<Index>{0}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(3)), (std::vector<Index>{0, 1}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(6)), (std::vector<Index>{}));
  EXPECT_EQ(moves(change.tetrahedron_moves), (std::vector<std::pair<Index, Index>>{{3, 3}, {2, 0}}));
  EXPECT_EQ(change.removed_edges, (std::vector<Index>{15, 14, 13, 1, 0}));
  EXPECT_EQ(moves(change.edge_moves),
            (std::vector<std::pair<Index, Index>>{{15, 15}, {14, 14}, {13, 13}, {12, 1}, {11, 0}}));
  EXPECT_EQ(change.isolated_points, (std::vector<Index>{6}));  // only D held 6
  // Old → new: A, D removed; B stays at 1; C 2 → 0.
  EXPECT_EQ(old_to_new(4, change.tetrahedron_moves), (std::vector<Index>{-1, 1, 0, -1}));
  const IndexRenumbering renumber(change.removed_tetrahedra, change.tetrahedron_moves);
  EXPECT_EQ(renumber(0), -1);
  EXPECT_EQ(renumber(1), 1);
  EXPECT_EQ(renumber(2), 0);
  EXPECT_EQ(renumber(3), -1);
  // Edges: 11 → 0, 12 → 1, 0, 1, 13, 14, 15 removed, the rest unchanged.
  const std::vector<Index> edge_map = old_to_new(16, change.edge_moves);
  EXPECT_EQ(edge_map, (std::vector<Index>{-1, -1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 0, 1, -1, -1, -1}));
  const IndexRenumbering renumber_edges(change.removed_edges, change.edge_moves);
  for (Index e = 0; e < 16; ++e) EXPECT_EQ(renumber_edges(e), edge_map[static_cast<std::size_t>(e)]) << e;
  expect_consistent(mesh);
}

TEST(TetMeshTest, RemoveFromExplicitEdgesKeepsOrientationAndUnusedEdges) {
  // Shuffled list plus 9 [0,4] that no tetrahedron uses: 0 [3,4] 1 [2,1] 2 [0,3] 3 [4,1] 4 [1,3]
  // 5 [2,0] 6 [3,2] 7 [0,1] 8 [2,4] 9 [0,4]. Removing B (the last) frees 8, 3, 0 (used by B only);
  // 9 was never used and stays. Decreasing: 9 [0,4] moves to 8, then (the new) 8 [0,4] to 3, then
  // 7 [0,1] to 0. A's edges (7 5 2 1 4 6) become (0 5 2 1 4 6), orientations as before.
  std::vector<Edge> edges = kTwoTetsShuffledEdges;
  edges.push_back({0, 4});
  TetMesh mesh(5, kTwoTets, edges);
  const std::vector<Index> remove = {1};
  const TopologyChange change = mesh.remove_tetrahedra(remove);
  EXPECT_EQ(to_vector(mesh.edges()),
            (std::vector<Edge>{{0, 1}, {2, 1}, {0, 3}, {0, 4}, {1, 3}, {2, 0}, {3, 2}}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{0, 5, 2, 1, 4, 6}));
  EXPECT_EQ(orientations(mesh, 0), (std::array<bool, 6>{true, false, true, false, true, false}));
  EXPECT_EQ(moves(change.edge_moves), (std::vector<std::pair<Index, Index>>{{9, 8}, {8, 3}, {7, 0}}));
  EXPECT_EQ(mesh.tetrahedra_around_edge_count(3), 0);  // [0,4], still unused
  EXPECT_EQ(change.isolated_points, (std::vector<Index>{4}));
  expect_consistent(mesh);
}

TEST(TetMeshTest, RemoveAllTetrahedra) {
  TetMesh mesh(5, kTwoTets);
  const std::vector<Index> remove = {1, 0};
  mesh.remove_tetrahedra(remove);
  EXPECT_EQ(mesh.num_tetrahedra(), 0);
  EXPECT_EQ(mesh.num_edges(), 0);
  EXPECT_EQ(mesh.num_points(), 5);  // points belong to the state and stay
  for (Index v = 0; v < 5; ++v) EXPECT_TRUE(mesh.tetrahedra_around_vertex(v).empty());
  EXPECT_TRUE(mesh.boundary_triangles().empty());
}

TEST(TetMeshTest, RemoveNothingChangesNothing) {
  TetMesh mesh(5, kTwoTets, kTwoTetsShuffledEdges);
  mesh.remove_tetrahedra(std::span<const Index>{});
  EXPECT_EQ(to_vector(mesh.tetrahedra()), kTwoTets);
  EXPECT_EQ(to_vector(mesh.edges()), kTwoTetsShuffledEdges);
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{8, 3, 0, 1, 6, 4}));
}

TEST(TetMeshTest, RemoveTetrahedraRejectsBadIndicesAndLeavesTheMeshUnchanged) {
  TetMesh mesh = four_tet_mesh();  // 4 tetrahedra: valid indices are [0, 4)
  const std::vector<Index> too_large = {1, 4};
  EXPECT_TRUE(mentions(error_message([&] { mesh.remove_tetrahedra(too_large); }), {"4"}));
  const std::vector<Index> negative = {-1};
  EXPECT_TRUE(mentions(error_message([&] { mesh.remove_tetrahedra(negative); }), {"-1"}));
  const std::vector<Index> repeated = {2, 0, 2};
  EXPECT_TRUE(
      mentions(error_message([&] { mesh.remove_tetrahedra(repeated); }), {"tetrahedron 2"}));
  EXPECT_EQ(mesh.num_tetrahedra(), 4);
  EXPECT_EQ(mesh.num_edges(), 16);
  expect_consistent(mesh);
}

TEST(TetMeshTest, UpdateTopologyInformationIsIdempotent) {
  TetMesh mesh(5, kTwoTets, kTwoTetsShuffledEdges);
  mesh.update_topology_information();
  mesh.update_topology_information();
  EXPECT_EQ(to_vector(mesh.edges()), kTwoTetsShuffledEdges);
  EXPECT_EQ(mesh.edges_of_tetrahedron(0), (std::array<Index, 6>{7, 5, 2, 1, 4, 6}));
  EXPECT_EQ(mesh.edges_of_tetrahedron(1), (std::array<Index, 6>{8, 3, 0, 1, 6, 4}));
  EXPECT_EQ(orientations(mesh, 0), (std::array<bool, 6>{true, false, true, false, true, false}));
  EXPECT_EQ(orientations(mesh, 1), (std::array<bool, 6>{false, true, false, true, false, true}));
  EXPECT_EQ(to_vector(mesh.tetrahedra_around_vertex(3)), (std::vector<Index>{0, 1}));
}

TEST(TetMeshTest, UpdateTopologyInformationAfterTheMeshIsRebuilt) {
  // Remove A from kTwoTets: B takes index 0; A's edges 0 [0,1] 1 [0,2] 2 [0,3] go in decreasing
  // order, the last ones moving in: 8 [3,4] → 2, 7 [1,4] → 1, 6 [2,4] → 0, so B's edges
  // (6 7 8 3 5 4) become (0 1 2 3 5 4). Adding A = (0 1 2 3) back appends (0,1) → 6, (0,2) → 7,
  // (0,3) → 8 and reuses (1,2) → 3, (1,3) → 4, (2,3) → 5; A is tetrahedron 1.
  TetMesh mesh(5, kTwoTets);
  const std::vector<Index> remove = {0};
  mesh.remove_tetrahedra(remove);
  const std::vector<Tetrahedron> a = {{0, 1, 2, 3}};
  const TopologyChange change = mesh.add_tetrahedra(a);
  EXPECT_EQ(change.first_added_tetrahedron, 1);
  EXPECT_EQ(change.num_added_tetrahedra, 1);
  EXPECT_EQ(change.first_added_edge, 6);
  EXPECT_EQ(change.num_added_edges, 3);
  EXPECT_EQ(change.reconnected_points, (std::vector<Index>{0}));  // 0 had no tetrahedron left
  const auto check = [](const TetMesh& m) {
    EXPECT_EQ(to_vector(m.tetrahedra()), (std::vector<Tetrahedron>{{4, 2, 1, 3}, {0, 1, 2, 3}}));
    EXPECT_EQ(to_vector(m.edges()), (std::vector<Edge>{{2, 4}, {1, 4}, {3, 4}, {1, 2}, {1, 3},
                                                       {2, 3}, {0, 1}, {0, 2}, {0, 3}}));
    EXPECT_EQ(m.edges_of_tetrahedron(0), (std::array<Index, 6>{0, 1, 2, 3, 5, 4}));
    EXPECT_EQ(m.edges_of_tetrahedron(1), (std::array<Index, 6>{6, 7, 8, 3, 4, 5}));
    EXPECT_EQ(orientations(m, 0), (std::array<bool, 6>{false, false, false, false, true, true}));
    EXPECT_EQ(orientations(m, 1), (std::array<bool, 6>{true, true, true, true, true, true}));
    EXPECT_EQ(to_vector(m.tetrahedra_around_vertex(0)), (std::vector<Index>{1}));
    EXPECT_EQ(to_vector(m.tetrahedra_around_vertex(4)), (std::vector<Index>{0}));
    EXPECT_EQ(to_vector(m.tetrahedra_around_vertex(2)), (std::vector<Index>{0, 1}));
  };
  check(mesh);
  expect_consistent(mesh);
  mesh.update_topology_information();
  check(mesh);
}

// ---------------------------------------------------------------------------------------------
// Construction errors: the message names the element and the offending value.

TEST(TetMeshTest, RejectsVertexIndexOutOfRange) {
  const std::string message =
      error_message([] { TetMesh(5, {{0, 1, 2, 3}, {0, 1, 2, 17}}); });
  EXPECT_TRUE(mentions(message, {"tetrahedron 1", "17", "out of range"}));
  // num_points itself is out of range.
  EXPECT_TRUE(mentions(error_message([] { TetMesh(4, {{4, 1, 2, 3}}); }), {"tetrahedron 0", "4"}));
  // The explicit-edge constructor checks tetrahedra too.
  EXPECT_TRUE(mentions(error_message([] { TetMesh(4, {{0, 1, 2, 9}}, {}); }),
                       {"tetrahedron 0", "9"}));
}

TEST(TetMeshTest, RejectsNegativeVertexIndex) {
  const std::string message = error_message([] { TetMesh(5, {{0, 1, 2, 3}, {4, -3, 1, 2}}); });
  EXPECT_TRUE(mentions(message, {"tetrahedron 1", "-3"}));
}

TEST(TetMeshTest, RejectsNegativePointCount) {
  EXPECT_TRUE(mentions(error_message([] { TetMesh(-1, {}); }), {"-1"}));
}

TEST(TetMeshTest, RejectsRepeatedVertex) {
  const std::string message =
      error_message([] { TetMesh(5, {{0, 1, 2, 3}, {1, 2, 3, 4}, {3, 4, 0, 4}}); });
  EXPECT_TRUE(mentions(message, {"tetrahedron 2", "vertex 4", "repeat"}));
}

TEST(TetMeshTest, RejectsExplicitEdgeListMissingAnEdgeOfATetrahedron) {
  // Drop 0 [3,4]: B = (4 2 1 3) needs it as local edge (0,3) = (4,3).
  std::vector<Edge> edges(kTwoTetsShuffledEdges.begin() + 1, kTwoTetsShuffledEdges.end());
  const std::string message = error_message([&] { TetMesh(5, kTwoTets, edges); });
  EXPECT_TRUE(mentions(message, {"tetrahedron 1", "(4, 3)", "missing"}));
}

TEST(TetMeshTest, RejectsRepeatedEdge) {
  std::vector<Edge> edges = kTwoTetsDerivedEdges;
  edges.push_back({1, 3});  // edge 9 repeats edge 4
  EXPECT_TRUE(mentions(error_message([&] { TetMesh(5, kTwoTets, edges); }),
                       {"edge 9", "(1, 3)", "edge 4"}));
  edges.back() = {3, 1};  // a reversed duplicate is the same edge
  EXPECT_TRUE(mentions(error_message([&] { TetMesh(5, kTwoTets, edges); }),
                       {"edge 9", "(3, 1)", "edge 4"}));
}

TEST(TetMeshTest, RejectsDegenerateEdge) {
  std::vector<Edge> edges = kTwoTetsDerivedEdges;
  edges.insert(edges.begin() + 2, Edge{3, 3});
  EXPECT_TRUE(mentions(error_message([&] { TetMesh(5, kTwoTets, edges); }),
                       {"edge 2", "(3, 3)"}));
}

TEST(TetMeshTest, RejectsEdgeOutOfRange) {
  std::vector<Edge> edges = kTwoTetsDerivedEdges;
  edges[4] = {1, 12};
  EXPECT_TRUE(mentions(error_message([&] { TetMesh(5, kTwoTets, edges); }),
                       {"edge 4", "12", "out of range"}));
  edges[4] = {-2, 3};
  EXPECT_TRUE(mentions(error_message([&] { TetMesh(5, kTwoTets, edges); }), {"edge 4", "-2"}));
  edges[4] = {5, 3};  // 5 == num_points
  EXPECT_TRUE(mentions(error_message([&] { TetMesh(5, kTwoTets, edges); }), {"edge 4", "5"}));
}

// ---------------------------------------------------------------------------------------------
// signed_volume.

TEST(SignedVolumeTest, SofaSignOnUnitTetrahedron) {
  // SOFA: V = -dot(p1-p0, (p2-p0)×(p3-p0)) / 6. Order 0 1 2 3 of the unit tetrahedron:
  // dot(x, y×z) = 1 → V = -1/6. Order (2 3 1 0) (SPEC's example): q0 = y, q1 = z, q2 = x, q3 = 0;
  // q1-q0 = (0,-1,1), q2-q0 = (1,-1,0), q3-q0 = (0,-1,0); (1,-1,0)×(0,-1,0) = (0,0,-1);
  // dot = -1 → V = +1/6.
  const std::vector<Vec3<double>> x = {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0),
                                       Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1)};
  EXPECT_DOUBLE_EQ(signed_volume(tetrahedron_points<double>({0, 1, 2, 3}, x)), -1.0 / 6.0);
  EXPECT_DOUBLE_EQ(signed_volume(tetrahedron_points<double>({2, 3, 1, 0}, x)), 1.0 / 6.0);

  const std::vector<Vec3<float>> xf = {Vec3<float>(0, 0, 0), Vec3<float>(1, 0, 0),
                                       Vec3<float>(0, 1, 0), Vec3<float>(0, 0, 1)};
  EXPECT_FLOAT_EQ(signed_volume(tetrahedron_points<float>({0, 1, 2, 3}, xf)), -1.0f / 6.0f);
  EXPECT_FLOAT_EQ(signed_volume(tetrahedron_points<float>({2, 3, 1, 0}, xf)), 1.0f / 6.0f);
}

TEST(SignedVolumeTest, ExampleAndProperties) {
  // B of kTwoTets: dot = 2 (see the table above kTwoTets) → V = -2/6 = -1/3.
  const auto x = two_tets_points();
  EXPECT_DOUBLE_EQ(signed_volume(tetrahedron_points<double>({4, 2, 1, 3}, x)), -1.0 / 3.0);

  const std::array<Vec3<double>, 4> p = {Vec3<double>(0.3, -0.2, 0.5), Vec3<double>(1.4, 0.1, 0.4),
                                         Vec3<double>(0.2, 1.1, 0.7), Vec3<double>(0.5, 0.0, 1.6)};
  const double v = signed_volume(p);
  ASSERT_GT(std::abs(v), 0.05);
  // Swapping two vertices flips the sign; an even permutation keeps it.
  EXPECT_DOUBLE_EQ(signed_volume<double>({p[1], p[0], p[2], p[3]}), -v);
  EXPECT_DOUBLE_EQ(signed_volume<double>({p[0], p[1], p[3], p[2]}), -v);
  EXPECT_NEAR(signed_volume<double>({p[1], p[2], p[0], p[3]}), v, 1e-15);
  // Translation invariance and cubic scaling.
  const Vec3<double> shift(10.0, -7.0, 3.0);
  EXPECT_NEAR(signed_volume<double>({p[0] + shift, p[1] + shift, p[2] + shift, p[3] + shift}), v,
              1e-13);
  EXPECT_NEAR(signed_volume<double>({2 * p[0], 2 * p[1], 2 * p[2], 2 * p[3]}), 8 * v, 1e-14);
}

// ---------------------------------------------------------------------------------------------
// check_rest_volumes.

template <class Real>
class CheckRestVolumesTest : public testing::Test {};
using RealTypes = testing::Types<float, double>;
TYPED_TEST_SUITE(CheckRestVolumesTest, RealTypes);

template <class Real>
std::vector<Vec3<Real>> cast_points(const std::vector<Vec3<double>>& x) {
  std::vector<Vec3<Real>> out;
  for (const auto& p : x) out.push_back(p.cast<Real>());
  return out;
}

TYPED_TEST(CheckRestVolumesTest, GoodMeshPasses) {
  using Real = TypeParam;
  const TetMesh mesh(5, kTwoTets);
  const auto x = cast_points<Real>(two_tets_points());
  EXPECT_NO_THROW(check_rest_volumes<Real>(mesh, x));
  // The threshold is relative (1000 eps L^3): the same mesh in millimetres or kilometres passes.
  for (double scale : {1e-3, 1e3}) {
    std::vector<Vec3<double>> scaled = two_tets_points();
    for (auto& p : scaled) p *= scale;
    EXPECT_NO_THROW(check_rest_volumes<Real>(mesh, cast_points<Real>(scaled))) << scale;
  }
  // Both orientations are accepted (SOFA's (2 3 1 0) has V > 0, (0 1 2 3) has V < 0).
  const TetMesh both(4, {{0, 1, 2, 3}, {2, 3, 1, 0}});
  EXPECT_NO_THROW(check_rest_volumes<Real>(both, cast_points<Real>({Vec3<double>(0, 0, 0),
                                                                    Vec3<double>(1, 0, 0),
                                                                    Vec3<double>(0, 1, 0),
                                                                    Vec3<double>(0, 0, 1)})));
}

TYPED_TEST(CheckRestVolumesTest, FlatTetrahedronIsAnError) {
  using Real = TypeParam;
  // Tetrahedron 1 = (0 1 2 4) with p4 = (1,1,0): all four points on z = 0, volume 0.
  const TetMesh mesh(5, {{0, 1, 2, 3}, {0, 1, 2, 4}});
  const auto x = cast_points<Real>({Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0),
                                    Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1),
                                    Vec3<double>(1, 1, 0)});
  EXPECT_TRUE(mentions(error_message([&] { check_rest_volumes<Real>(mesh, x); }),
                       {"tetrahedron 1", "volume"}));
}

// Sliver on (0,0,0), (1,0,0), (0,1,0), (1,1,h): y×(1,1,h) = (h,0,-1), dot with x = h, so
// |V| = h/6; the longest edge is sqrt(2 + h^2) ≈ 1.414, L^3 ≈ 2.83.
//   double: 1000 eps L^3 ≈ 1000 · 2.2e-16 · 2.83 ≈ 6.3e-13;  float: ≈ 1000 · 1.19e-7 · 2.83 ≈ 3.4e-4.
std::vector<Vec3<double>> sliver_points(double h) {
  return {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0),
          Vec3<double>(1, 1, h)};
}

TYPED_TEST(CheckRestVolumesTest, NearDegenerateSliverIsAnError) {
  using Real = TypeParam;
  // h = 6e-14 → |V| = 1e-14, below both thresholds.
  const TetMesh mesh(4, {{0, 1, 2, 3}});
  std::vector<Vec3<double>> x = sliver_points(6e-14);
  EXPECT_TRUE(mentions(error_message([&] { check_rest_volumes<Real>(mesh, cast_points<Real>(x)); }),
                       {"tetrahedron 0", "volume"}));

  // Index reported correctly: sliver as tetrahedron 1 after a good tetrahedron.
  const TetMesh second(5, {{0, 1, 2, 4}, {0, 1, 2, 3}});
  x.push_back(Vec3<double>(0, 0, 1));  // p4: (0 1 2 4) is the unit tetrahedron
  EXPECT_TRUE(
      mentions(error_message([&] { check_rest_volumes<Real>(second, cast_points<Real>(x)); }),
               {"tetrahedron 1", "volume"}));
}

TEST(RestVolumeThresholdTest, ThinButValidTetrahedraPass) {
  // double: h = 1e-6 → |V| ≈ 1.7e-7 > 6.3e-13.  float: h = 1e-2 → |V| ≈ 1.7e-3 > 3.4e-4.
  const TetMesh mesh(4, {{0, 1, 2, 3}});
  EXPECT_NO_THROW(check_rest_volumes<double>(mesh, sliver_points(1e-6)));
  EXPECT_NO_THROW(check_rest_volumes<float>(mesh, cast_points<float>(sliver_points(1e-2))));
  // float: h = 1e-3 → |V| ≈ 1.7e-4 < 3.4e-4, too thin for single precision.
  EXPECT_TRUE(mentions(error_message([&] {
                         check_rest_volumes<float>(mesh, cast_points<float>(sliver_points(1e-3)));
                       }),
                       {"tetrahedron 0", "volume"}));
}

TYPED_TEST(CheckRestVolumesTest, WrongNumberOfPointsIsAnError) {
  using Real = TypeParam;
  const TetMesh mesh(5, kTwoTets);
  auto x = cast_points<Real>(two_tets_points());
  x.pop_back();
  EXPECT_TRUE(mentions(error_message([&] { check_rest_volumes<Real>(mesh, x); }), {"4", "5"}));
  x.push_back(Vec3<Real>::Zero());
  x.push_back(Vec3<Real>::Zero());
  EXPECT_TRUE(mentions(error_message([&] { check_rest_volumes<Real>(mesh, x); }), {"6", "5"}));
}

TYPED_TEST(CheckRestVolumesTest, NonFiniteCoordinateIsAnError) {
  using Real = TypeParam;
  const TetMesh mesh(5, kTwoTets);
  auto x = cast_points<Real>(two_tets_points());
  x[3][1] = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_TRUE(mentions(error_message([&] { check_rest_volumes<Real>(mesh, x); }),
                       {"point 3", "finite"}));
  x[3][1] = 0;
  x[4][2] = std::numeric_limits<Real>::infinity();
  EXPECT_TRUE(mentions(error_message([&] { check_rest_volumes<Real>(mesh, x); }),
                       {"point 4", "finite"}));
  // A NaN in a point no tetrahedron uses is still an error: the state would carry it.
  const TetMesh with_free_point(6, kTwoTets);
  auto y = cast_points<Real>(two_tets_points());
  y.push_back(Vec3<Real>(0, std::numeric_limits<Real>::quiet_NaN(), 0));
  EXPECT_TRUE(mentions(error_message([&] { check_rest_volumes<Real>(with_free_point, y); }),
                       {"point 5"}));
}

}  // namespace
}  // namespace fastcorot
