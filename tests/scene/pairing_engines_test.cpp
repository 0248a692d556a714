// NearestPointROI and IndexValueMapper (src/scene/scene_data_compute.cpp) read through the scene's
// data, against pairings and lists worked out by hand from SOFA's rules (NearestPointROI.inl:
// for each point of object2, the first nearest point of object1, kept when strictly closer than
// radius; IndexValueMapper.inl: the input list, grown with defaultValue, `value` at each index);
// and springs on an EdgeSetTopologyContainer's edges.
#include "scene/scene_data.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_data_text.h"
#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot::scene_detail {
namespace {

using Data = testing::SceneDataText;

TEST(NearestPointRoi, PairsEachSecondPointWithItsFirstNearestWithinTheRadius) {
  // object1: 0 (0,0,0), 1 (1,0,0), 2 (2,0,0). object2: 0 near 1, 1 midway between 0 and 1 (the
  // first of equals: 0), 2 too far from all, 3 on 2.
  Data data("<MechanicalObject name=\"a\" position=\"0 0 0  1 0 0  2 0 0\"/>"
            "<MechanicalObject name=\"b\" position=\"1.1 0 0  0.5 0 0  5 5 5  2 0 0\"/>"
            "<NearestPointROI name=\"np\" object1=\"@a\" object2=\"@b\" radius=\"0.6\"/>");
  EXPECT_EQ(data("np", "indices1"), (Numbers{1, 0, 2}));
  EXPECT_EQ(data("np", "indices2"), (Numbers{0, 1, 3}));
  EXPECT_EQ(data("np", "indexPairs"), (Numbers{0, 1, 1, 0, 0, 0, 1, 1, 0, 2, 1, 3}));
  EXPECT_EQ(data("np", "edges"), (Numbers{0, 1, 2, 3, 6, 7}));  // SOFA's (2 i2, 2 i2 + 1)
  const Numbers distances = data("np", "distances");
  ASSERT_EQ(distances.size(), 3u);
  EXPECT_NEAR(distances[0], 0.1, 1e-15);
  EXPECT_NEAR(distances[1], 0.5, 1e-15);
  EXPECT_EQ(distances[2], 0.0);
}

TEST(NearestPointRoi, FiltersItsCandidatesAndRefusesABadRadius) {
  Data data("<MechanicalObject name=\"a\" position=\"0 0 0  1 0 0  2 0 0\"/>"
            "<MechanicalObject name=\"b\" position=\"1.1 0 0  0.5 0 0\"/>"
            "<NearestPointROI name=\"np\" object1=\"@a\" object2=\"@b\" radius=\"10\" inputIndices1=\"0 2\" inputIndices2=\"0\"/>"
            "<NearestPointROI name=\"bad\" object1=\"@a\" object2=\"@b\" radius=\"0\"/>");
  // Point 1 of object1 is not a candidate: b's point 0 (x = 1.1) pairs with 2 (0.9 away) rather than 0 (1.1).
  EXPECT_EQ(data("np", "indices1"), (Numbers{2}));
  EXPECT_EQ(data("np", "indices2"), (Numbers{0}));
  EXPECT_THROW(data("bad", "indices1"), Error);
}

TEST(IndexValueMapper, SetsValuesAndGrowsWithTheDefault) {
  Data data("<IndexValueMapper name=\"first\" indices=\"1 3\" value=\"7\"/>"
            "<IndexValueMapper name=\"second\" inputValues=\"@first.outputValues\" indices=\"0 5\" value=\"2\" defaultValue=\"9\"/>");
  EXPECT_EQ(data("first", "outputValues"), (Numbers{1, 7, 1, 7}));
  EXPECT_EQ(data("second", "outputValues"), (Numbers{2, 7, 1, 7, 9, 2}));
}

TEST(EdgeSetTopologyContainer, GivesMeshSpringForceFieldItsEdges) {
  // Two points 2 apart, one spring of rest length 1 along x between them (stiffness 10): the
  // force on point 0 is +10 × (2 - 1) along x.
  LoadedScene scene = testing::build_scene_text(
      "<Node name=\"pair\"><EulerImplicitSolver/><CGLinearSolver/>"
      "<MechanicalObject name=\"p\" position=\"0 0 0  2 0 0\" rest_position=\"0 0 0  1 0 0\"/><UniformMass vertexMass=\"1\"/>"
      "<EdgeSetTopologyContainer edges=\"0 1\"/><MeshSpringForceField linesStiffness=\"10\" linesDamping=\"0\"/></Node>",
      "gravity=\"0 0 0\"");
  auto& system = scene.simulation.objects.at(0).system;
  std::vector<Vec3<double>> f(2);
  system.compute_force(system.state.position, f);
  EXPECT_NEAR(f[0].x(), 10.0, 1e-12);
  EXPECT_NEAR(f[1].x(), -10.0, 1e-12);
  EXPECT_NE(testing::scene_error("<Node name=\"pair\"><EulerImplicitSolver/><CGLinearSolver/>"
                                 "<MechanicalObject name=\"p\" position=\"0 0 0  2 0 0\"/><UniformMass vertexMass=\"1\"/>"
                                 "<EdgeSetTopologyContainer edges=\"0 4\"/><MeshSpringForceField linesStiffness=\"10\"/></Node>")
                .find("out of range"),
            std::string::npos);
}

TEST(ConstantForceField, OneForceGoesToEveryIndex) {
  LoadedScene scene = testing::build_scene_text(
      "<Node name=\"pts\"><EulerImplicitSolver/><CGLinearSolver/>"
      "<MechanicalObject name=\"p\" position=\"0 0 0  1 0 0  2 0 0\"/><UniformMass vertexMass=\"1\"/>"
      "<ConstantForceField forces=\"0.1 0 0\"/></Node>",
      "gravity=\"0 0 0\"");
  auto& system = scene.simulation.objects.at(0).system;
  std::vector<Vec3<double>> f(3);
  system.compute_force(system.state.position, f);
  for (const auto& fi : f) EXPECT_EQ(fi, Vec3<double>(0.1, 0, 0));
}

}  // namespace
}  // namespace fastcorot::scene_detail
