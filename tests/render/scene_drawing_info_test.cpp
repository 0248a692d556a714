// The scene builder keeps what the render layer draws (src/scene/scene_builder.cpp): each force
// field's `drawing` and drawColor1..4 in SOFA's RGBAColor syntax (sofa/type/RGBAColor.cpp:
// "r g b [a]", #rgb[a], #rrggbb[aa], nine names), and the BoxROI boxes.
#include "fastcorot/core/error.h"
#include "render/render_scenes.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using testing::build_test_scene;

std::string tetrahedron_with(const std::string& attributes) {
  return R"(<EulerImplicitSolver/><EigenSimplicialLDLT/>
  <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <UniformMass vertexMass="1"/>
  <FastTetrahedralCorotationalForceField )" +
         attributes + "/>";
}

TEST(SceneDrawingInfo, DefaultsAreTheSpecs) {
  const LoadedScene scene = build_test_scene(tetrahedron_with(""));
  const auto& drawing = scene.simulation.objects[0].force_field_drawing;
  ASSERT_EQ(drawing.size(), 1u);
  EXPECT_FALSE(drawing[0].drawing);
  EXPECT_EQ(drawing[0].colors[0], (Rgba{0, 0, 1, 1}));
  EXPECT_EQ(drawing[0].colors[1], (Rgba{0, 0.5f, 1, 1}));
  EXPECT_EQ(drawing[0].colors[2], (Rgba{0, 1, 1, 1}));
  EXPECT_EQ(drawing[0].colors[3], (Rgba{0.5f, 1, 1, 1}));
  EXPECT_TRUE(scene.simulation.objects[0].boxes.empty());
}

TEST(SceneDrawingInfo, ColoursInEverySofaSyntax) {
  const LoadedScene scene = build_test_scene(tetrahedron_with(
      R"(drawing="1" drawColor1="0.25 0.5 0.75" drawColor2="#ff000080" drawColor3="#0f0" drawColor4="magenta")"));
  const auto& drawing = scene.simulation.objects[0].force_field_drawing[0];
  EXPECT_TRUE(drawing.drawing);
  EXPECT_EQ(drawing.colors[0], (Rgba{0.25f, 0.5f, 0.75f, 1}));
  EXPECT_EQ(drawing.colors[1], (Rgba{1, 0, 0, 128.0f / 255.0f}));
  EXPECT_EQ(drawing.colors[2], (Rgba{0, 1, 0, 1}));
  EXPECT_EQ(drawing.colors[3], (Rgba{1, 0, 1, 1}));
}

TEST(SceneDrawingInfo, BadColoursNameTheAttributeAndLine) {
  for (const std::string value : {"1 2 3", "0.5 0.5", "#12345", "purple", "0 0 1 1 1", "nan 0 0"}) {
    try {
      build_test_scene(tetrahedron_with("drawColor2=\"" + value + "\""));
      ADD_FAILURE() << "accepted " << value;
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("test.scn:6"), std::string::npos) << message;
      EXPECT_NE(message.find("drawColor2 = \"" + value + "\""), std::string::npos) << message;
    }
  }
  EXPECT_THROW(build_test_scene(tetrahedron_with("drawing=\"maybe\"")), Error);
}

TEST(SceneDrawingInfo, BoxRoiBoxesAreKept) {
  const LoadedScene scene = build_test_scene(R"(<EulerImplicitSolver/><EigenSimplicialLDLT/>
  <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <UniformMass vertexMass="1"/>
  <FastTetrahedralCorotationalForceField/>
  <BoxROI name="two" box="1 1 1 -1 -1 -1  5 5 5 6 6 6"/>
  <FixedProjectiveConstraint indices="@two.indices"/>)");
  const auto& boxes = scene.simulation.objects[0].boxes;
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].min, Vec3<double>(-1, -1, -1));  // corners given in any order
  EXPECT_EQ(boxes[0].max, Vec3<double>(1, 1, 1));
  EXPECT_EQ(boxes[1].min, Vec3<double>(5, 5, 5));
  EXPECT_EQ(scene.simulation.objects[0].system.fixed,
            (std::vector<Index>{0, 1, 2, 3}));  // all in the first box
}

}  // namespace
}  // namespace fastcorot
