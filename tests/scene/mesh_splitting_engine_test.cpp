// SOFA's MeshSplittingEngine (src/scene/mesh_splitting_engine.cpp) read through the scene's data.
// Expected outputs worked out by hand from SOFA's rules (MeshSplittingEngine.inl, master
// 2a278d891f): the first sub-mesh that lists a point (directly or by an element) takes it, the rest
// go to the last; each sub-mesh keeps the input order.
#include "scene/scene_data.h"
#include "support/scene_data_text.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

// A mesh of four tetrahedra and the engine `split` (named "split") on it.
class Split : public testing::SceneDataText {
 public:
  explicit Split(const std::string& split)
      : SceneDataText("<TetrahedronSetTopologyContainer name=\"mesh\" "
                      "position=\"0 0 0  1 0 0  0 1 0  0 0 1  2 0 0  2 1 1  3 3 3  2 1 0\" "
                      "tetrahedra=\"0 1 2 3  1 4 5 2  0 2 3 6  1 4 5 7\"/>" + split,
                      "split.scn") {}
  Numbers operator()(const std::string& name) { return SceneDataText::operator()("split", name); }
};

TEST(MeshSplittingEngine, TheFirstSubMeshToListAPointTakesItAndTheRestGoesLast) {
  // Sub-mesh 1: tetrahedron 2 (points 0 2 3 6) and point 4; sub-mesh 2: points 4 (taken by 1) and
  // 5; the rest: 1 and 7.
  Split s("<MeshSplittingEngine name=\"split\" src=\"@mesh\" nbInputs=\"2\" tetrahedronIndices1=\"2\" indices1=\"4\" "
          "indices2=\"4 5\"/>");
  EXPECT_EQ(s("position1"), (Numbers{0, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 0, 3, 3, 3}));
  EXPECT_EQ(s("position2"), (Numbers{2, 1, 1}));
  EXPECT_EQ(s("position3"), (Numbers{1, 0, 0, 2, 1, 0}));
  EXPECT_EQ(s("indexPairs"), (Numbers{0, 0, 2, 0, 0, 1, 0, 2, 0, 3, 1, 0, 0, 4, 2, 1}));
  EXPECT_TRUE(s.warnings().empty()) << s.warnings().front();  // indices1, indices2, ... are known
}

TEST(MeshSplittingEngine, WithoutListsEveryPointIsInTheLastSubMesh) {
  Split s("<MeshSplittingEngine name=\"split\" src=\"@mesh\"/>");
  EXPECT_EQ(s("position1").size(), 24u);
  EXPECT_EQ(s("indexPairs"), (Numbers{0, 0, 0, 1, 0, 2, 0, 3, 0, 4, 0, 5, 0, 6, 0, 7}));
}

TEST(MeshSplittingEngine, BadInputIsAnErrorNamingTheComponentAndTheData) {
  const auto message = [](const std::string& split, const std::string& output) {
    try {
      Split s(split);
      s(output);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string element =
      message("<MeshSplittingEngine name=\"split\" src=\"@mesh\" nbInputs=\"1\" tetrahedronIndices1=\"4\"/>", "position1");
  EXPECT_NE(element.find("MeshSplittingEngine 'split'"), std::string::npos) << element;
  EXPECT_NE(element.find("tetrahedronIndices1 has element 4 of 4"), std::string::npos) << element;
  const std::string point = message("<MeshSplittingEngine name=\"split\" src=\"@mesh\" nbInputs=\"1\" indices1=\"8\"/>", "indexPairs");
  EXPECT_NE(point.find("indices1 reaches point 8"), std::string::npos) << point;
  const std::string output = message("<MeshSplittingEngine name=\"split\" src=\"@mesh\" nbInputs=\"1\"/>", "position3");
  EXPECT_NE(output.find("no output position3"), std::string::npos) << output;
}

}  // namespace
}  // namespace fastcorot::scene_detail
