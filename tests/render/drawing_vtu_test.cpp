// The drawn tetrahedra as a VTK grid: four shrunk corners and four coloured triangles per drawn
// tetrahedron, displacement interpolated, and a file that read_vtu reads back.
#include "fastcorot/render/drawing_vtu.h"
#include "fastcorot/io/mesh_readers.h"

#include "fastcorot/render/tetrahedron_drawing.h"
#include "render/render_scenes.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace fastcorot {
namespace {

using testing::build_test_scene;

const VtuField& field(const std::vector<VtuField>& fields, const std::string& name) {
  for (const auto& f : fields) {
    if (f.name == name) return f;
  }
  throw std::runtime_error("no field " + name);
}

TEST(DrawingVtu, OneDrawnTetrahedron) {
  LoadedScene scene = build_test_scene(testing::kDrawnTetrahedron);
  auto& object = scene.simulation.objects[0];
  for (auto& p : object.system.state.position)
    p += Vec3<double>(0, 0, 3);  // displaced by (0, 0, 3)
  const DrawnTetrahedraGrid grid = drawn_tetrahedra_grid(object, TetrahedronDrawing::scene);
  ASSERT_EQ(grid.points.size(), 4u);
  EXPECT_EQ(grid.triangles.vtk_cell_type, 5);
  EXPECT_EQ(grid.triangles.connectivity, (std::vector<Index>{0, 1, 2, 1, 2, 3, 2, 3, 0, 3, 0, 1}));
  const auto& x = object.system.state.position;
  const auto corners = shrunk_tetrahedron<double>({x[0], x[1], x[2], x[3]});
  for (int j = 0; j < 4; ++j) EXPECT_EQ(grid.points[static_cast<std::size_t>(j)], corners[j]);
  EXPECT_EQ(field(grid.point_fields, "displacement").values,
            (std::vector<double>{0, 0, 3, 0, 0, 3, 0, 0, 3, 0, 0, 3}));
  EXPECT_EQ(field(grid.cell_fields, "drawColor").values,
            (std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0}));
  EXPECT_EQ(field(grid.cell_fields, "opacity").values, (std::vector<double>{1, 1, 1, 1}));
  EXPECT_EQ(field(grid.cell_fields, "face").values, (std::vector<double>{3, 0, 1, 2}));
  EXPECT_EQ(field(grid.cell_fields, "tetrahedron").values, (std::vector<double>{0, 0, 0, 0}));
}

TEST(DrawingVtu, EmptyWhenNothingIsDrawn) {
  const LoadedScene scene = build_test_scene(testing::small_beam("false"));
  EXPECT_TRUE(
      drawn_tetrahedra_grid(scene.simulation.objects[0], TetrahedronDrawing::scene).empty());
  EXPECT_TRUE(drawn_tetrahedra_grid(scene.simulation.objects[0], TetrahedronDrawing::none).empty());
  const DrawnTetrahedraGrid all =
      drawn_tetrahedra_grid(scene.simulation.objects[0], TetrahedronDrawing::all);
  EXPECT_EQ(all.points.size(), 4u * 12u);
  EXPECT_EQ(all.triangles.connectivity.size(), 3u * 4u * 12u);
}

TEST(DrawingVtu, WrittenFileReadsBack) {
  const LoadedScene scene = build_test_scene(testing::small_beam("true"));
  const DrawnTetrahedraGrid grid =
      drawn_tetrahedra_grid(scene.simulation.objects[0], TetrahedronDrawing::scene);
  const auto path = testing::unique_temp_path("drawing_vtu_test.vtu");
  write_drawn_tetrahedra_vtu(path, grid);
  const MeshData read = read_vtu(path);
  std::filesystem::remove(path);
  EXPECT_EQ(read.points, grid.points);
  EXPECT_EQ(read.triangles.size(), 4u * 12u);
  EXPECT_TRUE(read.tetrahedra.empty());
}

}  // namespace
}  // namespace fastcorot
