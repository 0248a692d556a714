// SOFA's volume engines (src/scene/volume_engines.cpp) read through the scene's data: a box's
// volume from its tetrahedra, its hexahedra, and its closed surface (triangles, quads), worked out
// by hand (the product of its sides); SOFA's defaults (the node's state and topology) and bad input.
#include "scene/scene_data.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

double volume_of(const std::string& body) {
  SceneNode scene = parse_scene_text("<Node name=\"root\">" + body + "</Node>", "volume.scn");
  std::vector<std::string> info, warnings;
  SceneData data(scene, info, &warnings);
  for (auto& component : data.root().components) {
    if (component->name() == "volume") {
      const Numbers v = data.data(*component, "volume");
      if (v.size() != 1) throw make_error("volume: ", v.size(), " numbers");
      return v[0];
    }
  }
  throw make_error("no engine named volume");
}

// A 2 × 3 × 4 box (volume 24) as a grid of 3 × 2 × 2 points moved by (1, 2, 3).
const std::string kGrid =
    "<RegularGridTopology name=\"grid\" n=\"3 2 2\" min=\"0 0 0\" max=\"2 3 4\"/><MechanicalObject name=\"state\" translation=\"1 2 3\"/>";

TEST(VolumeEngines, TetrahedraHexahedraAndClosedSurfacesGiveTheBoxsVolume) {
  EXPECT_NEAR(volume_of(kGrid + "<TetrahedronSetTopologyContainer name=\"tets\"/><Hexa2TetraTopologicalMapping input=\"@grid\" "
                                "output=\"@tets\"/><VolumeFromTetrahedrons name=\"volume\"/>"),
              24.0, 1e-12);
  // Hexahedra given, on the grid's points (SOFA's corner order), under the newer name.
  EXPECT_NEAR(volume_of(kGrid + "<VolumeFromVolumetricElements name=\"volume\" hexas=\"0 1 4 3 6 7 10 9  1 2 5 4 7 8 11 10\" "
                                "tetras=\"\"/>"),
              24.0, 1e-12);
  // A closed surface: the unit cube's six faces as quads (outward), then as twelve triangles, scaled by 2.
  const std::string cube = "<MechanicalObject name=\"state\" position=\"0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\" scale3d=\"2 2 2\"/>";
  const std::string quads = "0 3 2 1  4 5 6 7  0 1 5 4  2 3 7 6  1 2 6 5  0 4 7 3";
  EXPECT_NEAR(volume_of(cube + "<VolumeFromTriangles name=\"volume\" quads=\"" + quads + "\" triangles=\"\"/>"), 8.0, 1e-12);
  const std::string triangles = "0 3 2 0 2 1  4 5 6 4 6 7  0 1 5 0 5 4  2 3 7 2 7 6  1 2 6 1 6 5  0 4 7 0 7 3";
  EXPECT_NEAR(volume_of(cube + "<VolumeFromTriangles name=\"volume\" triangles=\"" + triangles + "\" quads=\"\"/>"), 8.0, 1e-12);
  // Inward faces give the same (SOFA takes the absolute value).
  const std::string inward = "0 2 3 0 1 2  4 6 5 4 7 6  0 5 1 0 4 5  2 7 3 2 6 7  1 6 2 1 5 6  0 7 4 0 3 7";
  EXPECT_NEAR(volume_of(cube + "<VolumeFromTriangles name=\"volume\" triangles=\"" + inward + "\" quads=\"\"/>"), 8.0, 1e-12);
}

TEST(VolumeEngines, BadInputIsAnErrorNamingIt) {
  try {
    volume_of(kGrid + "<VolumeFromTetrahedrons name=\"volume\" tetras=\"0 1 2 99\"/>");
    ADD_FAILURE() << "an index beyond the points accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("tetras names point 99 of 12"), std::string::npos) << error.what();
  }
  try {
    volume_of("<VolumeFromTriangles name=\"volume\"/>");
    ADD_FAILURE() << "no positions accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("no MechanicalObject at or above"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fastcorot::scene_detail
