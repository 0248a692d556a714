// Tests of read_mesh_file: dispatch on the extension, the same mesh from every format that gmsh,
// meshio and VTK wrote (tests/data/meshes, see its README.md), robustness against truncated and
// corrupted files (every outcome is a result or a fastcorot::Error, never a crash or another
// exception), and the cylinder validation mesh examples/meshes/cylinder.msh.
#include "fastcorot/io/mesh_readers.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

std::filesystem::path meshes_dir() {
  return std::filesystem::path(FASTCOROT_TEST_DATA_DIR) / "meshes";
}

std::filesystem::path temp_dir() {
  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   ("fastcorot_mesh_file_" +
                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::create_directories(dir);
  return dir;
}

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// Removes the old file first: rewriting a truncated file makes ext4 flush it on close (its
// auto_da_alloc heuristic), which slows the thousands of rewrites below by a factor of ten.
void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::filesystem::remove(path);
  std::ofstream(path, std::ios::binary) << bytes;
}

// Every mesh file of tests/data/meshes.
std::vector<std::filesystem::path> test_mesh_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(meshes_dir())) {
    const std::string extension = entry.path().extension().string();
    if (extension == ".msh" || extension == ".vtk" || extension == ".vtu")
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(MeshFile, EveryFormatOfTheBoxGivesTheSameMesh) {
  // The reference: gmsh's binary 4.1 file (coordinates stored as doubles).
  const MeshData reference = read_mesh_file(meshes_dir() / "box_gmsh_v41_binary.msh");
  ASSERT_EQ(reference.points.size(), 44u);
  ASSERT_EQ(reference.tetrahedra.size(), 90u);
  ASSERT_EQ(reference.triangles.size(), 84u);
  int compared = 0;
  for (const auto& path : test_mesh_files()) {
    const std::string name = path.filename().string();
    if (name.rfind("box_", 0) != 0) continue;
    SCOPED_TRACE(name);
    const MeshData mesh = read_mesh_file(path);
    ASSERT_EQ(mesh.points.size(), reference.points.size());
    // Float32 files keep 7 digits; VTK's legacy ASCII writer keeps 11, meshio's ASCII 12.
    const double tolerance = name.find("float32") != std::string::npos ? 1e-7 : 1e-10;
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
      EXPECT_LE((mesh.points[i] - reference.points[i]).norm(), tolerance) << "point " << i;
    }
    EXPECT_EQ(mesh.tetrahedra, reference.tetrahedra);
    EXPECT_EQ(mesh.triangles, reference.triangles);
    ++compared;
  }
  EXPECT_EQ(compared, 26);  // 5 gmsh + 9 meshio + 12 VTK files
}

TEST(MeshFile, ExtensionChoosesTheReaderWhateverItsCase) {
  const auto dir = temp_dir();
  for (const char* name :
       {"box_gmsh_v41_ascii.msh", "box_vtk_v51_ascii.vtk", "box_vtk_ascii.vtu"}) {
    std::string upper = name;
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return std::toupper(c); });
    std::filesystem::copy_file(meshes_dir() / name, dir / upper,
                               std::filesystem::copy_options::overwrite_existing);
    EXPECT_EQ(read_mesh_file(dir / upper).tetrahedra.size(), 90u) << upper;
  }
}

TEST(MeshFile, AVtkXmlFileNamedVtkIsReadAsSofasLoaderReadsIt) {
  // SoftRobots ships VTK XML meshes named .vtk (Tentacle.vtk); SOFA's MeshVTKLoader reads them.
  const auto dir = temp_dir();
  std::filesystem::copy_file(meshes_dir() / "box_vtk_ascii.vtu", dir / "xml_named.vtk",
                             std::filesystem::copy_options::overwrite_existing);
  const MeshData xml = read_mesh_file(dir / "xml_named.vtk");
  EXPECT_EQ(xml.tetrahedra, read_mesh_file(meshes_dir() / "box_vtk_ascii.vtu").tetrahedra);
  EXPECT_EQ(xml.tetrahedra.size(), 90u);
}

TEST(MeshFile, UnknownExtensionAndMissingFileAreErrors) {
  try {
    read_mesh_file("mesh.stl");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "mesh.stl: unknown mesh file extension '.stl' (supported: .msh (Gmsh), .vtk (legacy "
              "VTK), .vtu (VTK XML), .gidmsh (GiD))");
  }
  for (const char* name : {"missing.msh", "missing.vtk", "missing.vtu"}) {
    const auto path = meshes_dir() / name;
    try {
      read_mesh_file(path);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), path.string() + ": no such file");
    }
  }
  const auto folder = temp_dir() / "folder.msh";  // exists, but is not a file
  std::filesystem::create_directories(folder);
  try {
    read_mesh_file(folder);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), folder.string() + ": not a regular file");
  }
}

// Reads `path`; true when it gives a mesh, false when it throws fastcorot::Error. Any other
// exception fails the test; a crash ends it.
bool reads_or_throws_error(const std::filesystem::path& path) {
  try {
    read_mesh_file(path);
    return true;
  } catch (const Error&) {
    return false;
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": not a fastcorot::Error: " << e.what();
    return false;
  }
}

TEST(MeshFile, TruncatedFilesGiveAnErrorNeverACrash) {
  const auto dir = temp_dir();
  for (const auto& path : test_mesh_files()) {
    SCOPED_TRACE(path.filename().string());
    const std::string bytes = file_bytes(path);
    const auto cut = dir / path.filename();
    std::vector<std::size_t> lengths = {
        0, 1, 2, 10, bytes.size() - 1, bytes.size() - 2, bytes.size() - 20};
    for (int k = 1; k < 40; ++k) lengths.push_back(bytes.size() * static_cast<std::size_t>(k) / 40);
    int errors = 0;
    for (const std::size_t length : lengths) {
      write_bytes(cut, bytes.substr(0, length));
      errors += reads_or_throws_error(cut) ? 0 : 1;
    }
    EXPECT_GT(errors, 30);  // most cuts lose part of the geometry
  }
}

TEST(MeshFile, CorruptedBytesGiveAnErrorNeverACrash) {
  const auto dir = temp_dir();
  for (const auto& path : test_mesh_files()) {
    SCOPED_TRACE(path.filename().string());
    const std::string bytes = file_bytes(path);
    const auto bad = dir / path.filename();
    for (int k = 0; k < 60; ++k) {
      std::string corrupt = bytes;
      const std::size_t at = (bytes.size() * static_cast<std::size_t>(k)) / 60;
      // Flip bits of a few consecutive bytes, then try a value that breaks counts.
      for (std::size_t i = at; i < std::min(at + 3, corrupt.size()); ++i)
        corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5a);
      write_bytes(bad, corrupt);
      reads_or_throws_error(bad);
      std::fill(corrupt.begin() + static_cast<std::ptrdiff_t>(at),
                corrupt.begin() + static_cast<std::ptrdiff_t>(std::min(at + 4, corrupt.size())),
                '\xff');
      write_bytes(bad, corrupt);
      reads_or_throws_error(bad);
    }
  }
}

TEST(MeshFile, CylinderValidationMesh) {
  // examples/meshes/cylinder.msh (see cylinder.geo): radius 1, height 1, axis z, base at z = 0.
  const auto path = std::filesystem::path(FASTCOROT_TEST_DATA_DIR).parent_path().parent_path() /
                    "examples" / "meshes" / "cylinder.msh";
  const MeshData mesh = read_mesh_file(path);
  // "$Nodes" / "9 1091 1 1091"; "$Elements" / "1 4452 1 4452" (gmsh 4.8.4).
  ASSERT_EQ(mesh.points.size(), 1091u);
  ASSERT_EQ(mesh.tetrahedra.size(), 4452u);
  EXPECT_TRUE(mesh.triangles.empty());

  const TetMesh topology(static_cast<Index>(mesh.points.size()), mesh.tetrahedra);
  EXPECT_NO_THROW(check_rest_volumes<double>(topology, mesh.points));

  std::vector<bool> used(mesh.points.size(), false);
  double volume = 0;
  for (const Tetrahedron& t : mesh.tetrahedra) {
    for (const Index v : t) used[static_cast<std::size_t>(v)] = true;
    volume += std::abs(signed_volume<double>(tetrahedron_points<double>(t, mesh.points)));
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0) << "points used by no tetrahedron";

  double max_radius = 0;
  for (const auto& p : mesh.points) {
    max_radius = std::max(max_radius, std::hypot(p.x(), p.y()));
    EXPECT_GE(p.z(), -1e-12);
    EXPECT_LE(p.z(), 1 + 1e-12);
  }
  EXPECT_NEAR(max_radius, 1.0, 1e-9);
  // The inscribed polyhedron is a little smaller than the cylinder: pi r^2 h (1 - O(h^2)).
  EXPECT_LT(volume, std::numbers::pi);
  EXPECT_GT(volume, 0.98 * std::numbers::pi);
}

}  // namespace
}  // namespace fastcorot
