// SOFA's SubsetTopology (src/scene/subset_topology.cpp) read through the scene's data, as links to
// its outputs read it. Expected outputs are worked out by hand from SOFA's rules
// (SubsetTopology.inl, master 2a278d891f) on a small mesh of 8 points: inside the box
// x in [-0.5, 0.5] are points 0, 2, 3 and 6; tetrahedron 0 (0 1 2 3) and 1 (1 4 5 2) cross it,
// 2 (0 2 3 6) is inside, 3 (1 4 5 7) outside.
#include "scene/scene_data.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

const char* kPoints = "0 0 0  1 0 0  0 1 0  0 0 1  2 0 0  2 1 1  -0.3 0.6 0.6  2 1 0";
const std::vector<Vec3<double>> kP = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                                      {2, 0, 0}, {2, 1, 1}, {-0.3, 0.6, 0.6}, {2, 1, 0}};
const char* kTetrahedra = "0 1 2 3  1 4 5 2  0 2 3 6  1 4 5 7";

// The mesh (a MechanicalObject and a tetrahedron container) and `subset` in the same node.
class Subset {
 public:
  explicit Subset(const std::string& subset) {
    scene_ = parse_scene_text(std::string("<Node name=\"root\"><MechanicalObject name=\"state\" position=\"") + kPoints +
                                  "\"/><TetrahedronSetTopologyContainer name=\"tets\" position=\"" + kPoints +
                                  "\" tetrahedra=\"" + kTetrahedra + "\"/>" + subset + "</Node>",
                              "subset.scn");
    data_ = std::make_unique<SceneData>(scene_, info_, &warnings_);
  }
  Numbers operator()(const std::string& name) {
    for (auto& component : data_->root().components) {
      if (component->name() == "subset") return data_->data(*component, name);
    }
    throw make_error("no subset");
  }
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  SceneNode scene_;
  std::vector<std::string> info_, warnings_;
  std::unique_ptr<SceneData> data_;
};

Numbers points_of(const std::vector<int>& which) {
  Numbers out;
  for (int i : which) out.insert(out.end(), {kP[static_cast<std::size_t>(i)].x(), kP[static_cast<std::size_t>(i)].y(), kP[static_cast<std::size_t>(i)].z()});
  return out;
}

TEST(SubsetTopology, SelectsPointsAndElementsInsideTheBoxWithGlobalIndices) {
  Subset s("<SubsetTopology name=\"subset\" box=\"-0.5 -1 -1 0.5 2 2\" edges=\"0 2  1 4  2 6\" "
           "triangles=\"0 2 3  1 4 5  0 1 2\"/>");
  EXPECT_EQ(s("indices"), (Numbers{0, 2, 3, 6}));
  EXPECT_EQ(s("pointsInROI"), points_of({0, 2, 3, 6}));
  EXPECT_EQ(s("pointsOutROI"), points_of({1, 4, 5, 7}));
  EXPECT_EQ(s("tetrahedronIndices"), (Numbers{2}));
  EXPECT_EQ(s("tetrahedraInROI"), (Numbers{0, 2, 3, 6}));
  EXPECT_EQ(s("tetrahedraOutROI"), (Numbers{0, 1, 2, 3, 1, 4, 5, 2, 1, 4, 5, 7}));
  EXPECT_EQ(s("edgeIndices"), (Numbers{0, 2}));
  EXPECT_EQ(s("edgesOutROI"), (Numbers{1, 4}));
  EXPECT_EQ(s("triangleIndices"), (Numbers{0}));
  EXPECT_EQ(s("trianglesOutROI"), (Numbers{1, 4, 5, 0, 1, 2}));
  EXPECT_EQ(s("nbrborder"), (Numbers{0}));
  EXPECT_TRUE(s.warnings().empty());
}

TEST(SubsetTopology, LocalIndicesPutTheBorderPointsFirstInBothSubMeshes) {
  // Border (first box, points of tetrahedra 0 and 1 inside it): 0, 2, 3, numbered 0 1 2 in both
  // lists; then inside point 6 -> 3, outside points 1 4 5 7 -> 3 4 5 6.
  Subset s("<SubsetTopology name=\"subset\" box=\"-0.5 -1 -1 0.5 2 2\" localIndices=\"1\" edges=\"0 2  1 4  2 6\" "
           "triangles=\"0 2 3  1 4 5  0 1 2\"/>");
  EXPECT_EQ(s("nbrborder"), (Numbers{3}));
  EXPECT_EQ(s("indices"), (Numbers{0, 2, 3, 6}));
  EXPECT_EQ(s("pointsInROI"), points_of({0, 2, 3, 6}));
  EXPECT_EQ(s("pointsOutROI"), points_of({0, 2, 3, 1, 4, 5, 7}));
  EXPECT_EQ(s("tetrahedraInROI"), (Numbers{0, 1, 2, 3}));
  EXPECT_EQ(s("tetrahedraOutROI"), (Numbers{0, 3, 1, 2, 3, 4, 5, 1, 3, 4, 5, 6}));
  EXPECT_EQ(s("edgesInROI"), (Numbers{0, 1, 1, 3}));
  EXPECT_EQ(s("edgesOutROI"), (Numbers{3, 4}));
  EXPECT_EQ(s("trianglesInROI"), (Numbers{0, 1, 2}));
  EXPECT_EQ(s("trianglesOutROI"), (Numbers{3, 4, 5, 0, 3, 1}));
}

TEST(SubsetTopology, ReversedBoundsAreSwappedAndReadFromTheNodesStateAndTopology) {
  // No rest_position or tetrahedra given: the MechanicalObject's position and the container's.
  Subset s("<SubsetTopology name=\"subset\" box=\"0.5 2 2 -0.5 -1 -1\"/>");
  EXPECT_EQ(s("indices"), (Numbers{0, 2, 3, 6}));
  EXPECT_EQ(s("tetrahedronIndices"), (Numbers{2}));
}

TEST(SubsetTopology, SpheresIncludeTheirBoundary) {
  // Distance <= 1 from the origin: 0, 1 and 2 and 3 (at 1), 6 (at 0.9).
  Subset s("<SubsetTopology name=\"subset\" centers=\"0 0 0\" radii=\"1\"/>");
  EXPECT_EQ(s("indices"), (Numbers{0, 1, 2, 3, 6}));
  EXPECT_EQ(s("tetrahedronIndices"), (Numbers{0, 2}));
}

TEST(SubsetTopology, AnElementIsInsideWhenAllItsPointsAreInOneSameRegion) {
  // Two small boxes, one around point 0 and one around point 1: both points are selected, the edge
  // between them is not.
  Subset s("<SubsetTopology name=\"subset\" box=\"-0.1 -0.1 -0.1 0.1 0.1 0.1  0.9 -0.1 -0.1 1.1 0.1 0.1\" "
           "edges=\"0 1\"/>");
  EXPECT_EQ(s("indices"), (Numbers{0, 1}));
  EXPECT_EQ(s("edgeIndices"), (Numbers{}));
  EXPECT_EQ(s("edgesOutROI"), (Numbers{0, 1}));
}

TEST(SubsetTopology, TetrahedraInputKeepsTheListedTetrahedraAndRebuildsThePointLists) {
  // indices: the box's points (0 2 3 6), then the listed tetrahedra's points met first (0 1 2 3,
  // then 6); points out: those of the other tetrahedra in the order met (1 4 5 2, then 7).
  Subset s("<SubsetTopology name=\"subset\" box=\"-0.5 -1 -1 0.5 2 2\" tetrahedraInput=\"2 0\"/>");
  EXPECT_EQ(s("indices"), (Numbers{0, 2, 3, 6, 0, 1, 2, 3, 6}));
  EXPECT_EQ(s("pointsInROI"), points_of({0, 1, 2, 3, 6}));
  EXPECT_EQ(s("pointsOutROI"), points_of({1, 4, 5, 2, 7}));
  EXPECT_EQ(s("tetrahedronIndices"), (Numbers{0, 2}));
  EXPECT_EQ(s("tetrahedraInROI"), (Numbers{0, 1, 2, 3, 0, 2, 3, 6}));
  EXPECT_EQ(s("tetrahedraOutROI"), (Numbers{1, 4, 5, 2, 1, 4, 5, 7}));
}

TEST(SubsetTopology, LocalIndicesOnALoadedMeshGiveTwoConsistentSubMeshes) {
  // SOFA's refining-mesh scene in small: a Gmsh cylinder (radius 1, z in [0, 1]) read through src,
  // cut at z = 0.5. Checked by properties of SOFA's rule: each output tetrahedron, read through its
  // sub-mesh's points, is the input tetrahedron it comes from; the border points open both point
  // lists; every point of a tetrahedron inside is in the box.
  SceneNode scene = parse_scene_text(
      "<Node name=\"root\"><MeshGmshLoader name=\"loader\" filename=\"meshes/cylinder.msh\"/>"
      "<SubsetTopology name=\"subset\" src=\"@loader\" rest_position=\"@loader.position\" box=\"-2 -2 -0.1 2 2 0.5\" "
      "localIndices=\"1\"/></Node>",
      std::string(FASTCOROT_SOURCE_DIR) + "/examples/subset.scn");
  std::vector<std::string> info, warnings;
  SceneData data(scene, info, &warnings);
  Component& loader = *data.root().components[0];
  Component& subset = *data.root().components[1];
  const auto x0 = points_from(data.data(loader, "position"), loader, "position");
  const Numbers& tetrahedra = data.data(loader, "tetrahedra");
  const auto in = points_from(data.data(subset, "pointsInROI"), subset, "pointsInROI");
  const auto out = points_from(data.data(subset, "pointsOutROI"), subset, "pointsOutROI");
  const Numbers& in_tetrahedra = data.data(subset, "tetrahedraInROI");
  const Numbers& out_tetrahedra = data.data(subset, "tetrahedraOutROI");
  const Numbers& selected = data.data(subset, "tetrahedronIndices");
  const auto border = static_cast<std::size_t>(data.data(subset, "nbrborder").at(0));
  ASSERT_GT(border, 0u);
  ASSERT_GT(selected.size(), 0u);
  ASSERT_LT(selected.size(), tetrahedra.size() / 4);
  ASSERT_EQ(in_tetrahedra.size(), 4 * selected.size());
  ASSERT_EQ(out_tetrahedra.size() + in_tetrahedra.size(), tetrahedra.size());
  for (std::size_t b = 0; b < border; ++b) EXPECT_EQ(in[b], out[b]);
  std::size_t next_in = 0, next_out = 0;
  for (std::size_t t = 0; t < tetrahedra.size() / 4; ++t) {
    const bool inside = next_in < selected.size() && selected[next_in] == static_cast<double>(t);
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec3<double>& global = x0[static_cast<std::size_t>(tetrahedra[4 * t + k])];
      if (inside) {
        EXPECT_EQ(in.at(static_cast<std::size_t>(in_tetrahedra[4 * next_in + k])), global) << "tetrahedron " << t;
        EXPECT_LE(global.z(), 0.5);
      } else {
        EXPECT_EQ(out.at(static_cast<std::size_t>(out_tetrahedra[4 * next_out + k])), global) << "tetrahedron " << t;
      }
    }
    ++(inside ? next_in : next_out);
  }
}

TEST(SubsetTopology, BadInputIsAnErrorNamingTheComponentAndTheData) {
  const auto message = [](const std::string& subset, const std::string& output) {
    try {
      Subset s(subset);
      s(output);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string box = message("<SubsetTopology name=\"subset\" box=\"0 0 0 1 1\"/>", "indices");
  EXPECT_NE(box.find("SubsetTopology 'subset'"), std::string::npos) << box;
  EXPECT_NE(box.find("box needs 6 numbers"), std::string::npos) << box;
  const std::string radii = message("<SubsetTopology name=\"subset\" centers=\"0 0 0  1 1 1\" radii=\"1\"/>", "indices");
  EXPECT_NE(radii.find("2 centers but 1 radii"), std::string::npos) << radii;
  const std::string tetra = message("<SubsetTopology name=\"subset\" tetrahedra=\"0 1 2 9\"/>", "indices");
  EXPECT_NE(tetra.find("tetrahedra: element 0 has point 9"), std::string::npos) << tetra;
  const std::string rigid = message("<SubsetTopology name=\"subset\" template=\"Rigid3\"/>", "indices");
  EXPECT_NE(rigid.find("template Rigid3"), std::string::npos) << rigid;
}

}  // namespace
}  // namespace fastcorot::scene_detail
