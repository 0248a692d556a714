#include "fastcorot/fem/tetrahedron_element.h"

#include "fastcorot/core/rotation.h"
#include "fastcorot/topology/tet_mesh.h"

namespace fastcorot {

template <class Real>
TetrahedronRest<Real> tetrahedron_rest(const TetPoints<Real>& p, const LameParameters<Real>& lame,
                                       RotationMethod method) {
  TetrahedronRest<Real> rest;
  rest.volume = signed_volume(p);
  const Real abs_volume = std::abs(rest.volume);
  rest.mu = lame.mu * abs_volume;
  rest.lambda = lame.lambda * abs_volume;
  // s_j = ±(p_{j+2} - p_{j+1}) × (p_{j+3} - p_{j+1}) / (6V), + for even j (indices mod 4). With
  // SOFA's sign of V this is the gradient of vertex j's barycentric coordinate.
  for (int j = 0; j < 4; ++j) {
    const Vec3<Real>& a = p[(j + 1) % 4];
    const Vec3<Real>& b = p[(j + 2) % 4];
    const Vec3<Real>& c = p[(j + 3) % 4];
    const Real sign = (j % 2 == 0) ? Real(1) : Real(-1);
    rest.shape[j] = sign * (b - a).cross(c - a) / (6 * rest.volume);
  }
  switch (method) {
    case RotationMethod::qr:
      rest.rest_rotation = qr_frame<Real>(p[1] - p[0], p[2] - p[0]);
      break;
    case RotationMethod::polar2:
      rest.rest_rotation = polar_frame<Real>(p[1] - p[0], p[2] - p[0], p[3] - p[0]);
      break;
    case RotationMethod::polar:
    case RotationMethod::none:
      rest.rest_rotation.setIdentity();
      break;
  }
  return rest;
}

template <class Real>
Mat3<Real> vertex_block(const TetrahedronRest<Real>& rest, int j) {
  const Vec3<Real>& s = rest.shape[j];
  return (rest.lambda + rest.mu) * s * s.transpose() + rest.mu * s.squaredNorm() * Mat3<Real>::Identity();
}

template <class Real>
Mat3<Real> edge_block(const TetrahedronRest<Real>& rest, int e) {
  const Vec3<Real>& sk = rest.shape[kTetrahedronEdges[e][0]];
  const Vec3<Real>& sl = rest.shape[kTetrahedronEdges[e][1]];
  return rest.lambda * sl * sk.transpose() + rest.mu * sk * sl.transpose() +
         rest.mu * sl.dot(sk) * Mat3<Real>::Identity();
}

template <class Real>
Mat3<Real> tetrahedron_rotation(const TetrahedronRest<Real>& rest, const TetPoints<Real>& x,
                                RotationMethod method) {
  switch (method) {
    case RotationMethod::qr:
      return qr_frame<Real>(x[1] - x[0], x[2] - x[0]).transpose() * rest.rest_rotation;
    case RotationMethod::polar: {
      Mat3<Real> deformation_gradient = Mat3<Real>::Zero();
      for (int i = 1; i < 4; ++i) deformation_gradient += (x[i] - x[0]) * rest.shape[i].transpose();
      return polar_factor(deformation_gradient);
    }
    case RotationMethod::polar2:
      return polar_frame<Real>(x[1] - x[0], x[2] - x[0], x[3] - x[0]).transpose() * rest.rest_rotation;
    case RotationMethod::none:
      break;
  }
  return Mat3<Real>::Identity();
}

namespace {

// Rest-frame displacement gradient H = sum_{j>=1} u_j s_j^T, u_j = R^T (x_j - x0) - (p_j - p0)
// (u_0 = 0; differences keep precision far from the origin).
template <class Real>
Mat3<Real> displacement_gradient(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p,
                                 const TetPoints<Real>& x, const Mat3<Real>& rotation) {
  Mat3<Real> h = Mat3<Real>::Zero();
  for (int j = 1; j < 4; ++j) {
    const Vec3<Real> u = rotation.transpose() * (x[j] - x[0]) - (p[j] - p[0]);
    h.noalias() += u * rest.shape[j].transpose();
  }
  return h;
}

}  // namespace

template <class Real>
TetPoints<Real> tetrahedron_force(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p,
                                  const TetPoints<Real>& x, const Mat3<Real>& rotation) {
  const Mat3<Real> h = displacement_gradient(rest, p, x, rotation);
  Mat3<Real> stress = rest.mu * (h + h.transpose());
  stress.diagonal().array() += rest.lambda * h.trace();
  // World-frame forces f_j = -R stress s_j.
  const Mat3<Real> world_stress = rotation * stress;
  TetPoints<Real> f;
  for (int j = 0; j < 4; ++j) f[j] = -(world_stress * rest.shape[j]);
  return f;
}

template <class Real>
Real tetrahedron_energy(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p,
                        const TetPoints<Real>& x, const Mat3<Real>& rotation) {
  const Mat3<Real> h = displacement_gradient(rest, p, x, rotation);
  const Mat3<Real> strain = (h + h.transpose()) / 2;
  const Real trace = h.trace();
  return rest.lambda / 2 * trace * trace + rest.mu * strain.squaredNorm();
}

#define FASTCOROT_INSTANTIATE(Real)                                                                \
  template TetrahedronRest<Real> tetrahedron_rest(const TetPoints<Real>&,                          \
                                                  const LameParameters<Real>&, RotationMethod);    \
  template Mat3<Real> vertex_block(const TetrahedronRest<Real>&, int);                             \
  template Mat3<Real> edge_block(const TetrahedronRest<Real>&, int);                               \
  template Mat3<Real> tetrahedron_rotation(const TetrahedronRest<Real>&, const TetPoints<Real>&,   \
                                           RotationMethod);                                        \
  template TetPoints<Real> tetrahedron_force(const TetrahedronRest<Real>&, const TetPoints<Real>&, \
                                             const TetPoints<Real>&, const Mat3<Real>&);           \
  template Real tetrahedron_energy(const TetrahedronRest<Real>&, const TetPoints<Real>&,           \
                                   const TetPoints<Real>&, const Mat3<Real>&);
FASTCOROT_INSTANTIATE(float)
FASTCOROT_INSTANTIATE(double)
#undef FASTCOROT_INSTANTIATE

}  // namespace fastcorot
