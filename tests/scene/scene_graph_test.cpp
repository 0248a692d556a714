#include "fastcorot/scene/scene_graph.h"
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fastcorot {
namespace {

std::string error_of(const std::string& text, const std::filesystem::path& file = "scene.scn") {
  try {
    parse_scene_text(text, file);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(SceneGraph, ReadsNodesObjectsAttributesAndLines) {
  const SceneNode root = parse_scene_text(R"(<?xml version="1.0"?>
<Node name="root" dt="0.02" gravity="0 0 -1">
  <DefaultAnimationLoop/>
  <Node name="child">
    <MechanicalObject name="state" position="0 0 0"/>
    <Object type="UniformMass" totalMass="2"/>
  </Node>
</Node>)", "scene.scn");
  EXPECT_EQ(root.name, "root");
  EXPECT_EQ(root.attributes.at("dt"), "0.02");
  ASSERT_EQ(root.objects.size(), 1u);
  EXPECT_EQ(root.objects[0].type, "DefaultAnimationLoop");
  EXPECT_EQ(root.objects[0].location.line, 3);
  ASSERT_EQ(root.children.size(), 1u);
  const SceneNode& child = root.children[0];
  EXPECT_EQ(child.name, "child");
  ASSERT_EQ(child.objects.size(), 2u);
  EXPECT_EQ(child.objects[0].name(), "state");
  EXPECT_EQ(child.objects[0].location.to_string(), "scene.scn:5");
  // SOFA's older <Object type="..."/> form.
  EXPECT_EQ(child.objects[1].type, "UniformMass");
  EXPECT_EQ(child.objects[1].attributes.count("type"), 0u);
}

TEST(SceneGraph, MalformedXmlNamesFileAndLine) {
  const std::string message = error_of("<Node name=\"root\">\n  <MechanicalObject\n</Node>", "bad.scn");
  EXPECT_NE(message.find("bad.scn:"), std::string::npos) << message;
  EXPECT_NE(message.find("malformed XML"), std::string::npos) << message;
  EXPECT_NE(error_of("<Scene/>").find("root must be a <Node>"), std::string::npos);
  EXPECT_NE(error_of("").find("scene.scn"), std::string::npos);
}

class SceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("fastcorot_scene_graph_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "parts");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }
  std::filesystem::path dir_;
};

TEST_F(SceneFiles, IncludeInsertsANodeAsChildAndAGroupInPlace) {
  write("parts/body.xml", R"(<Node name="body"><MechanicalObject name="state"/></Node>)");
  write("parts/solvers.xml", R"(<Group><EulerImplicitSolver/><CGLinearSolver/></Group>)");
  const auto scene = write("main.scn", R"(<Node name="root">
  <include href="parts/solvers.xml"/>
  <include href="parts/body.xml"/>
</Node>)");
  const SceneNode root = parse_scene_file(scene);
  ASSERT_EQ(root.objects.size(), 2u);
  EXPECT_EQ(root.objects[0].type, "EulerImplicitSolver");
  EXPECT_EQ(root.objects[1].type, "CGLinearSolver");
  EXPECT_EQ(root.objects[0].location.file, dir_ / "parts/solvers.xml");
  ASSERT_EQ(root.children.size(), 1u);
  EXPECT_EQ(root.children[0].name, "body");
}

TEST_F(SceneFiles, IncludeAttributesReplaceThoseOfTheIncludedObjectsAsInSofa) {
  // SOFA's examples/Objects/TetrahedronSetTopology.xml pattern: a Node named Group whose objects
  // join the including node, with src="@" replaced by the include's src.
  write("parts/topology.xml", R"(<Node name="Group">
  <TetrahedronSetTopologyContainer name="Container" src="@" tags=" "/>
  <TetrahedronSetGeometryAlgorithms name="GeomAlgo" template="Vec3"/>
</Node>)");
  write("parts/named.xml", R"(<Node name="part"><Object type="MechanicalObject" name="a" template="Vec3"/><Object type="MechanicalObject" name="b" template="Vec3"/></Node>)");
  const auto scene = write("main.scn", R"(<Node name="root">
  <include href="parts/topology.xml" src="@loader" template="Vec1"/>
  <include href="parts/named.xml" name="renamed" b__template="Vec3f" color="red"/>
</Node>)");
  const SceneNode root = parse_scene_file(scene);
  ASSERT_EQ(root.objects.size(), 2u);
  EXPECT_EQ(root.objects[0].attributes.at("src"), "@loader");
  EXPECT_EQ(root.objects[0].attributes.count("template"), 0u);  // only replaced where present
  EXPECT_EQ(root.objects[1].attributes.at("template"), "Vec1");
  ASSERT_EQ(root.children.size(), 1u);
  EXPECT_EQ(root.children[0].name, "renamed");
  EXPECT_EQ(root.children[0].objects[0].attributes.at("template"), "Vec3");
  EXPECT_EQ(root.children[0].objects[1].attributes.at("template"), "Vec3f");
  EXPECT_EQ(root.children[0].objects[0].attributes.count("color"), 0u);
}

TEST(SceneGraph, BoxAndPlaneConstraintAreSofasObjectFilesBuiltIn) {
  // Read away from SOFA's folders: the nodes of SOFA's examples/Objects/BoxConstraint.xml and
  // PlaneConstraint.xml, with the element's attributes where the files' objects have them. (With
  // SOFA's examples on FASTCOROT_DATA_PATH the files themselves are read, their lines named.)
  const char* given = std::getenv("FASTCOROT_DATA_PATH");
  const std::string kept = given ? given : "";
  ::unsetenv("FASTCOROT_DATA_PATH");
  struct Restore {
    const char* value;
    ~Restore() {
      if (value) ::setenv("FASTCOROT_DATA_PATH", value, 1);
    }
  } restore{given ? kept.c_str() : nullptr};
  const SceneNode root = parse_scene_text(R"(<Node name="root">
  <BoxConstraint box="-1 -1 -1 1 1 1" fixAll="0"/>
  <BoxConstraint name="second" box="2 2 2 3 3 3" drawBoxes="1"/>
  <PlaneConstraint plane="0 0 0 1 0 0 1 1 0 0.5"/>
</Node>)",
                                          "b.scn");
  ASSERT_EQ(root.objects.size(), 6u);
  EXPECT_TRUE(root.children.empty());  // a Group joins the node, named or not (as in SOFA)
  EXPECT_EQ(root.objects[0].type, "BoxROI");
  EXPECT_EQ(root.objects[0].attributes.at("box"), "-1 -1 -1 1 1 1");
  EXPECT_EQ(root.objects[0].attributes.count("fixAll"), 0u);  // only attributes SOFA's file has are set
  EXPECT_EQ(root.objects[1].type, "FixedProjectiveConstraint");
  EXPECT_EQ(root.objects[1].attributes.at("indices"), "@[-1].indices");
  EXPECT_EQ(root.objects[2].attributes.at("drawBoxes"), "1");
  EXPECT_EQ(root.objects[2].attributes.at("box"), "2 2 2 3 3 3");
  EXPECT_EQ(root.objects[2].location.line, 3);  // errors name the scene's element
  EXPECT_EQ(root.objects[4].type, "PlaneROI");
  EXPECT_EQ(root.objects[4].attributes.at("plane"), "0 0 0 1 0 0 1 1 0 0.5");
  EXPECT_EQ(root.objects[5].type, "FixedProjectiveConstraint");
}

TEST_F(SceneFiles, AddDataRepositoryAddsItsFolderRelativeToTheScene) {
  // The mesh lies only in dir/repository_<pid>_<run>/; the scene names it by its file name.
  // A new folder each run: repositories stay added for the rest of the process (--gtest_repeat).
  static int run = 0;
  const std::string folder = "repository_" + std::to_string(::getpid()) + "_" + std::to_string(run++);
  std::filesystem::create_directories(dir_ / folder);
  std::filesystem::copy_file(std::filesystem::path(FASTCOROT_SOURCE_DIR) / "examples/meshes/cylinder.msh",
                             dir_ / folder / "cylinder_in_repository.msh");
  const std::string body = R"(<Node name="body"><EulerImplicitSolver/><CGLinearSolver iterations="10"/>
    <MeshGmshLoader name="loader" filename="cylinder_in_repository.msh"/><TetrahedronSetTopologyContainer src="@loader"/>
    <MechanicalObject/><UniformMass totalMass="1"/><TetrahedronFEMForceField youngModulus="100"/></Node>)";
  const auto without = write("without.scn", "<Node name=\"root\">" + body + "</Node>");
  EXPECT_THROW(load_scene_file(without), Error);
  const auto with = write("with.scn", "<Node name=\"root\"><AddDataRepository path=\"" + folder + "\"/>"
                                      "<AddResourceRepository path=\"absent\"/><AddPluginRepository path=\"x\"/>" + body + "</Node>");
  const LoadedScene scene = load_scene_file(with);
  EXPECT_GT(scene.simulation.objects.at(0).system.size(), 0);
  bool warned = false;
  for (const auto& line : scene.warnings) warned = warned || line.find("AddResourceRepository: path") != std::string::npos;
  EXPECT_TRUE(warned) << "a missing folder is warned";
  const auto repositories = data_repositories();
  EXPECT_NE(std::find(repositories.begin(), repositories.end(), (dir_ / folder).lexically_normal()), repositories.end());
}

TEST_F(SceneFiles, DataFilesAreFoundAsSofasRepositoriesFindThem) {
  // dir/share/mesh/m.obj, dir/examples/Objects/o.xml, the scene in dir/examples/Component/A.
  std::filesystem::create_directories(dir_ / "share/mesh");
  std::filesystem::create_directories(dir_ / "examples/Objects");
  std::filesystem::create_directories(dir_ / "examples/Component/A");
  std::filesystem::create_directories(dir_ / "elsewhere/mesh");
  write("share/mesh/m.obj", "v 0 0 0\n");
  write("share/s.txt", "");
  write("examples/Objects/o.xml", "<Group/>");
  write("elsewhere/mesh/n.obj", "");
  write("examples/Component/A/local.msh", "");
  const auto from = write("examples/Component/A/scene.scn", "<Node/>");
  EXPECT_EQ(find_data_file(from, "local.msh"), dir_ / "examples/Component/A/local.msh");  // the scene's folder first
  EXPECT_EQ(find_data_file(from, "mesh/m.obj"), std::filesystem::absolute(dir_ / "share/mesh/m.obj"));
  EXPECT_EQ(find_data_file(from, "m.obj"), std::filesystem::absolute(dir_ / "share/mesh/m.obj"));
  EXPECT_EQ(find_data_file(from, "s.txt"), std::filesystem::absolute(dir_ / "share/s.txt"));
  EXPECT_EQ(find_data_file(from, "Objects/o.xml"), std::filesystem::absolute(dir_ / "examples/Objects/o.xml"));
  EXPECT_THROW(find_data_file(from, "mesh/n.obj"), Error);
  ::setenv("FASTCOROT_DATA_PATH", ("/nonexistent:" + (dir_ / "elsewhere").string()).c_str(), 1);
  EXPECT_EQ(find_data_file(from, "mesh/n.obj"), dir_ / "elsewhere/mesh/n.obj");
  ::unsetenv("FASTCOROT_DATA_PATH");
  try {
    find_data_file(from, "mesh/absent.obj");
    ADD_FAILURE() << "found an absent file";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("mesh/absent.obj: no such file (looked for"), std::string::npos) << error.what();
  }
}

TEST_F(SceneFiles, AnUnknownTagIsReplacedByItsObjectsFileOnTheDataPath) {
  // As SOFA's loader does: Objects/<tag>.xml found from the scene (its folder, then the data path)
  // replaces the element, as an include with the element's attributes; a file on the path wins
  // over the built-in BoxConstraint.
  std::filesystem::create_directories(dir_ / "examples/Objects");
  std::filesystem::create_directories(dir_ / "examples/Component");
  write("examples/Objects/Clamp.xml", R"(<Node name="Group">
  <BoxROI name="clamp_box" box="0 0 0 1 1 1"/>
  <FixedProjectiveConstraint indices="@[-1].indices"/>
</Node>)");
  write("examples/Objects/BoxConstraint.xml", R"(<Node name="Group"><BoxROI box="0 0 0 1 1 1" strict="0"/></Node>)");
  write("examples/Objects/Tool.xml", R"(<Node name="Tool"><MechanicalObject position="0 0 0"/></Node>)");
  const auto scene = write("examples/Component/scene.scn", R"(<Node name="root">
  <Clamp box="-1 -1 -1 0 0 0" color="red"/>
  <BoxConstraint box="5 5 5 6 6 6"/>
  <Object type="Tool" name="tool"/>
  <Undefined size="3"/>
</Node>)");
  const SceneNode root = parse_scene_file(scene);
  ASSERT_EQ(root.objects.size(), 4u);
  EXPECT_EQ(root.objects[0].type, "BoxROI");
  EXPECT_EQ(root.objects[0].attributes.at("box"), "-1 -1 -1 0 0 0");
  EXPECT_EQ(root.objects[0].attributes.count("color"), 0u);
  EXPECT_EQ(root.objects[0].location.file, dir_ / "examples/Objects/Clamp.xml");
  EXPECT_EQ(root.objects[1].type, "FixedProjectiveConstraint");
  EXPECT_EQ(root.objects[2].attributes.at("strict"), "0");  // the file on the path, not the built-in
  EXPECT_EQ(root.objects[2].attributes.at("box"), "5 5 5 6 6 6");
  ASSERT_EQ(root.children.size(), 1u);  // not a Group: a child node, renamed by the element
  EXPECT_EQ(root.children[0].name, "tool");
  EXPECT_EQ(root.objects[3].type, "Undefined");  // no file: left for the builder to report
}

TEST_F(SceneFiles, IncludeErrors) {
  write("cycle_a.scn", R"(<Node name="a"><include href="cycle_b.scn"/></Node>)");
  write("cycle_b.scn", R"(<Node name="b"><include href="cycle_a.scn"/></Node>)");
  try {
    parse_scene_file(dir_ / "cycle_a.scn");
    ADD_FAILURE() << "no error for an include cycle";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("include cycle"), std::string::npos) << error.what();
  }
  const auto missing = write("missing.scn", "<Node name=\"r\">\n<include href=\"nowhere.xml\"/>\n</Node>");
  try {
    parse_scene_file(missing);
    ADD_FAILURE() << "no error for a missing include";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("missing.scn:2"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("nowhere.xml"), std::string::npos) << error.what();
  }
  EXPECT_THROW(parse_scene_file(dir_ / "absent.scn"), Error);
}

}  // namespace
}  // namespace fastcorot
