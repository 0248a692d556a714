// SOFA's drawn tetrahedra: the 2/3 shrink about the centroid and the face order of
// FastTetrahedralCorotationalForceField::draw (sofa-framework/sofa,
// Sofa/Component/SolidMechanics/FEM/Elastic/.../FastTetrahedralCorotationalForceField.inl).
#include "fastcorot/render/tetrahedron_drawing.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace fastcorot {
namespace {

const std::array<Vec3<double>, 4> kTetrahedron = {
    Vec3<double>(0.3, -1.0, 2.0), Vec3<double>(2.1, 0.4, 1.5), Vec3<double>(-0.7, 1.9, 0.8),
    Vec3<double>(0.5, 0.2, 3.9)};

TEST(TetrahedronDrawing, ShrinksToTwoThirdsAboutTheCentroidAsSofa) {
  const auto shrunk = shrunk_tetrahedron<double>(kTetrahedron);
  const Vec3<double> centroid =
      (kTetrahedron[0] + kTetrahedron[1] + kTetrahedron[2] + kTetrahedron[3]) / 4;
  const Vec3<double> sum = 4 * centroid;
  for (int j = 0; j < 4; ++j) {
    EXPECT_TRUE(shrunk[j].isApprox(centroid + 2.0 / 3.0 * (kTetrahedron[j] - centroid), 1e-15));
    // SOFA's own expression, with its rounded constant: the same corner to 1e-6.
    const Vec3<double> sofa = (kTetrahedron[j] + sum * 0.125) * 0.666667;
    EXPECT_LT((shrunk[j] - sofa).norm(), 1e-5 * sofa.norm());
  }
  const Vec3<double> shrunk_centroid = (shrunk[0] + shrunk[1] + shrunk[2] + shrunk[3]) / 4;
  EXPECT_TRUE(shrunk_centroid.isApprox(centroid, 1e-15));
}

TEST(TetrahedronDrawing, FacesAndColoursFollowSofasOrder) {
  // SOFA: triangles (a b c) (b c d) (c d a) (d a b) in drawColor1..4.
  EXPECT_EQ(kDrawnFaces[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(kDrawnFaces[1], (std::array<int, 3>{1, 2, 3}));
  EXPECT_EQ(kDrawnFaces[2], (std::array<int, 3>{2, 3, 0}));
  EXPECT_EQ(kDrawnFaces[3], (std::array<int, 3>{3, 0, 1}));
  for (int k = 0; k < 4; ++k) {
    const int opposite = kOppositeVertexOfDrawnFace[static_cast<std::size_t>(k)];
    const auto& face = kDrawnFaces[static_cast<std::size_t>(k)];
    EXPECT_EQ(std::count(face.begin(), face.end(), opposite), 0) << "triangle " << k;
    EXPECT_EQ(drawn_color_of_face(opposite), k);
  }
}

template <class Real>
void check_faces(const std::array<Vec3<Real>, 4>& x) {
  const auto faces = drawn_tetrahedron_faces<Real>(x);
  const auto shrunk = shrunk_tetrahedron<Real>(x);
  for (std::size_t k = 0; k < 4; ++k) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(faces[k].corners[c], shrunk[kDrawnFaces[k][c]]);
    EXPECT_NEAR(faces[k].normal.norm(), Real(1), Real(1e-6));
    const Vec3<Real>& opposite = shrunk[kOppositeVertexOfDrawnFace[k]];
    EXPECT_GT(faces[k].normal.dot(faces[k].corners[0] - opposite), Real(0))
        << "normal of triangle " << k;
  }
}

TEST(TetrahedronDrawing, NormalsPointOutwardForEitherOrientation) {
  check_faces<double>(kTetrahedron);
  check_faces<double>(
      {kTetrahedron[1], kTetrahedron[0], kTetrahedron[2], kTetrahedron[3]});  // inverted
  std::array<Vec3<float>, 4> single;
  for (int j = 0; j < 4; ++j) single[j] = kTetrahedron[j].cast<float>();
  check_faces<float>(single);
}

TEST(TetrahedronDrawing, DegenerateTetrahedronGivesZeroNormals) {
  const Vec3<double> p(1, 2, 3);
  const auto faces = drawn_tetrahedron_faces<double>({p, p, p, p});
  for (const auto& face : faces) EXPECT_EQ(face.normal, Vec3<double>::Zero());
}

}  // namespace
}  // namespace fastcorot
