// Basic value types shared by every layer: fixed-size Eigen vectors and matrices templated on the
// scalar, the integer index used for points, edges and tetrahedra, and the small index tuples that
// name a tetrahedron, an edge or a triangle. Arrays of points are contiguous `Vec3<Real>` (three
// scalars each, no padding), so an #V×3 row-major buffer can be viewed as `std::span<Vec3<Real>>`.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include <array>
#include <cstdint>
#include <span>

namespace fastcorot {

template <class Real>
using Vec3 = Eigen::Matrix<Real, 3, 1>;

template <class Real>
using Mat3 = Eigen::Matrix<Real, 3, 3>;

// Index of a point, edge or tetrahedron. Signed, like Eigen's sparse storage index.
using Index = std::int32_t;

// Four point indices (v0, v1, v2, v3), SOFA's Tetrahedron.
using Tetrahedron = std::array<Index, 4>;

// Two point indices (a, b); `a` is the edge's first vertex, which fixes its orientation.
using Edge = std::array<Index, 2>;

// Three point indices.
using Triangle = std::array<Index, 3>;

static_assert(sizeof(Vec3<double>) == 3 * sizeof(double), "Vec3 must be three packed scalars");
static_assert(sizeof(Vec3<float>) == 3 * sizeof(float), "Vec3 must be three packed scalars");

}  // namespace fastcorot
