// SOFA's MeshTetraStuffing (master 2a278d891f), step by step as its doUpdate computes it; the
// comments name SOFA's variables where the correspondence helps a reader compare.
#include "fastcorot/topology/mesh_tetra_stuffing.h"

#include "fastcorot/core/error.h"
#include "mesh_tetra_stuffing_lattice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

namespace fastcorot {
namespace {

using namespace stuffing_detail;

// sofa::geometry::Triangle::rayIntersection (Moller-Trumbore): barycentric coordinates accepted
// within one machine epsilon outside [0, 1], hits at t >= epsilon only; t in units of `direction`.
bool ray_hit(const Point& n0, const Point& n1, const Point& n2, const Point& origin, const Point& direction,
             double& t) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const Point e0 = n1 - n0, e1 = n2 - n0;
  const Point pvec = cross(direction, e1);
  const double det = dot(e0, pvec);
  if (std::fabs(det) <= eps) return false;
  const double inv_det = 1.0 / det;
  const Point tvec = origin - n0;
  const double u = dot(tvec, pvec) * inv_det;
  if (u < 0.0 - eps || u > 1.0 + eps) return false;
  const Point qvec = cross(tvec, e0);
  const double v = dot(direction, qvec) * inv_det;
  if (v < 0.0 - eps || (u + v) > 1.0 + eps) return false;
  t = dot(e1, qvec) * inv_det;
  return !(t < eps || t != t || v != v || u != u);
}

struct Hit {
  double t;
  int triangle;
  int side;  // -1 where the ray enters (against the triangle's normal), +1 where it leaves
};

// All surface triangles a ray crosses. SOFA traces through its TriangleOctree, which tests the
// triangles of the cells the ray visits with the same intersection and keeps each triangle once:
// the hits are the same as testing every triangle it holds (ties in t aside, ordered here by
// triangle). Triangles are first rejected by their bounding box across the ray's lattice
// direction (a margin far above rounding keeps every true hit).
class SurfaceTracer {
 public:
  static constexpr double kOctreeHalfSize = 800;  // SOFA's TriangleOctreeRoot::CUBE_SIZE

  SurfaceTracer(const std::vector<Point>& points, const std::vector<Triangle>& triangles, double margin)
      : points_(points), triangles_(triangles), margin_(margin) {
    normals_.reserve(triangles.size());
    for (const auto& t : triangles) {
      const Point& a = points[static_cast<std::size_t>(t[0])];
      normals_.push_back(cross(points[static_cast<std::size_t>(t[1])] - a, points[static_cast<std::size_t>(t[2])] - a));
      // SOFA's octree spans [-800, 800]^3 and leaves out the triangles that reach beyond it.
      bool in_octree = true;
      for (Index v : t) in_octree = in_octree && points[static_cast<std::size_t>(v)].cwiseAbs().maxCoeff() <= kOctreeHalfSize;
      in_octree_.push_back(in_octree);
    }
  }

  // Hits sorted by t (ties by triangle, SOFA's order among equal t being its octree's).
  std::vector<Hit> trace(const Point& origin, const Point& direction, int line_direction) {
    const Frame& frame = frame_of(line_direction, direction);
    const double ou = dot(origin, frame.u), ow = dot(origin, frame.w);
    std::vector<Hit> hits;
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const auto& box = frame.boxes[i];
      if (!in_octree_[i] || ou < box[0] || ou > box[1] || ow < box[2] || ow > box[3]) continue;
      const auto& tri = triangles_[i];
      double t = 0;
      if (!ray_hit(points_[static_cast<std::size_t>(tri[0])], points_[static_cast<std::size_t>(tri[1])],
                   points_[static_cast<std::size_t>(tri[2])], origin, direction, t)) {
        continue;
      }
      hits.push_back({t, static_cast<int>(i), dot(normals_[i], direction) < 0 ? -1 : 1});
    }
    std::sort(hits.begin(), hits.end(),
              [](const Hit& a, const Hit& b) { return a.t < b.t || (a.t == b.t && a.triangle < b.triangle); });
    return hits;
  }

 private:
  struct Frame {
    bool ready = false;
    Point u, w;
    std::vector<std::array<double, 4>> boxes;  // umin umax wmin wmax, widened by the margin
  };

  const Frame& frame_of(int line_direction, const Point& direction) {
    Frame& frame = frames_[static_cast<std::size_t>(line_direction)];
    if (frame.ready) return frame;
    const Point d = direction.normalized();
    Point axis = Point::Zero();
    int smallest = 0;
    for (int k = 1; k < 3; ++k) {
      if (std::fabs(d[k]) < std::fabs(d[smallest])) smallest = k;
    }
    axis[smallest] = 1;
    frame.u = d.cross(axis).normalized();
    frame.w = d.cross(frame.u);
    for (const auto& tri : triangles_) {
      std::array<double, 4> box = {std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                                   std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()};
      for (Index v : tri) {
        const Point& p = points_[static_cast<std::size_t>(v)];
        const double pu = dot(p, frame.u), pw = dot(p, frame.w);
        box = {std::min(box[0], pu), std::max(box[1], pu), std::min(box[2], pw), std::max(box[3], pw)};
      }
      frame.boxes.push_back({box[0] - margin_, box[1] + margin_, box[2] - margin_, box[3] + margin_});
    }
    frame.ready = true;
    return frame;
  }

  const std::vector<Point>& points_;
  const std::vector<Triangle>& triangles_;
  double margin_;
  std::vector<Point> normals_;  // SOFA's inTN: (b - a) x (c - a), not normalised
  std::vector<bool> in_octree_;
  std::array<Frame, 7> frames_;
};

}  // namespace

TetraStuffing stuff_tetrahedra(const std::vector<Point>& surface_points, const std::vector<Triangle>& surface_triangles,
                               const std::vector<std::array<Index, 4>>& quads, const TetraStuffingOptions& options) {
  if (surface_points.empty() || (surface_triangles.empty() && quads.empty())) {
    throw make_error("MeshTetraStuffing: empty input surface (inputPoints with inputTriangles or inputQuads)");
  }
  std::vector<Triangle> triangles = surface_triangles;
  for (const auto& q : quads) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  }
  const auto point_count = static_cast<Index>(surface_points.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (Index v : triangles[t]) {
      if (v < 0 || v >= point_count) {
        throw make_error("MeshTetraStuffing: ", t < surface_triangles.size() ? "triangle " : "quad triangle ", t,
                         " has point ", v, " of ", point_count, " input points");
      }
    }
  }
  for (std::size_t i = 0; i < surface_points.size(); ++i) {
    if (!surface_points[i].allFinite()) throw make_error("MeshTetraStuffing: input point ", i, " is not finite");
  }

  // The box: as given, else the surface's grown by 1% each side; the cell size.
  TetraStuffing out;
  Point low = surface_points[0], high = surface_points[0];
  for (std::size_t p = 1; p < surface_points.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      if (surface_points[p][c] < low[c]) {
        low[c] = surface_points[p][c];
      } else if (surface_points[p][c] > high[c]) {
        high[c] = surface_points[p][c];
      }
    }
  }
  auto& bb = out.bbox;
  bb = options.bbox;
  if (!bb[0].allFinite() || !bb[1].allFinite()) throw make_error("MeshTetraStuffing: vbbox is not finite");
  if (bb[0][0] >= bb[1][0]) {
    bb[0] = low - (high - low) * 0.01;
    bb[1] = high + (high - low) * 0.01;
  }
  double cell = options.size;
  if (cell < 0) {
    const Point extent = bb[1] - bb[0];
    cell = extent[0];
    if (extent[1] > cell) cell = extent[1];
    if (extent[2] > cell) cell = extent[2];
    cell = cell / -options.size;
  }
  if (!(cell > 0) || !std::isfinite(cell)) {
    throw make_error("MeshTetraStuffing: size ", options.size, " gives cell size ", cell, " (needs a finite size != 0 and a surface with some extent)");
  }
  out.cell_size = cell;

  // The lattice: the first grid at least 2 cells beyond the box around its centre, the second at
  // the first's cell centres.
  const Point centre = (bb[0] + bb[1]) / 2;
  Lattice lattice;
  Point g0, h0;
  for (int c = 0; c < 3; ++c) {
    const double below = (centre[c] - bb[0][c]) / cell, above = (bb[1][c] - centre[c]) / cell;
    if (!(std::fabs(below) < 1e6 && std::fabs(above) < 1e6)) {
      throw make_error("MeshTetraStuffing: size ", options.size, ": more than a million cells across the box");
    }
    const int c0 = -(static_cast<int>(below) + 2);
    const int c1 = static_cast<int>(above) + 2;
    const auto axis = static_cast<std::size_t>(c);
    lattice.g[axis] = c1 - c0 + 1;
    lattice.h[axis] = lattice.g[axis] + 1;
    g0[c] = centre[c] + c0 * cell;
    h0[c] = g0[c] - cell / 2;
  }
  const double lattice_points = 2.0 * lattice.h[0] * lattice.h[1] * lattice.h[2];
  if (lattice_points > 5e7) {
    throw make_error("MeshTetraStuffing: size ", options.size, " needs ", lattice_points, " lattice points (at most 5e7)");
  }
  lattice.second = lattice.g[0] * lattice.g[1] * lattice.g[2];
  const int nbp = lattice.second + lattice.h[0] * lattice.h[1] * lattice.h[2];
  std::vector<Point>& points = out.points;
  points.resize(static_cast<std::size_t>(nbp));
  {
    std::size_t p = 0;
    for (int z = 0; z < lattice.g[2]; ++z)
      for (int y = 0; y < lattice.g[1]; ++y)
        for (int x = 0; x < lattice.g[0]; ++x) points[p++] = g0 + Point(x * cell, y * cell, z * cell);
    for (int z = 0; z < lattice.h[2]; ++z)
      for (int y = 0; y < lattice.h[1]; ++y)
        for (int x = 0; x < lattice.h[0]; ++x) points[p++] = h0 + Point(x * cell, y * cell, z * cell);
  }

  // Inside votes along every lattice line, traced once from its first point; on each point the
  // distance (in edge lengths) to the next crossing ahead and the last one behind.
  const auto at = [](int p) { return static_cast<std::size_t>(p); };
  std::vector<int> inside(at(nbp), 0);
  std::vector<std::array<double, kEdgeShell>> crossing(at(nbp));  // SOFA's eBDist
  for (auto& row : crossing) row.fill(0.0);
  {
    const double scale = (points[at(nbp - 1)] - points[0]).cwiseAbs().maxCoeff() + points[0].cwiseAbs().maxCoeff();
    SurfaceTracer tracer(surface_points, triangles, 1e-7 * (scale + cell));
    for (int p = 0; p < nbp; ++p) {
      for (int e = 0; e < kEdgeShell; e += 2) {
        const int next = lattice.neighbour(p, e);
        if (next == -1 || lattice.neighbour(p, e + 1) != -1) continue;
        const Point origin = points[at(p)];
        const std::vector<Hit> hits = tracer.trace(origin, points[at(next)] - origin, e / 2);
        if (hits.empty()) continue;
        const std::size_t n = hits.size();
        std::size_t i = 0;
        int d = 0;
        for (int q = p; q != -1; q = lattice.neighbour(q, e), ++d) {
          while (i < n && hits[i].t < d) ++i;
          int& vote = inside[at(q)];
          if (i >= n) {
            vote -= hits[n - 1].side;
          } else if (i == 0) {
            vote += hits[0].side;
          } else if ((d - hits[i - 1].t) < (hits[i].t - d)) {
            vote += hits[i].side;
          } else {
            vote -= hits[i - 1].side;
          }
          if (i < n) crossing[at(q)][at(e)] = hits[i].t - d;
          if (i > 0) crossing[at(q)][at(e + 1)] = d - hits[i - 1].t;
        }
      }
    }
  }
  for (int& vote : inside) {
    if (vote == 0) --vote;  // undecided points are outside
  }

  // Snapping: points closer to the surface than alpha (of an edge toward a point on the other
  // side) move onto it and count as on the surface (vote 0).
  if (options.snap_points) {
    const auto alpha_of = [&](int e) { return e < 6 ? options.alpha_long : options.alpha_short; };
    std::vector<bool> violated(at(nbp), false);
    std::set<int> violated_inside, violated_outside;
    for (int p = 0; p < nbp; ++p) {
      const bool in1 = inside[at(p)] > 0;
      bool v = false;
      for (int e = 0; e < kEdgeShell && !v; ++e) {
        const int p2 = lattice.neighbour(p, e);
        if (p2 == -1 || in1 == (inside[at(p2)] > 0)) continue;
        const double alpha = crossing[at(p)][at(e)];
        v = alpha != 0.0 && alpha < alpha_of(e);
      }
      violated[at(p)] = v;
      if (v) (in1 ? violated_inside : violated_outside).insert(p);
    }
    // Moves p along its edge e by the crossing distance and removes the crossings at p.
    const auto wrap = [&](int p, int e) {
      const int p2 = lattice.neighbour(p, e);
      points[at(p)] += (points[at(p2)] - points[at(p)]) * crossing[at(p)][at(e)];
      inside[at(p)] = 0;
      violated[at(p)] = false;
    };
    // The violated edge of p with the smallest squared crossing distance among those toward points
    // `toward` accepts; -1 if none.
    const auto closest_violated_edge = [&](int p, const auto& toward) {
      double smallest = 0;
      int best = -1;
      for (int e = 0; e < kEdgeShell; ++e) {
        const int p2 = lattice.neighbour(p, e);
        if (p2 == -1 || !toward(p2)) continue;
        const double alpha = crossing[at(p)][at(e)];
        if (alpha == 0.0 || alpha >= alpha_of(e)) continue;
        const double dist = alpha * alpha * edge_size2(e);
        if (best == -1 || dist < smallest) {
          best = e;
          smallest = dist;
        }
      }
      return best;
    };
    // First the outside points (SOFA moves them only toward unviolated points that are not inside).
    int wraps = 0;
    do {
      wraps = 0;
      for (const int p : violated_outside) {
        if (inside[at(p)] == 0) continue;
        const int e = closest_violated_edge(p, [&](int p2) { return !(inside[at(p2)] > 0) && !violated[at(p2)]; });
        if (e == -1) continue;
        wrap(p, e);
        ++wraps;
        for (int f = 0; f < kEdgeShell; ++f) {
          crossing[at(p)][at(f)] = 0;
          const int p2 = lattice.neighbour(p, f);
          if (p2 == -1) continue;
          crossing[at(p2)][at(f ^ 1)] = 0;
          if (!violated[at(p2)] || !(inside[at(p2)] > 0)) continue;
          // Is p2 still violated? (SOFA picks alpha by f, the edge from p, not by f2.)
          bool still = false;
          for (int f2 = 0; f2 < kEdgeShell && !still; ++f2) {
            const int p3 = lattice.neighbour(p2, f2);
            if (p3 == -1 || inside[at(p3)] >= 0) continue;
            const double alpha = crossing[at(p2)][at(f2)];
            still = alpha != 0.0 && alpha < alpha_of(f);
          }
          if (!still) {
            violated[at(p2)] = false;
            violated_inside.erase(p2);
          }
        }
      }
    } while (wraps > 0);
    // Then the inside points still violated, toward outside points.
    for (const int p : violated_inside) {
      if (inside[at(p)] == 0) continue;
      const int e = closest_violated_edge(p, [&](int p2) { return inside[at(p2)] < 0; });
      if (e == -1) continue;
      wrap(p, e);
      for (int f = 0; f < kEdgeShell; ++f) {
        crossing[at(p)][at(f)] = 0;
        const int p2 = lattice.neighbour(p, f);
        if (p2 != -1) crossing[at(p2)][at(f ^ 1)] = 0;
      }
    }
  }

  // The crossing points, on the edges from each outside point to an inside one, in that order.
  std::map<std::pair<int, int>, int> cuts;
  if (options.split_tetrahedra) {
    for (int p = 0; p < nbp; ++p) {
      if (inside[at(p)] >= 0) continue;
      for (int e = 0; e < kEdgeShell; ++e) {
        const int p2 = lattice.neighbour(p, e);
        if (p2 == -1 || inside[at(p2)] <= 0) continue;
        const Point cut = points[at(p)] + (points[at(p2)] - points[at(p)]) * crossing[at(p)][at(e)];
        cuts[{p, p2}] = static_cast<int>(points.size());
        points.push_back(cut);
      }
    }
  }

  // The lattice's tetrahedra: 4 around each edge of the first grid, along x, then y, then z, at
  // each of its points in order.
  StuffingBuilder builder(lattice, points, inside, cuts, options.split_tetrahedra);
  const int g01 = lattice.g[0] * lattice.g[1];
  const int h0n = lattice.h[0], h01 = lattice.h[0] * lattice.h[1];
  for (int p = 0, ph = lattice.second, z = 0; z < lattice.g[2]; ++z, ph += h0n) {
    for (int y = 0; y < lattice.g[1]; ++y, ++ph) {
      for (int x = 0; x < lattice.g[0]; ++x, ++p, ++ph) {
        const auto around = [&](int p2, const std::array<int, 4>& shell) {
          for (std::size_t i = 0; i < 4; ++i) builder.add(p, p2, shell[(i + 1) % 4], shell[i]);
        };
        if (x > 0) around(p - 1, {ph, ph + h0n, ph + h0n + h01, ph + h01});
        if (y > 0) around(p - lattice.g[0], {ph, ph + h01, ph + 1 + h01, ph + 1});
        if (z > 0) around(p - g01, {ph, ph + 1, ph + 1 + h0n, ph + h0n});
      }
    }
  }

  // Only the points the tetrahedra use, in order; then any tetrahedron left inverted is turned.
  std::vector<int> renumber(points.size(), 0);
  for (const auto& t : builder.tetrahedra) {
    for (Index v : t) renumber[at(v)] = 1;
  }
  int used = 0;
  for (std::size_t p = 0; p < renumber.size(); ++p) {
    if (renumber[p] == 0) continue;
    renumber[p] = used++;
    points[at(renumber[p])] = points[p];
  }
  points.resize(at(used));
  out.tetrahedra = std::move(builder.tetrahedra);
  for (auto& t : out.tetrahedra) {
    for (Index& v : t) v = renumber[at(v)];
    if (volume6(points[at(t[0])], points[at(t[1])], points[at(t[2])], points[at(t[3])]) < 0) std::swap(t[2], t[3]);
  }
  return out;
}

}  // namespace fastcorot
