// The edges and quads of a hexahedral mesh as SOFA's HexahedronSetTopologyContainer creates them
// (createEdgeSetArray, createQuadSetArray), for containers given hexahedra alone. Hexahedron
// corners in SOFA's order: bottom face 0 1 2 3 counter-clockwise seen from above, top face 4 5 6 7
// above them (grid_cell_corners in regular_grid.h).
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <span>
#include <vector>

namespace fastcorot {

// SOFA's edgesInHexahedronArray: the twelve edges of a hexahedron by local corners.
inline constexpr std::array<std::array<int, 2>, 12> kHexahedronEdges = {
    {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3}, {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}}};

// Hexahedra in order, local edges in kHexahedronEdges order, each new edge stored (min, max).
std::vector<Edge> hexahedron_set_edges(std::span<const std::array<Index, 8>> hexahedra);

// Hexahedra in order, faces (0 3 2 1) (4 5 6 7) (0 1 5 4) (1 2 6 5) (2 3 7 6) (3 0 4 7), each rotated
// to start at its smallest corner, kept the first time it appears in either orientation.
std::vector<std::array<Index, 4>> hexahedron_set_quads(std::span<const std::array<Index, 8>> hexahedra);

// The quads of `quads` that are a face of exactly one of `hexahedra` (SOFA's Hexa2QuadTopologicalMapping:
// the surface of a hexahedral mesh), in their order and orientation, or reversed (3 2 1 0) with `flip`.
std::vector<std::array<Index, 4>> boundary_quads(std::span<const std::array<Index, 4>> quads,
                                                 std::span<const std::array<Index, 8>> hexahedra, bool flip);

}  // namespace fastcorot
