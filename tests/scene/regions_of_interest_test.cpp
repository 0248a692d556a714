// SOFA's BoxROI and PlaneROI (src/scene/regions_of_interest.cpp) read through the scene's data, as
// links to their outputs read them. Expected selections are worked out independently: a slab over
// a parallelogram is the set |(p - c)·u| <= a, |(p - c)·v| <= b, |(p - p0)·n| <= depth / 2 for its
// centre c and unit edge directions u, v (SOFA's BoxROI.inl and PlaneROI.inl define the same set
// with four side planes); the grid points are placed off every boundary so that rounding cannot
// decide membership.
#include "scene/scene_data.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

// A 5×5×5 grid over [-1, 1]^3 (spacing 0.5), moved by `rotation` about the origin, its tetrahedra,
// and `roi` in the same node.
class Roi {
 public:
  explicit Roi(const std::string& roi, const Mat3<double>& rotation = Mat3<double>::Identity()) {
    std::ostringstream position;
    position.precision(17);
    for (int k = 0; k < 5; ++k) {
      for (int j = 0; j < 5; ++j) {
        for (int i = 0; i < 5; ++i) {
          const Vec3<double> p = rotation * Vec3<double>(-1 + 0.5 * i, -1 + 0.5 * j, -1 + 0.5 * k);
          points_.push_back(p);
          position << p.x() << ' ' << p.y() << ' ' << p.z() << ' ';
        }
      }
    }
    scene_ = parse_scene_text("<Node name=\"root\"><RegularGridTopology name=\"grid\" n=\"5 5 5\" min=\"-1 -1 -1\" "
                              "max=\"1 1 1\"/><MechanicalObject name=\"state\" position=\"" + position.str() +
                                  "\"/><TetrahedronSetTopologyContainer name=\"tets\"/><Hexa2TetraTopologicalMapping "
                                  "input=\"@grid\" output=\"@tets\"/>" + roi + "</Node>",
                              "roi.scn");
    data_ = std::make_unique<SceneData>(scene_, info_, &warnings_);
  }

  Numbers operator()(const std::string& name) {
    for (auto& component : data_->root().components) {
      if (component->name() == "roi") return data_->data(*component, name);
    }
    throw make_error("no roi");
  }
  std::vector<Index> indices(const std::string& name = "indices") {
    std::vector<Index> out;
    for (double v : (*this)(name)) out.push_back(static_cast<Index>(v));
    return out;
  }
  const std::vector<Vec3<double>>& points() const { return points_; }
  std::vector<Index> tetrahedra() {
    std::vector<Index> out;
    for (auto& component : data_->root().components) {
      if (component->name() == "tets") {
        for (double v : data_->data(*component, "tetrahedra")) out.push_back(static_cast<Index>(v));
      }
    }
    return out;
  }

 private:
  SceneNode scene_;
  std::vector<std::string> info_, warnings_;
  std::unique_ptr<SceneData> data_;
  std::vector<Vec3<double>> points_;
};

// The points of `points` in the slab over p0, p1, p2 (fourth corner p0 + p2 - p1) `depth` thick.
std::vector<Index> in_slab(const std::vector<Vec3<double>>& points, const Vec3<double>& p0, const Vec3<double>& p1,
                           const Vec3<double>& p2, double depth) {
  const Vec3<double> centre = (p0 + p2) / 2;
  const Vec3<double> u = (p1 - p0).normalized(), n = (p1 - p0).cross(p2 - p0).normalized(), v = n.cross(u);
  const double a = std::abs((p2 - p0).dot(u)) / 2, b = std::abs((p2 - p0).dot(v)) / 2;
  std::vector<Index> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3<double> d = points[i] - centre;
    if (std::abs(d.dot(u)) <= a && std::abs(d.dot(v)) <= b && std::abs((points[i] - p0).dot(n)) <= depth / 2) {
      out.push_back(static_cast<Index>(i));
    }
  }
  return out;
}

std::string numbers(std::initializer_list<Vec3<double>> corners, double depth) {
  std::ostringstream out;
  out.precision(17);
  for (const auto& c : corners) out << c.x() << ' ' << c.y() << ' ' << c.z() << ' ';
  out << depth;
  return out.str();
}

TEST(PlaneRoi, SelectsTheSlabOverItsParallelogramAlsoWhenTurned) {
  // A rectangle 1.2 by 0.7 about (0.5, 0.25, 0.1), 0.6 thick: x in {0, 0.5, 1}, y in {0, 0.5}, z 0.
  const Vec3<double> p0(-0.1, -0.1, 0.1), p1(1.1, -0.1, 0.1), p2(1.1, 0.6, 0.1);
  const Mat3<double> turn = Eigen::AngleAxisd(0.7, Vec3<double>(1, 2, 3).normalized()).toRotationMatrix();
  for (const Mat3<double>& rotation : {Mat3<double>(Mat3<double>::Identity()), turn}) {
    Roi roi("<PlaneROI name=\"roi\" plane=\"" + numbers({rotation * p0, rotation * p1, rotation * p2}, 0.6) + "\"/>",
            rotation);
    const auto expected = in_slab(roi.points(), rotation * p0, rotation * p1, rotation * p2, 0.6);
    EXPECT_EQ(expected.size(), 6u);
    EXPECT_EQ(roi.indices(), expected);
    // pointsInROI: their positions; tetrahedra only with all four points in the slab (none: the
    // slab holds one layer of points).
    const Numbers positions = roi("pointsInROI");
    ASSERT_EQ(positions.size(), 3 * expected.size());
    EXPECT_EQ(Vec3<double>(positions[0], positions[1], positions[2]), roi.points()[static_cast<std::size_t>(expected[0])]);
    EXPECT_TRUE(roi.indices("tetrahedronIndices").empty());
  }
}

TEST(BoxRoi, OrientedBoxesSelectThePlaneRoiSlabAndAddToTheBoxes) {
  const Vec3<double> p0(-0.1, -0.1, 0.1), p1(1.1, -0.1, 0.1), p2(1.1, 0.6, 0.1);
  Roi oriented("<BoxROI name=\"roi\" orientedBox=\"" + numbers({p0, p1, p2}, 0.6) + "\"/>");
  EXPECT_EQ(oriented.indices(), in_slab(oriented.points(), p0, p1, p2, 0.6));
  // With a box too: the union, in point order, each point once (the box overlaps the slab).
  Roi both("<BoxROI name=\"roi\" box=\"-1.1 -1.1 -1.1 0.1 0.1 0.1\" orientedBox=\"" + numbers({p0, p1, p2}, 0.6) + "\"/>");
  std::set<Index> expected;
  for (Index i : in_slab(both.points(), p0, p1, p2, 0.6)) expected.insert(i);
  for (std::size_t i = 0; i < both.points().size(); ++i) {
    const Vec3<double>& p = both.points()[i];
    if (p.maxCoeff() <= 0.1) expected.insert(static_cast<Index>(i));
  }
  EXPECT_EQ(both.indices(), std::vector<Index>(expected.begin(), expected.end()));
  EXPECT_EQ(both("nbIndices"), Numbers{static_cast<double>(expected.size())});
}

TEST(BoxRoi, OutputsInsideAndOutsideAgreeWithEachOther) {
  // Reversed bounds are swapped, as SOFA does at init.
  Roi roi("<BoxROI name=\"roi\" box=\"0.6 1.1 1.1 -1.1 -1.1 -1.1\"/>");
  const auto inside = roi.indices();
  const auto outside = roi.indices("indicesOut");
  EXPECT_EQ(inside.size() + outside.size(), roi.points().size());
  for (Index i : inside) EXPECT_TRUE(roi.points()[static_cast<std::size_t>(i)].x() <= 0.6);
  for (Index i : outside) EXPECT_TRUE(roi.points()[static_cast<std::size_t>(i)].x() > 0.6);
  const Numbers out_positions = roi("pointsOutROI");
  ASSERT_EQ(out_positions.size(), 3 * outside.size());
  EXPECT_EQ(out_positions[0], roi.points()[static_cast<std::size_t>(outside[0])].x());

  // Tetrahedra: strict (all four points inside), the elements themselves, and the complement.
  const auto tetrahedra = roi.tetrahedra();
  const auto in_tets = roi.indices("tetrahedronIndices");
  const auto out_tets = roi.indices("tetrahedronOutIndices");
  EXPECT_EQ(in_tets.size() + out_tets.size(), tetrahedra.size() / 4);
  EXPECT_FALSE(in_tets.empty());
  for (Index t : in_tets) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_LE(roi.points()[static_cast<std::size_t>(tetrahedra[static_cast<std::size_t>(4 * t + j)])].x(), 0.6);
    }
  }
  const auto in_roi = roi.indices("tetrahedraInROI");
  ASSERT_EQ(in_roi.size(), 4 * in_tets.size());
  EXPECT_EQ(in_roi[4], tetrahedra[static_cast<std::size_t>(4 * in_tets[1])]);
}

TEST(BoxRoi, StrictOffTakesElementsByTheirCentreAndBooleansReadAsSofaReadsThem) {
  // Edges given: along x from x = 0.5 to 1 (centre 0.75) and from 0 to 0.5 (centre 0.25).
  const std::string edges = "edges=\"93 94 92 93\"";  // (0.5, 0.5, 0.5)-(1, 0.5, 0.5) and (0, ...)-(0.5, ...)
  for (const char* strict : {"1", "true", "T", "12"}) {
    Roi roi("<BoxROI name=\"roi\" box=\"-1.1 -1.1 -1.1 0.6 1.1 1.1\" strict=\"" + std::string(strict) + "\" " + edges + "/>");
    EXPECT_EQ(roi.indices("edgeIndices"), std::vector<Index>{1}) << strict;
  }
  for (const char* loose : {"0", "false", "F", "0.9"}) {
    Roi roi("<BoxROI name=\"roi\" box=\"-1.1 -1.1 -1.1 0.8 1.1 1.1\" strict=\"" + std::string(loose) + "\" " + edges + "/>");
    EXPECT_EQ(roi.indices("edgeIndices"), (std::vector<Index>{0, 1})) << loose;
    EXPECT_EQ(roi("edgesInROI"), (Numbers{93, 94, 92, 93})) << loose;
  }
  Roi off("<BoxROI name=\"roi\" computeEdges=\"0\" " + edges + "/>");
  EXPECT_TRUE(off("edgeIndices").empty());
  Roi bad("<BoxROI name=\"roi\" strict=\"yes\" " + edges + "/>");
  try {
    bad("edgeIndices");
    ADD_FAILURE() << "strict=\"yes\" accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("strict = \"yes\""), std::string::npos) << error.what();
  }
}

TEST(SphereRoi, SelectsThePointsWithinAnyBallAndKeepsBoxRoisRules) {
  // Two balls of radius 0.6 (one radius for both): points within 0.6 of (-1, -1, -1) or (1, 1, 1).
  Roi roi("<SphereROI name=\"roi\" centers=\"-1 -1 -1  1 1 1\" radii=\"0.6\"/>");
  std::vector<Index> expected;
  for (std::size_t i = 0; i < roi.points().size(); ++i) {
    const Vec3<double>& p = roi.points()[i];
    if ((p - Vec3<double>(-1, -1, -1)).norm() <= 0.6 || (p - Vec3<double>(1, 1, 1)).norm() <= 0.6) {
      expected.push_back(static_cast<Index>(i));
    }
  }
  EXPECT_EQ(expected.size(), 8u);  // each corner and its three neighbours at 0.5
  EXPECT_EQ(roi.indices(), expected);
  EXPECT_EQ(roi.indices("pointIndices"), expected);  // SphereROI's other name
  EXPECT_EQ(roi.indices("indicesOut").size(), roi.points().size() - expected.size());
  // No tetrahedron has its four points within 0.6 of a corner; with radius 0.9 some do.
  EXPECT_TRUE(roi.indices("tetrahedronIndices").empty());
  Roi wider("<SphereROI name=\"roi\" centers=\"-1 -1 -1\" radii=\"0.9\"/>");
  const auto tetrahedra = wider.tetrahedra();
  const auto in_tets = wider.indices("tetrahedronIndices");
  EXPECT_FALSE(in_tets.empty());
  for (Index t : in_tets) {
    for (int j = 0; j < 4; ++j) {
      const Vec3<double>& p = wider.points()[static_cast<std::size_t>(tetrahedra[static_cast<std::size_t>(4 * t + j)])];
      EXPECT_LE((p - Vec3<double>(-1, -1, -1)).norm(), 0.9);
    }
  }
}

TEST(SphereRoi, EdgeAngleLeavesOutEdgesAlongTheDirection) {
  // Edges (0,1) along x and (0,5) along y, both within the ball around point 0 (-1, -1, -1).
  const std::string ball = "<SphereROI name=\"roi\" centers=\"-1 -1 -1\" radii=\"0.6\" edges=\"0 1  0 5\"";
  EXPECT_EQ(Roi(ball + "/>").indices("edgeIndices"), (std::vector<Index>{0, 1}));
  EXPECT_EQ(Roi(ball + " edgeAngle=\"10\" direction=\"1 0 0\"/>").indices("edgeIndices"), std::vector<Index>{1});
  Roi mismatched("<SphereROI name=\"roi\" centers=\"0 0 0  1 1 1  2 2 2\" radii=\"1 2\"/>");
  try {
    mismatched("indices");
    ADD_FAILURE() << "3 centres and 2 radii accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("3 centers but 2 radii"), std::string::npos) << error.what();
  }
}

TEST(RegionsOfInterest, BadShapesAreErrorsNamingTheData) {
  for (const auto& [roi, message] : std::initializer_list<std::pair<const char*, const char*>>{
           {"<BoxROI name=\"roi\" box=\"0 0 0 1 1\"/>", "box needs 6 numbers per box"},
           {"<BoxROI name=\"roi\" orientedBox=\"0 0 0 1 0 0 1 1 0\"/>", "orientedBox needs 10 numbers each"},
           {"<PlaneROI name=\"roi\" plane=\"0 0 0 1 0 0 1 1 0 1 2\"/>", "plane needs 10 numbers each"},
           {"<BoxROI name=\"roi\" edges=\"0 1 2\"/>", "edges needs 2 point indices per edge"}}) {
    Roi scene(roi);
    try {
      scene(std::string(roi).find("edges") != std::string::npos ? "edgeIndices" : "indices");
      ADD_FAILURE() << roi;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("roi.scn:1"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace fastcorot::scene_detail
