// Picking: which tetrahedron lies under a pixel of a picture, for cutting with the mouse. The ray
// leaves the camera's eye through the pixel (the inverse of Camera::project) and meets the mesh's
// boundary triangles, what the viewer shows, at their current positions (Möller–Trumbore
// ray/triangle test, both sides, so that a cut's freshly exposed faces count whatever their
// winding); the nearest triangle hit names its tetrahedron. A ray enters an object through its
// boundary, so the nearest of all tetrahedra's faces is a boundary triangle too: that is how a mesh
// is picked without finding its boundary first. A cutting "brush" then takes every tetrahedron
// whose centroid lies within a radius of the point hit. Nothing here touches OpenGL.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/render/camera.h"
#include "fastcorot/topology/tet_mesh.h"

#include <optional>
#include <span>
#include <vector>

namespace fastcorot {

// A half line origin + t direction, t >= 0, with |direction| = 1 (t is a distance).
struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;
};

// The ray from the eye through `pixel` of a width × height picture (x to the right, y downwards
// from the top left corner, pixel centres at .5, as Camera::project). Throws fastcorot::Error for a
// width or height below 1.
Ray pixel_ray(const Camera& camera, int width, int height, const Eigen::Vector2d& pixel);

// Distance along `ray` to triangle (a, b, c), or nullopt when the ray misses it, runs parallel to
// its plane, or meets it behind the origin. Möller & Trumbore, "Fast, minimum storage ray/triangle
// intersection" (1997), without back-face culling. A degenerate triangle is never hit.
std::optional<double> intersect_ray_triangle(const Ray& ray, const Eigen::Vector3d& a,
                                             const Eigen::Vector3d& b, const Eigen::Vector3d& c);

struct TetrahedronHit {
  Index tetrahedron = -1;                           // in the mesh's current numbering
  double distance = 0;                              // along the ray, world units
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // where the ray meets the boundary
};

// The nearest of `boundary` (triangles of a mesh, e.g. TetMesh::boundary_triangles()) hit by `ray`
// with the points at `positions` (#V), or nullopt. Pass the boundary when it is already at hand (a
// drawer keeps it between frames); it must be that of the mesh's current tetrahedra.
template <class Real>
std::optional<TetrahedronHit> pick_tetrahedron(std::span<const BoundaryTriangle> boundary,
                                               std::span<const Vec3<Real>> positions,
                                               const Ray& ray);

// The same for every tetrahedron of `mesh`: the nearest face hit among all their faces is where the
// ray first enters the mesh, so the answer is that of its boundary (a tie on a shared edge may name
// either neighbour) without computing the boundary. Time linear in the mesh, no allocation.
template <class Real>
std::optional<TetrahedronHit> pick_tetrahedron(const TetMesh& mesh,
                                               std::span<const Vec3<Real>> positions,
                                               const Ray& ray);

// Tetrahedra of `mesh` whose centroid (mean of its four `positions`) lies within `radius` (world
// units, inclusive) of `centre`, in increasing order: the cutting brush. A radius below 0 or NaN
// takes none.
template <class Real>
std::vector<Index> tetrahedra_within(const TetMesh& mesh, std::span<const Vec3<Real>> positions,
                                     const Eigen::Vector3d& centre, double radius);

}  // namespace fastcorot
