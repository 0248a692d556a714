// GiD ASCII meshes as SOFA's GIDMeshLoader reads them: points in file order (their ids unread),
// node numbers from 1, keywords in any case; malformed files give an error naming the line.
#include "fastcorot/io/mesh_readers.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

const std::string kTwoTetrahedra =
    "MESH dimension 3 ElemType Tetrahedra Nnode 4\n"
    "Coordinates\n"
    "  7  0 0 0\n"
    "  3  1 0 0\n"
    "  1  0 1 0\n"
    "  2  0 0 1\n"
    "  9  0 0 -2\n"
    "End Coordinates\n"
    "\n"
    "elements\n"
    "1 1 2 3 4\n"
    "2 1 3 2 5\n"
    "end elements\n";

std::string error_of(const std::string& text) {
  try {
    read_gid_bytes(text, "t.gidmsh");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(GidReader, PointsInFileOrderAndNodesFromOne) {
  const MeshData mesh = read_gid_bytes(kTwoTetrahedra, "t.gidmsh");
  ASSERT_EQ(mesh.points.size(), 5u);
  EXPECT_EQ(mesh.points[1], Vec3<double>(1, 0, 0));
  EXPECT_EQ(mesh.points[4], Vec3<double>(0, 0, -2));
  ASSERT_EQ(mesh.tetrahedra.size(), 2u);
  EXPECT_EQ(mesh.tetrahedra[0], (Tetrahedron{0, 1, 2, 3}));
  EXPECT_EQ(mesh.tetrahedra[1], (Tetrahedron{0, 2, 1, 4}));
}

TEST(GidReader, QuadraticTetrahedraKeepTheirCornersAndTrianglesAreSurfaces) {
  const MeshData quadratic = read_gid_bytes(
      "MESH dimension 3 ElemType Tetrahedra Nnode 10\nCoordinates\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\nEnd Coordinates\n"
      "Elements\n1 1 2 3 4 1 1 1 1 1 1\nEnd Elements\n",
      "q.gidmsh");
  EXPECT_EQ(quadratic.tetrahedra.at(0), (Tetrahedron{0, 1, 2, 3}));
  const MeshData flat = read_gid_bytes(
      "MESH dimension 2 ElemType Triangle Nnode 3\nCoordinates\n1 0 0\n2 1 0\n3 0 1\nEnd Coordinates\nElements\n1 1 2 3\nEnd Elements\n",
      "f.gidmsh");
  EXPECT_TRUE(flat.tetrahedra.empty());
  EXPECT_EQ(flat.triangles.at(0), (Triangle{0, 1, 2}));
  EXPECT_EQ(flat.points[2], Vec3<double>(0, 1, 0));
}

TEST(GidReader, MalformedFilesNameTheLine) {
  EXPECT_NE(error_of("Coordinates\n").find("t.gidmsh:1: expected a header line"), std::string::npos);
  EXPECT_NE(error_of("MESH dimension 3 ElemType Hexahedra Nnode 8\n").find("ElemType Hexahedra"), std::string::npos);
  std::string bad = kTwoTetrahedra;
  bad.replace(bad.find("2 1 3 2 5"), 9, "2 1 3 2 6");
  EXPECT_NE(error_of(bad).find("t.gidmsh:12: element 2: node 6 out of range [1, 5]"), std::string::npos);
  EXPECT_NE(error_of(kTwoTetrahedra.substr(0, kTwoTetrahedra.find("End Coordinates"))).find("unexpected end of file in Coordinates"), std::string::npos);
  std::string nan = kTwoTetrahedra;
  nan.replace(nan.find("  3  1 0 0"), 10, "  3  1 x 0");
  EXPECT_NE(error_of(nan).find("point 3: expected 3 coordinates"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
