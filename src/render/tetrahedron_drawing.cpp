#include "fastcorot/render/tetrahedron_drawing.h"

namespace fastcorot {

template <class Real>
std::array<Vec3<Real>, 4> shrunk_tetrahedron(const std::array<Vec3<Real>, 4>& x) {
  const Vec3<Real> centroid = (x[0] + x[1] + x[2] + x[3]) / Real(4);
  const Real scale = static_cast<Real>(kDrawnTetrahedronScale);
  std::array<Vec3<Real>, 4> shrunk;
  for (int j = 0; j < 4; ++j) shrunk[j] = centroid + scale * (x[j] - centroid);
  return shrunk;
}

template <class Real>
std::array<DrawnTriangle<Real>, 4> drawn_tetrahedron_faces(const std::array<Vec3<Real>, 4>& x) {
  const std::array<Vec3<Real>, 4> p = shrunk_tetrahedron(x);
  std::array<DrawnTriangle<Real>, 4> faces;
  for (int k = 0; k < 4; ++k) {
    const auto& f = kDrawnFaces[static_cast<std::size_t>(k)];
    DrawnTriangle<Real>& face = faces[static_cast<std::size_t>(k)];
    face.corners = {p[f[0]], p[f[1]], p[f[2]]};
    Vec3<Real> n = (face.corners[1] - face.corners[0]).cross(face.corners[2] - face.corners[0]);
    // Away from the opposite vertex, whatever the tetrahedron's orientation, so lighting is right.
    const Vec3<Real>& opposite = p[kOppositeVertexOfDrawnFace[static_cast<std::size_t>(k)]];
    if (n.dot(face.corners[0] - opposite) < 0) n = -n;
    const Real length = n.norm();
    face.normal = length > 0 ? Vec3<Real>(n / length) : Vec3<Real>::Zero();
  }
  return faces;
}

template std::array<Vec3<float>, 4> shrunk_tetrahedron(const std::array<Vec3<float>, 4>&);
template std::array<Vec3<double>, 4> shrunk_tetrahedron(const std::array<Vec3<double>, 4>&);
template std::array<DrawnTriangle<float>, 4> drawn_tetrahedron_faces(
    const std::array<Vec3<float>, 4>&);
template std::array<DrawnTriangle<double>, 4> drawn_tetrahedron_faces(
    const std::array<Vec3<double>, 4>&);

}  // namespace fastcorot
