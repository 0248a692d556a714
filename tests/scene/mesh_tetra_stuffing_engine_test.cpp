// SOFA's MeshTetraStuffing as a scene engine (src/scene/mesh_tetra_stuffing_engine.cpp): its data
// read through links as a TetrahedronSetTopologyContainer reads them. The expected mesh is the
// hand-derived one of tests/topology/mesh_tetra_stuffing_test.cpp (one lattice point inside: its
// 24 tetrahedra over 15 points).
#include "scene/scene_data.h"
#include "support/scene_data_text.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

// The unit cube as 12 outward triangles.
const char* kCube =
    "inputPoints=\"0 0 0  1 0 0  0 1 0  1 1 0  0 0 1  1 0 1  0 1 1  1 1 1\" "
    "inputTriangles=\"0 2 3  0 3 1  4 5 7  4 7 6  0 1 5  0 5 4  2 6 7  2 7 3  0 4 6  0 6 2  1 3 7  1 7 5\"";

// The engine and a container linked to its outputs.
class Stuffing : public testing::SceneDataText {
 public:
  explicit Stuffing(const std::string& attributes)
      : SceneDataText("<MeshTetraStuffing name=\"stuffing\" " + attributes +
                          "/><TetrahedronSetTopologyContainer name=\"volume\" points=\"@stuffing.outputPoints\" "
                          "tetrahedra=\"@stuffing.outputTetras\"/>",
                      "stuffing.scn") {}
};

TEST(MeshTetraStuffingEngine, OutputsTheStuffedMeshToLinks) {
  Stuffing s(std::string(kCube) + " size=\"-1\" vbbox=\"-0.0137 -0.0211 -0.0173 1.0119 1.0231 1.0157\"");
  const Numbers tetrahedra = s("volume", "tetrahedra");
  ASSERT_EQ(tetrahedra.size(), 4u * 24);
  EXPECT_EQ((Numbers{tetrahedra[0], tetrahedra[1], tetrahedra[2], tetrahedra[3]}), (Numbers{3, 2, 9, 7}));
  EXPECT_EQ(s("stuffing", "outputPoints").size(), 3u * 15);
  EXPECT_EQ(s("stuffing", "outputTetrahedra"), tetrahedra);
  EXPECT_EQ(s("stuffing", "vbbox"), (Numbers{-0.0137, -0.0211, -0.0173, 1.0119, 1.0231, 1.0157}));
}

TEST(MeshTetraStuffingEngine, WithoutVbboxTheBoxIsTheSurfacesGrownByOnePercent) {
  Stuffing s(std::string(kCube) + " splitTetras=\"1\" snapPoints=\"1\"");
  const Numbers box = s("stuffing", "vbbox");
  const Numbers expected = {-0.01, -0.01, -0.01, 1.01, 1.01, 1.01};
  ASSERT_EQ(box.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(box[k], expected[k]);
  EXPECT_FALSE(s("stuffing", "outputTetrahedra").empty());
}

TEST(MeshTetraStuffingEngine, AnEmptySurfaceIsAnErrorNamingTheComponent) {
  Stuffing s("size=\"-4\"");
  try {
    s("volume", "tetrahedra");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("MeshTetraStuffing 'stuffing'"), std::string::npos) << m;
    EXPECT_NE(m.find("empty input surface"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace fastcorot::scene_detail
