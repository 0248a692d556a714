// PointsFromIndices (src/scene/points_from_indices.cpp) read through the scene's data, against
// lists picked by hand from SOFA's rule (PointsFromIndices.inl, master 2a278d891f): position[i] for
// each i of indices in order, a point already listed (every coordinate within 1e-6) left out; the
// node's state's position when none is given.
#include "scene/scene_data.h"

#include "fastcorot/core/error.h"

#include "../support/scene_data_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot::scene_detail {
namespace {

using Data = testing::SceneDataText;

std::string error_of(const std::string& body) {
  try {
    Data data(body);
    data("p", "indices_position");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(PointsFromIndices, TakesThePointsInIndexOrderEachOnce) {
  // Points 0..4; point 3 is point 1 moved by 1e-7 (the same point for SOFA), point 4 by 1e-5 (not).
  Data data("<PointsFromIndices name=\"p\" position=\"0 0 0  1 2 3  4 5 6  1.0000001 2 3  1.00001 2 3\""
            " indices=\"2 0 2 1 3 4\"/>");
  EXPECT_EQ(data("p", "indices_position"), (Numbers{4, 5, 6, 0, 0, 0, 1, 2, 3, 1.00001, 2, 3}));
}

TEST(PointsFromIndices, ReadsTheNodesStateByDefaultAndFeedsAState) {
  // InextensiblePendulum.scn's form: the engine in a child node, the state's position linked; and
  // with no position, the state of the node above. PointsFromIndices.scn's: a state fed by it, in a
  // node below (in the engine's own node that state would be the one it reads: a cycle).
  const std::string body =
      "<MechanicalObject name=\"dofs\" position=\"0 0 0  1 0 0  2 0 0\" translation=\"0 1 0\"/>"
      "<Node name=\"visual\">"
      "<PointsFromIndices name=\"linked\" position=\"@../dofs.position\" indices=\"2\"/>"
      "<PointsFromIndices name=\"implicit\" indices=\"1 2\"/>"
      "<Node name=\"selection\"><MechanicalObject name=\"selected\" position=\"@../implicit.indices_position\"/></Node>"
      "</Node>";
  SceneNode scene = parse_scene_text("<Node name=\"root\">" + body + "</Node>", "test.scn");
  std::vector<std::string> info, warnings;
  SceneData data(scene, info, &warnings);
  GraphNode& visual = *data.root().children.at(0);
  const auto named = [&](const std::string& name) -> Component& {
    for (auto& c : visual.components) {
      if (c->name() == name) return *c;
    }
    throw make_error("no ", name);
  };
  EXPECT_EQ(data.data(named("linked"), "indices_position"), (Numbers{2, 1, 0}));
  EXPECT_EQ(data.data(named("implicit"), "indices_position"), (Numbers{1, 1, 0, 2, 1, 0}));
  EXPECT_EQ(data.data(*visual.children.at(0)->components.at(0), "position"), (Numbers{1, 1, 0, 2, 1, 0}));
}

TEST(PointsFromIndices, BadInputIsAnErrorNamingTheEngine) {
  const std::string range = error_of("<PointsFromIndices name=\"p\" position=\"0 0 0  1 0 0\" indices=\"0 2\"/>");
  EXPECT_NE(range.find("PointsFromIndices 'p'"), std::string::npos) << range;
  EXPECT_NE(range.find("out of range"), std::string::npos) << range;
  const std::string sizes = error_of("<PointsFromIndices name=\"p\" position=\"0 0 0  1 0\" indices=\"0\"/>");
  EXPECT_NE(sizes.find("PointsFromIndices 'p'"), std::string::npos) << sizes;
  EXPECT_NE(sizes.find("position"), std::string::npos) << sizes;
  const std::string negative = error_of("<PointsFromIndices name=\"p\" position=\"0 0 0\" indices=\"-1\"/>");
  EXPECT_NE(negative.find("indices"), std::string::npos) << negative;
  const std::string tmpl = error_of("<PointsFromIndices name=\"p\" template=\"Rigid3d\" position=\"0 0 0\" indices=\"0\"/>");
  EXPECT_NE(tmpl.find("Rigid3d"), std::string::npos) << tmpl;
}

}  // namespace
}  // namespace fastcorot::scene_detail
