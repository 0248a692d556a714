// The edge and quad arrays SOFA's HexahedronSetTopologyContainer creates (createEdgeSetArray,
// createQuadSetArray, commit 2a278d891f), worked out by hand for one cube and for two cubes of a
// 3 x 2 x 2 grid (points i + 3 j + 6 k) sharing a face.
#include "fastcorot/topology/hexahedron_faces.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using Quad = std::array<Index, 4>;
using Hexa = std::array<Index, 8>;

TEST(HexahedronFaces, OneCube) {
  const std::vector<Hexa> cube = {{0, 1, 2, 3, 4, 5, 6, 7}};
  const std::vector<Edge> edges = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                   {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
  EXPECT_EQ(hexahedron_set_edges(cube), edges);
  // Faces (0 3 2 1) (4 5 6 7) (0 1 5 4) (1 2 6 5) (2 3 7 6) (3 0 4 7), the last rotated to start at 0.
  const std::vector<Quad> quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {0, 4, 7, 3}};
  EXPECT_EQ(hexahedron_set_quads(cube), quads);
}

TEST(HexahedronFaces, TwoCubesShareTheirFaceAndEdgesOnce) {
  const std::vector<Hexa> cubes = {{0, 1, 4, 3, 6, 7, 10, 9}, {1, 2, 5, 4, 7, 8, 11, 10}};
  const auto quads = hexahedron_set_quads(cubes);
  ASSERT_EQ(quads.size(), 11u);
  EXPECT_EQ(quads[3], (Quad{1, 4, 10, 7}));  // the first cube's face 3, which the second's face 5 repeats reversed
  EXPECT_EQ(quads[6], (Quad{1, 4, 5, 2}));
  EXPECT_EQ(quads[10], (Quad{4, 10, 11, 5}));  // face (5 4 10 11) rotated to start at 4
  const auto edges = hexahedron_set_edges(cubes);
  ASSERT_EQ(edges.size(), 20u);  // 8 along x, 6 along y, 6 along z
  const std::vector<Edge> added = {{1, 2}, {2, 5}, {2, 8}, {4, 5}, {5, 11}, {7, 8}, {8, 11}, {10, 11}};
  EXPECT_EQ(std::vector<Edge>(edges.begin() + 12, edges.end()), added);
}

}  // namespace
}  // namespace fastcorot
