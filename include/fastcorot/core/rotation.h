// Rotation extraction for the corotational method (SPEC.md, "Rotation"): the QR frame of two edge
// vectors, and the orthogonal polar factor of a 3×3 matrix computed exactly as SOFA computes it,
// so that our rotations agree with SOFA's to round-off.
#pragma once

#include "fastcorot/core/types.h"

namespace fastcorot {

// Orthonormal frame whose rows are x = a/|a|, z = (x × b)/|x × b|, y = z × x (SOFA's
// computeQRRotation). Undefined (non-finite) when a = 0 or b is parallel to a.
template <class Real>
Mat3<Real> qr_frame(const Vec3<Real>& a, const Vec3<Real>& b);

// qr_frame(a[i], b[i]) into out[i] for i < count, bit for bit the same, four at a time in SIMD
// lanes (square roots and divisions side by side).
template <class Real>
void qr_frames(const Vec3<Real>* a, const Vec3<Real>* b, Mat3<Real>* out, int count);

// Convergence tolerance SOFA uses for the polar factor: 1e-8 in double, 1e-6 in float.
template <class Real>
constexpr Real polar_tolerance() {
  return sizeof(Real) >= sizeof(double) ? Real(1e-8) : Real(1e-6);
}

// Orthogonal factor Q of the polar decomposition M = Q S (S symmetric), by Higham's scaled Newton
// iteration X <- (gamma X + X^-T / gamma) / 2 with the (1,inf)-norm scaling of Shoemake's code
// (Vega's PolarDecomposition, which SOFA uses), stopped when the 1-norm of the update is at most
// `tolerance` times the 1-norm of the new iterate. For det M < 0 the iteration converges to an
// orthogonal matrix of determinant -1 (a reflection), as in SOFA; we keep that for compatibility.
// A singular iterate stops the iteration (as in SOFA) and the current iterate is returned (M itself
// when M is singular: finite, not a rotation); callers that need a rotation should check the
// determinant of M first. Where SOFA's sequence over- or underflows into NaN (a nearly singular M,
// smallest singular value below ~1e-200 of the largest, or entries beyond ~1e150; in float far
// sooner), the iterate is rescaled by a power of two and the iteration goes on, so the result is
// finite for finite M (the polar factor down to a ratio of singular values of ~1e-300 in double;
// beyond, or with subnormal entries, finite but not necessarily a rotation); ordinary inputs give
// SOFA's results bit for bit. Non-finite M is returned as is. At most 100 iterations (Newton converges quadratically).
template <class Real>
Mat3<Real> polar_factor(const Mat3<Real>& m, Real tolerance = polar_tolerance<Real>());

// The rotation closest to F for any F, inverted or collapsed ones included (SOFA's
// Decompose::polarDecomposition_stable, through its SVD_stable, which TetrahedronFEMForceField's
// `svd` method uses for inverted or flat elements): U V^T of an SVD F = U S V^T whose U and V are
// rotations, the smallest singular value taking the sign of det F. Singular values below 1e-4
// (1e-3 in float; SOFA's tolerance on F^T F's eigenvalues) count as zero, and the missing
// directions are completed as SOFA completes them. The result is a rotation for every finite F.
template <class Real>
Mat3<Real> stable_polar_factor(const Mat3<Real>& f);

// polar_factor of m[0..count) into out[0..count), bit for bit the same, four matrices at a time in
// SIMD lanes (the iteration is a chain of square roots and divisions: four chains side by side
// take about the time of one). A lane that needs the rescaling or stopping rules above is computed
// again alone by polar_factor. m and out may not overlap.
template <class Real>
void polar_factors(const Mat3<Real>* m, Mat3<Real>* out, int count, Real tolerance = polar_tolerance<Real>());

// The polar factor of the matrix whose rows are a, b and c (SOFA's `polar2` frame of three edges).
template <class Real>
Mat3<Real> polar_frame(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c);

}  // namespace fastcorot
