#include "fastcorot/core/rotation.h"

#include "fastcorot/core/packed.h"

#include <Eigen/Eigenvalues>

#if defined(__SSE__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace fastcorot {

namespace {

// v / |v| with |v|² summed from the first coordinate (SOFA's norm2), v itself when |v|² is 0.
template <class Real>
Vec3<Real> normalized(const Vec3<Real>& v) {
  const Real norm2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  if (!(norm2 > 0)) return v;
  const Real norm = std::sqrt(norm2);
  return Vec3<Real>(v[0] / norm, v[1] / norm, v[2] / norm);
}

}  // namespace

template <class Real>
Mat3<Real> qr_frame(const Vec3<Real>& a, const Vec3<Real>& b) {
  const Vec3<Real> x = normalized(a);
  const Vec3<Real> z = normalized<Real>(x.cross(b));
  const Vec3<Real> y = z.cross(x);
  Mat3<Real> frame;
  frame.row(0) = x.transpose();
  frame.row(1) = y.transpose();
  frame.row(2) = z.transpose();
  return frame;
}

namespace {

// Maximum absolute column sum, each sum from the top (SOFA's oneNorm; Eigen's reductions sum
// three values in an order that depends on the type and the SIMD width).
template <class Real>
Real one_norm(const Mat3<Real>& m) {
  Real norm = 0;
  for (int c = 0; c < 3; ++c) {
    const Real sum = std::abs(m(0, c)) + std::abs(m(1, c)) + std::abs(m(2, c));
    if (sum > norm) norm = sum;
  }
  return norm;
}

// Maximum absolute row sum, each sum from the left (SOFA's infNorm).
template <class Real>
Real inf_norm(const Mat3<Real>& m) {
  Real norm = 0;
  for (int r = 0; r < 3; ++r) {
    const Real sum = std::abs(m(r, 0)) + std::abs(m(r, 1)) + std::abs(m(r, 2));
    if (sum > norm) norm = sum;
  }
  return norm;
}

}  // namespace

template <class Real>
Mat3<Real> polar_factor(const Mat3<Real>& m, Real tolerance) {
  // The iteration runs on the transpose, as Shoemake's code does; the rows of the cofactor matrix
  // are cross products of the iterate's rows, and its first row dotted with the iterate's first
  // row is the determinant. SOFA's sequence of operations, its sums from the left included: the
  // same bits as SOFA (without fused multiply-adds) whatever Eigen's SIMD width.
  Mat3<Real> mk = m.transpose();
  if (!mk.allFinite()) return m;
  Real mk_one = one_norm(mk);
  Real mk_inf = inf_norm(mk);
  constexpr int max_iterations = 100;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Mat3<Real> cofactor;
    cofactor.row(0) = mk.row(1).cross(mk.row(2));
    cofactor.row(1) = mk.row(2).cross(mk.row(0));
    cofactor.row(2) = mk.row(0).cross(mk.row(1));
    const Real det = mk(0, 0) * cofactor(0, 0) + mk(0, 1) * cofactor(0, 1) + mk(0, 2) * cofactor(0, 2);
    // Scales the iterate by a power of two (exact: the polar factor of c M is that of M for any
    // c > 0) to a largest entry in [0.5, 1); false when it is there already.
    int exponent = 0;
    std::frexp(mk.cwiseAbs().maxCoeff(), &exponent);
    auto rescale = [&] {
      if (exponent == 0) return false;
      mk = mk.unaryExpr([exponent](Real v) { return std::ldexp(v, -exponent); });
      mk_one = one_norm(mk);
      mk_inf = inf_norm(mk);
      return true;
    };
    if (det == Real(0)) {
      // A singular iterate stops the iteration as in SOFA, unless the determinant only underflowed
      // (entries so small that their cube does).
      if (exponent < std::numeric_limits<Real>::min_exponent / 3 && rescale()) continue;
      break;
    }
    const Real cofactor_one = one_norm(cofactor);
    const Real cofactor_inf = inf_norm(cofactor);
    const Real gamma =
        std::sqrt(std::sqrt((cofactor_one * cofactor_inf) / (mk_one * mk_inf)) / std::abs(det));
    const Real g1 = gamma * Real(0.5);
    const Real g2 = Real(0.5) / (gamma * det);
    const Mat3<Real> next = g1 * mk + g2 * cofactor;
    if (!(std::isfinite(g1) && g1 > 0 && std::isfinite(g2) && g2 != Real(0) && next.allFinite())) {
      // Over- or underflow, where SOFA's code returns NaN: a nearly singular matrix (a collapsed
      // element) makes the iterate grow like 1/sqrt(smallest singular value) and its determinant
      // overflow, and huge entries overflow the norms. The polar factor of c M is that of M for
      // any c > 0, so scale the iterate by a power of two (exact) to a largest entry near 1 and
      // go on. Never taken while SOFA's update stays finite with both terms non-zero, so such
      // results are unchanged.
      if (rescale()) continue;
      break;  // of order 1 and still not finite: keep the last finite iterate
    }
    const Real change_one = one_norm<Real>(mk - next);
    mk = next;
    mk_one = one_norm(mk);
    mk_inf = inf_norm(mk);
    // Negated so that a NaN stops the loop as SOFA's do-while does.
    if (!(change_one > mk_one * tolerance)) break;
  }
  return mk.transpose();
}

namespace {

// Four 3×3 matrices, entry (r, c) of matrix l in lane l of a[r][c].
template <class Real>
struct FourMatrices {
  Packed<Real> a[3][3];
};

template <class Real>
Packed<Real> packed_max(const Packed<Real>& a, const Packed<Real>& b) {
  return a > b ? a : b;
}

// one_norm and inf_norm above, lane by lane.
template <class Real>
Packed<Real> packed_one_norm(const FourMatrices<Real>& m) {
  Packed<Real> norm{};
  for (int c = 0; c < 3; ++c) {
    const Packed<Real> sum = (packed_abs<Real>(m.a[0][c]) + packed_abs<Real>(m.a[1][c])) + packed_abs<Real>(m.a[2][c]);
    norm = c == 0 ? sum : packed_max<Real>(norm, sum);
  }
  return norm;
}

template <class Real>
Packed<Real> packed_inf_norm(const FourMatrices<Real>& m) {
  Packed<Real> norm{};
  for (int r = 0; r < 3; ++r) {
    const Packed<Real> sum = (packed_abs<Real>(m.a[r][0]) + packed_abs<Real>(m.a[r][1])) + packed_abs<Real>(m.a[r][2]);
    norm = r == 0 ? sum : packed_max<Real>(norm, sum);
  }
  return norm;
}

// Lane by lane std::sqrt (correctly rounded, so the vector instruction gives the same bits).
template <class Real>
Packed<Real> packed_sqrt(const Packed<Real>& v) {
#if defined(__AVX__)
  if constexpr (std::is_same_v<Real, double>) return Packed<Real>(_mm256_sqrt_pd(__m256d(v)));
#endif
#if defined(__SSE__)
  if constexpr (std::is_same_v<Real, float>) return Packed<Real>(_mm_sqrt_ps(__m128(v)));
#endif
  Packed<Real> r;
  for (int l = 0; l < 4; ++l) r[l] = std::sqrt(v[l]);
  return r;
}

// Lanes whose value is finite (x - x is 0 but for an infinity or NaN), as a lane mask.
template <class Real>
auto packed_finite(const Packed<Real>& v) {
  return (v - v) == Real(0);
}

// polar_factor's iteration on four matrices at once, each lane doing exactly the scalar code's
// operations, for as long as no lane needs a rescaling (then that lane is marked in `alone`). A
// lane stops where the scalar loop breaks; its result is the transposed final iterate.
template <class Real>
void polar_factor_lanes(const Mat3<Real>* m, Mat3<Real>* out, Real tolerance, bool (&alone)[4]) {
  using P = Packed<Real>;
  FourMatrices<Real> mk;
  for (int l = 0; l < 4; ++l) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) mk.a[r][c][l] = m[l](c, r);
    }
  }
  P mk_one = packed_one_norm<Real>(mk), mk_inf = packed_inf_norm<Real>(mk);
  auto active = P{} == P{};  // every lane
  const P half = broadcast(Real(0.5));
  for (int iteration = 0; iteration < 100; ++iteration) {
    FourMatrices<Real> cofactor;
    const auto cross = [&](int i, int j, int to) {
      cofactor.a[to][0] = mk.a[i][1] * mk.a[j][2] - mk.a[i][2] * mk.a[j][1];
      cofactor.a[to][1] = mk.a[i][2] * mk.a[j][0] - mk.a[i][0] * mk.a[j][2];
      cofactor.a[to][2] = mk.a[i][0] * mk.a[j][1] - mk.a[i][1] * mk.a[j][0];
    };
    cross(1, 2, 0);
    cross(2, 0, 1);
    cross(0, 1, 2);
    const P det = (mk.a[0][0] * cofactor.a[0][0] + mk.a[0][1] * cofactor.a[0][1]) + mk.a[0][2] * cofactor.a[0][2];
    const P cofactor_one = packed_one_norm<Real>(cofactor), cofactor_inf = packed_inf_norm<Real>(cofactor);
    const P gamma = packed_sqrt<Real>(packed_sqrt<Real>((cofactor_one * cofactor_inf) / (mk_one * mk_inf)) / packed_abs<Real>(det));
    const P g1 = gamma * half;
    const P g2 = half / (gamma * det);
    FourMatrices<Real> next, change;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        next.a[r][c] = g1 * mk.a[r][c] + g2 * cofactor.a[r][c];
        change.a[r][c] = mk.a[r][c] - next.a[r][c];
      }
    }
    const P change_one = packed_one_norm<Real>(change);
    const P next_one = packed_one_norm<Real>(next), next_inf = packed_inf_norm<Real>(next);
    // Per lane, as lane masks: an iterate the scalar code would take (else the scalar code's
    // rescaling or stop: that lane again, alone), the active lanes taking it, those going on.
    auto fine = (det != Real(0)) & packed_finite<Real>(g1) & (g1 > Real(0)) & packed_finite<Real>(g2) & (g2 != Real(0));
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) fine &= packed_finite<Real>(next.a[r][c]);
    }
    const auto take = active & fine;
    for (int l = 0; l < 4; ++l) alone[l] = alone[l] || (active[l] && !fine[l]);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) mk.a[r][c] = take ? next.a[r][c] : mk.a[r][c];
    }
    mk_one = take ? next_one : mk_one;
    mk_inf = take ? next_inf : mk_inf;
    active = take & (change_one > next_one * tolerance);
    bool any = false;
    for (int l = 0; l < 4; ++l) any = any || active[l];
    if (!any) break;
  }
  for (int l = 0; l < 4; ++l) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) out[l](c, r) = mk.a[r][c][l];
    }
  }
}

}  // namespace

template <class Real>
void polar_factors(const Mat3<Real>* m, Mat3<Real>* out, int count, Real tolerance) {
  int first = 0;
  for (; first + 4 <= count; first += 4) {
    bool alone[4] = {false, false, false, false};
    bool finite = true;
    for (int l = 0; l < 4; ++l) finite = finite && m[first + l].allFinite();
    if (finite) polar_factor_lanes(m + first, out + first, tolerance, alone);
    for (int l = 0; l < 4; ++l) {
      if (!finite || alone[l]) out[first + l] = polar_factor(m[first + l], tolerance);
    }
  }
  for (; first < count; ++first) out[first] = polar_factor(m[first], tolerance);
}

template <class Real>
void qr_frames(const Vec3<Real>* a, const Vec3<Real>* b, Mat3<Real>* out, int count) {
  using P = Packed<Real>;
  int first = 0;
  for (; first + 4 <= count; first += 4) {
    P x[3]{}, e[3]{};
    for (int c = 0; c < 3; ++c) {
      for (int l = 0; l < 4; ++l) {
        x[c][l] = a[first + l][c];
        e[c][l] = b[first + l][c];
      }
    }
    const P x_norm2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    const P x_norm = packed_sqrt<Real>(x_norm2);
    for (int c = 0; c < 3; ++c) x[c] = x[c] / x_norm;
    P z[3] = {x[1] * e[2] - x[2] * e[1], x[2] * e[0] - x[0] * e[2], x[0] * e[1] - x[1] * e[0]};
    const P z_norm2 = z[0] * z[0] + z[1] * z[1] + z[2] * z[2];
    const P z_norm = packed_sqrt<Real>(z_norm2);
    for (int c = 0; c < 3; ++c) z[c] = z[c] / z_norm;
    const P y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
    for (int l = 0; l < 4; ++l) {
      if (!(x_norm2[l] > 0 && z_norm2[l] > 0)) {
        out[first + l] = qr_frame(a[first + l], b[first + l]);  // a zero edge or normal: as qr_frame leaves it
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        out[first + l](0, c) = x[c][l];
        out[first + l](1, c) = y[c][l];
        out[first + l](2, c) = z[c][l];
      }
    }
  }
  for (; first < count; ++first) out[first] = qr_frame(a[first], b[first]);
}

// SOFA's Decompose::zeroTolerance: below it an eigenvalue of F^T F counts as zero.
template <class Real>
constexpr Real zero_tolerance() {
  return sizeof(Real) >= sizeof(double) ? Real(1e-8) : Real(1e-6);
}

template <class Real>
Mat3<Real> stable_polar_factor(const Mat3<Real>& f) {
  // SOFA's SVD_stable: V and S^2 from the eigen decomposition of F^T F, V made a rotation, U = F V
  // S^-1 with the columns of zero singular values rebuilt, then U made a rotation by negating the
  // column of the smallest singular value; the result is U V^T.
  const Eigen::SelfAdjointEigenSolver<Mat3<Real>> eigen(f.transpose() * f);
  Mat3<Real> v = eigen.eigenvectors();
  Vec3<Real> s = eigen.eigenvalues();
  if (v.determinant() < 0) v.col(0) = -v.col(0);
  int degenerated = 0;
  Vec3<Real> inverse;
  for (int i = 0; i < 3; ++i) {
    if (s[i] < zero_tolerance<Real>()) {
      ++degenerated;
      s[i] = 0;
      inverse[i] = 1;
    } else {
      s[i] = std::sqrt(s[i]);
      inverse[i] = 1 / s[i];
    }
  }
  // Columns from the smallest singular value to the largest.
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return s[a] < s[b]; });
  Mat3<Real> u = f * v * inverse.asDiagonal();
  if (degenerated == 1) {
    // Flattened onto a plane: the two valid columns span it, their cross product completes them.
    u.col(order[0]) = u.col(order[1]).cross(u.col(order[2]));
  } else if (degenerated == 2) {
    // Collapsed onto a line: two unit vectors orthogonal to the valid column. (SOFA takes the line's
    // direction from entries of two columns, u(0, largest), u(1, smallest), u(2, smallest); kept.)
    const Vec3<Real> line(u(0, order[2]), u(1, order[0]), u(2, order[0]));
    const Real a0 = std::abs(line[0]), a1 = std::abs(line[1]), a2 = std::abs(line[2]);
    Vec3<Real> e0;
    if (a0 > a1) {
      e0 = a0 > a2 ? Vec3<Real>(0, 1, 0) : Vec3<Real>(1, 0, 0);
    } else {
      e0 = a1 > a2 ? Vec3<Real>(0, 0, 1) : Vec3<Real>(1, 0, 0);
    }
    Vec3<Real> e1 = line.cross(e0);
    e1.normalize();
    e0 = e1.cross(line);
    u.col(order[0]) = e0;
    u.col(order[1]) = e1;
  } else if (degenerated == 3) {
    u.setIdentity();
  }
  if (u.determinant() < 0) u.col(order[0]) = -u.col(order[0]);
  return u * v.transpose();
}

template <class Real>
Mat3<Real> polar_frame(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c) {
  Mat3<Real> rows;
  rows.row(0) = a.transpose();
  rows.row(1) = b.transpose();
  rows.row(2) = c.transpose();
  return polar_factor(rows);
}

template Mat3<float> qr_frame(const Vec3<float>&, const Vec3<float>&);
template Mat3<double> qr_frame(const Vec3<double>&, const Vec3<double>&);
template void qr_frames(const Vec3<float>*, const Vec3<float>*, Mat3<float>*, int);
template void qr_frames(const Vec3<double>*, const Vec3<double>*, Mat3<double>*, int);
template Mat3<float> polar_factor(const Mat3<float>&, float);
template Mat3<double> polar_factor(const Mat3<double>&, double);
template void polar_factors(const Mat3<float>*, Mat3<float>*, int, float);
template void polar_factors(const Mat3<double>*, Mat3<double>*, int, double);
template Mat3<float> stable_polar_factor(const Mat3<float>&);
template Mat3<double> stable_polar_factor(const Mat3<double>&);
template Mat3<float> polar_frame(const Vec3<float>&, const Vec3<float>&, const Vec3<float>&);
template Mat3<double> polar_frame(const Vec3<double>&, const Vec3<double>&, const Vec3<double>&);

}  // namespace fastcorot
