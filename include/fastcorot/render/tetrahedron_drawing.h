// How SOFA's FastTetrahedralCorotationalForceField draws its elements when `drawing` is on: each
// tetrahedron shrunk toward its centroid to 2/3 of its size, so that neighbours stay apart, and its
// four faces filled with drawColor1..4. SOFA's draw() (the same in modules/SofaMiscFem of 2018 and
// in today's Sofa.Component.SolidMechanics.FEM.Elastic) computes each drawn corner as
// 0.666667 · (x_v + Σx/8), i.e. centroid + 2/3 (x_v − centroid) up to its rounded constant, and
// fills the triangles (a b c), (b c d), (c d a), (d a b) with drawColor1, 2, 3, 4: drawColor(k+1)
// goes to the face opposite local vertex (k + 3) mod 4. So the face opposite vertex 3 is
// drawColor1, opposite 0 drawColor2, opposite 1 drawColor3, opposite 2 drawColor4
// (docs/rendering.md). We use the exact 2/3.
#pragma once

#include "fastcorot/core/types.h"

#include <array>

namespace fastcorot {

// The factor by which a drawn tetrahedron is scaled about its centroid.
inline constexpr double kDrawnTetrahedronScale = 2.0 / 3.0;

// SOFA's drawn triangles in SOFA's order: triangle k uses local vertices kDrawnFaces[k] and
// drawColor(k+1). Triangle k is the face opposite local vertex kOppositeVertexOfDrawnFace[k].
inline constexpr std::array<std::array<int, 3>, 4> kDrawnFaces = {
    {{0, 1, 2}, {1, 2, 3}, {2, 3, 0}, {3, 0, 1}}};
inline constexpr std::array<int, 4> kOppositeVertexOfDrawnFace = {3, 0, 1, 2};

// The index (0..3, i.e. drawColor1..4) of the colour of the face opposite local vertex i.
constexpr int drawn_color_of_face(int opposite_vertex) {
  return (opposite_vertex + 1) % 4;
}

// A drawn triangle: its corners, and the unit normal pointing away from the tetrahedron's
// centroid (zero for a degenerate triangle).
template <class Real>
struct DrawnTriangle {
  std::array<Vec3<Real>, 3> corners;
  Vec3<Real> normal;
};

// The four corners of tetrahedron x0..x3 as drawn: centroid + 2/3 (x_j − centroid).
template <class Real>
std::array<Vec3<Real>, 4> shrunk_tetrahedron(const std::array<Vec3<Real>, 4>& x);

// The four drawn triangles of tetrahedron x0..x3, triangle k in drawColor(k+1) (kDrawnFaces).
template <class Real>
std::array<DrawnTriangle<Real>, 4> drawn_tetrahedron_faces(const std::array<Vec3<Real>, 4>& x);

}  // namespace fastcorot
