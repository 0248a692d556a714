// Internal to MeshTetraStuffing (mesh_tetra_stuffing.h): the body-centred cubic lattice's
// numbering and edges, and the builder of its tetrahedra cut at the surface, as SOFA's
// MeshTetraStuffing (master 2a278d891f) computes them.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <map>
#include <utility>
#include <vector>

namespace fastcorot::stuffing_detail {

using Point = Vec3<double>;

// The lattice's edges from a point: 0..5 along its own grid's axes (-x, +x, -y, +y, -z, +z), 6..13
// to the 8 nearest points of the other grid; edge e ^ 1 is the opposite of edge e.
constexpr int kEdgeShell = 14;

// SOFA's Vec products, summed left to right (Eigen's dot may sum in another order).
inline double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double volume6(const Point& p1, const Point& p2, const Point& p3, const Point& p4) {
  return dot(p2 - p1, cross(p3 - p1, p4 - p1));
}

// The two grids: the first of gsize points from g0, the second of hsize = gsize + 1 points from
// h0 = g0 - size / 2, numbered x fastest, the second after the first (SOFA's getEdgePoint2).
struct Lattice {
  std::array<int, 3> g{}, h{};
  int second = 0;  // SOFA's ph0

  // The point at the other end of edge e from p, or -1 outside the lattice.
  int neighbour(int p, int e) const {
    const bool first_grid = p < second;
    const std::array<int, 3>& size = first_grid ? g : h;
    if (!first_grid) p -= second;
    int c[3];
    c[0] = p % size[0];
    p /= size[0];
    c[1] = p % size[1];
    c[2] = p / size[1];
    if (e < 6) {
      const int axis = e >> 1;
      c[axis] += (e & 1) ? 1 : -1;
      if (c[axis] < 0 || c[axis] >= size[axis]) return -1;
      return (first_grid ? 0 : second) + c[0] + size[0] * (c[1] + size[1] * c[2]);
    }
    const int k = e - 6;
    const int bits[3] = {k & 1, ((k >> 1) ^ k) & 1, ((k >> 2) ^ k) & 1};
    if (first_grid) return second + (c[0] + bits[0]) + h[0] * ((c[1] + bits[1]) + h[1] * (c[2] + bits[2]));
    for (int i = 0; i < 3; ++i) {
      c[i] += bits[i] - 1;
      if (c[i] < 0 || c[i] >= g[static_cast<std::size_t>(i)]) return -1;
    }
    return c[0] + g[0] * (c[1] + g[1] * c[2]);
  }
};

// Squared edge length in (size / 2)^2: long edges 4, short edges 3 (SOFA's getEdgeSize2).
inline double edge_size2(int e) { return e < 6 ? 4 : 3; }

// The lattice's tetrahedra, each kept whole, cut at the surface crossings, or dropped, as SOFA's
// addTetra and the functions it calls make them.
class StuffingBuilder {
 public:
  // `inside`: each lattice point's vote (> 0 inside, < 0 outside, 0 on the surface); `cuts`: the
  // crossing point made on the edge (outside point, inside point).
  StuffingBuilder(const Lattice& lattice, std::vector<Point>& points, const std::vector<int>& inside,
                  const std::map<std::pair<int, int>, int>& cuts, bool split)
      : lattice_(lattice), points_(points), inside_(inside), cuts_(cuts), split_(split) {}

  std::vector<Tetrahedron> tetrahedra;

  // A lattice tetrahedron p1 p2 p3 p4 (reordered to positive volume), kept whole when none of its
  // points is outside (or without splitting), cut at the surface crossings otherwise, dropped when
  // none is inside.
  void add(int p1, int p2, int p3, int p4);

 private:
  static std::size_t at(int p) { return static_cast<std::size_t>(p); }
  void add_final(int p1, int p2, int p3, int p4, bool flip);
  // The crossing point on the edge between two lattice points (SOFA: the edge's first point
  // itself when there is none, with an error message).
  int cut(int from, int to) const;
  // Whether the quad a b c d (a b the long edge, e the outside point) is cut along b d rather
  // than a c (SOFA's flipDiag; its argument d only draws).
  bool flip_diagonal(int a, int b, int c, int e) const;
  // Whether p1 p2 p3 p4 and q1 q2 q3 q4 (the same four points) are ordered with opposite
  // orientations (SOFA's needFlip, including its rules for the second vertex).
  static bool need_flip(int p1, int p2, int p3, int p4, int q1, int q2, int q3, int q4);

  const Lattice& lattice_;
  std::vector<Point>& points_;
  const std::vector<int>& inside_;
  const std::map<std::pair<int, int>, int>& cuts_;
  bool split_;
};
}  // namespace fastcorot::stuffing_detail
