// `fastcorot run` through the executable: state dumps against SOFA's four-beam trajectory, ParaView
// output, the built-in scene, and bad scenes (clear message, exit status 2).
#include "support/sofa_reference.h"

#include "fastcorot/io/mesh_readers.h"
#include "fastcorot/io/surface_readers.h"

#include "support/command.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fastcorot {
namespace {

using nlohmann::json;

using testing::CommandResult;
using testing::run_fastcorot;

std::filesystem::path output_dir(const std::string& name) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string write_scene(const std::filesystem::path& dir, const std::string& text) {
  const auto path = dir / "scene.scn";
  std::ofstream(path) << text;
  return path.string();
}

TEST(Run, DumpStateReproducesSofasFourBeams) {
  const auto dir = output_dir("run_four_beams");
  const auto dump = dir / "state.json";
  const auto result = run_fastcorot("run " + testing::sofa_reference_path("four_beams.scn") +
                                    " --steps 10 --dump-state " + dump.string() + " --dump-steps 0,1,10 --quiet");
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_EQ(result.output, "");  // --quiet
  std::ifstream ours_in(dump), reference_in(testing::sofa_reference_path("four_beams_trajectory.json"));
  const json ours = json::parse(ours_in), reference = json::parse(reference_in);
  EXPECT_EQ(ours["dt"], reference["dt"]);
  for (const auto& [step, frame] : reference["steps"].items()) {
    ASSERT_TRUE(ours["steps"].contains(step)) << step;
    for (const auto& [path, points] : frame.items()) {
      ASSERT_TRUE(ours["steps"][step].contains(path)) << path;
      const auto a = testing::json_points(ours["steps"][step][path]);
      const auto b = testing::json_points(points);
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT((a[i] - b[i]).norm(), 1e-11) << path << " point " << i;
    }
  }
}

TEST(Run, ThreadCountDoesNotChangeResults) {
  const auto dir = output_dir("run_threads");
  std::string dumps[2];
  for (int threads : {1, 3}) {
    const auto dump = dir / ("state_" + std::to_string(threads) + ".json");
    const auto result = run_fastcorot("run " + testing::sofa_reference_path("four_beams.scn") + " --steps 5 --quiet --threads " +
                                      std::to_string(threads) + " --dump-state " + dump.string() + " --dump-steps 5");
    ASSERT_EQ(result.status, 0) << result.output;
    std::ifstream in(dump);
    dumps[threads == 1 ? 0 : 1] = std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  EXPECT_FALSE(dumps[0].empty());
  EXPECT_EQ(dumps[0], dumps[1]);  // bitwise: the JSON holds every double exactly
}

TEST(Run, BuiltInSceneRunsAndSummarises) {
  const auto result = run_fastcorot("run --steps 2");
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("fastcorot run: 2 steps"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("steps/s"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("mean linear-solver iterations"), std::string::npos) << result.output;  // CG
}

TEST(Run, VtuSeriesHasOneFilePerWrittenStepAndACollection) {
  const auto dir = output_dir("run_vtu");
  const auto result = run_fastcorot("run " + testing::sofa_reference_path("four_beams.scn") + " --steps 3 --every 2 --vtu --quiet --out " +
                                    dir.string());
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* step : {"0", "2", "3"}) {
    const auto file = dir / (std::string("root_BeamFEM_LARGE_") + step + ".vtu");
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    const MeshData mesh = read_vtu(file);
    EXPECT_EQ(mesh.points.size(), 500u);
    EXPECT_EQ(mesh.tetrahedra.size(), 1824u);
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "root_BeamFEM_LARGE_1.vtu"));
  std::ifstream pvd(dir / "root_BeamFEM_LARGE.pvd");
  const std::string collection((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  EXPECT_NE(collection.find("root_BeamFEM_LARGE_3.vtu"), std::string::npos);
}

TEST(Run, VtuFramesCarryTheVonMisesStressOfTetrahedronFEMForceField) {
  const auto dir = output_dir("run_vtu_von_mises");
  const auto result = run_fastcorot("run " + std::string(FASTCOROT_EXAMPLES_DIR) +
                                    "/tetrahedron_fem_beams.scn --steps 2 --vtu --quiet --out " + dir.string());
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* beam : {"SMALL", "LARGE", "POLAR", "SVD"}) {
    std::ifstream in(dir / (std::string("root_BeamTFEM_") + beam + "_2.vtu"));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("Name=\"vonMisesPerNode\""), std::string::npos) << beam;
    EXPECT_NE(text.find("Name=\"vonMisesPerElement\""), std::string::npos) << beam;
  }
  // FastTetrahedralCorotationalForceField computes none.
  const auto plain = output_dir("run_vtu_plain");
  ASSERT_EQ(run_fastcorot("run " + testing::sofa_reference_path("four_beams.scn") + " --steps 1 --vtu --quiet --out " +
                          plain.string()).status, 0);
  std::ifstream in(plain / "root_BeamFEM_LARGE_1.vtu");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("vonMises"), std::string::npos);
}

TEST(Run, UnknownAttributesWarnAndStrictMakesThemErrors) {
  const auto dir = output_dir("run_strict");
  const std::string scene = write_scene(dir, R"(<Node name="root">
  <EulerImplicitSolver/><CGLinearSolver/>
  <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <UniformMass totalMass="1"/>
  <TetrahedronFEMForceField youngModulus="100" poissonRatio="0.3" methd="small"/>
</Node>)");
  const auto lenient = run_fastcorot("run " + scene + " --steps 2 --quiet");
  EXPECT_EQ(lenient.status, 0) << lenient.output;
  EXPECT_NE(lenient.output.find("warning: " + scene + ":6: TetrahedronFEMForceField: unknown attribute 'methd' "
                                "ignored (did you mean 'method'?)"),
            std::string::npos)
      << lenient.output;
  const auto strict = run_fastcorot("run " + scene + " --steps 2 --quiet --strict");
  EXPECT_EQ(strict.status, 2) << strict.output;
  EXPECT_NE(strict.output.find("unknown attribute 'methd' (did you mean 'method'?)"), std::string::npos)
      << strict.output;
}

TEST(Run, VisualSurfacesGetVtuSeriesOfTheirOwn) {
  const auto dir = output_dir("run_visual");
  std::ofstream(dir / "tri.obj") << "v 0.2 0.2 0.2\nv 0.8 0.2 0.2\nv 0.2 0.8 0.2\nf 1 2 3\n";
  const std::string scene = write_scene(dir, R"(<Node name="root">
  <Node name="body">
    <EulerImplicitSolver/><CGLinearSolver/>
    <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
    <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
    <UniformMass totalMass="1"/>
    <TetrahedronFEMForceField/>
    <Node name="Visu">
      <MeshOBJLoader name="l" filename="tri.obj"/>
      <OglModel name="V" src="@l"/>
      <BarycentricMapping input="@.." output="@V"/>
    </Node>
  </Node>
</Node>)");
  const auto out = dir / "frames";
  const auto result = run_fastcorot("run " + scene + " --steps 2 --vtu --quiet --out " + out.string());
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* step : {"0", "1", "2"}) {
    const MeshData surface = read_vtu(out / (std::string("root_body_Visu_V_") + step + ".vtu"));
    EXPECT_EQ(surface.points.size(), 3u);
    EXPECT_EQ(surface.triangles.size(), 1u);
  }
  EXPECT_TRUE(std::filesystem::exists(out / "root_body_Visu_V.pvd"));
  // The free fall moves the triangle with the tetrahedron.
  const MeshData first = read_vtu(out / "root_body_Visu_V_0.vtu"), last = read_vtu(out / "root_body_Visu_V_2.vtu");
  EXPECT_LT(last.points[0].y(), first.points[0].y());
}

TEST(Run, ObjFramesHoldTheVisualSurfacesOrTheBoundary) {
  const auto dir = output_dir("run_obj");
  std::ofstream(dir / "tri.obj") << "v 0.2 0.2 0.2\nv 0.8 0.2 0.2\nv 0.2 0.8 0.2\nf 1 2 3\n";
  const std::string body = R"(
    <EulerImplicitSolver/><CGLinearSolver/>
    <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
    <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
    <UniformMass totalMass="1"/>
    <TetrahedronFEMForceField/>)";
  const std::string scene = write_scene(dir, R"(<Node name="root"><Node name="body">)" + body + R"(
    <Node name="Visu">
      <MeshOBJLoader name="l" filename="tri.obj"/>
      <OglModel name="V" src="@l"/>
      <BarycentricMapping input="@.." output="@V"/>
    </Node>
  </Node><Node name="bare">)" + body + "</Node></Node>");
  const auto out = dir / "frames";
  const auto result = run_fastcorot("run " + scene + " --steps 3 --every 2 --obj --vtu --quiet --out " + out.string());
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* step : {"0", "2", "3"}) {
    // The mapped triangle, point for point the VTU frame's (17 digits read back exactly).
    const SurfaceData surface = read_obj(out / (std::string("root_body_Visu_V_") + step + ".obj"));
    const MeshData vtu = read_vtu(out / (std::string("root_body_Visu_V_") + step + ".vtu"));
    ASSERT_EQ(surface.points.size(), 3u);
    EXPECT_EQ(surface.points, vtu.points);
    EXPECT_EQ(surface.triangles, vtu.triangles);
    // Without a visual model: the tetrahedron's four boundary triangles on its points.
    const SurfaceData boundary = read_obj(out / (std::string("root_bare_") + step + ".obj"));
    EXPECT_EQ(boundary.points, read_vtu(out / (std::string("root_bare_") + step + ".vtu")).points);
    EXPECT_EQ(boundary.triangles.size(), 4u);
  }
  EXPECT_FALSE(std::filesystem::exists(out / "root_bare_1.obj"));
  EXPECT_NE(read_obj(out / "root_bare_3.obj").points, read_obj(out / "root_bare_0.obj").points);
}

TEST(Run, BadScenesExitWith2AndAClearMessage) {
  const auto dir = output_dir("run_bad");
  const std::string solver = "<EulerImplicitSolver/><CGLinearSolver/>";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"<Node name=\"root\">\n<MechanicalObject\n</Node>", "malformed XML"},
      {"<Node name=\"root\">" + solver + "<Frobnicator/></Node>", "unknown component 'Frobnicator'"},
      {"<Node name=\"root\">" + solver + "<MechanicalObject position=\"@missing.position\"/></Node>", "broken link"},
      {"<Node name=\"root\">" + solver + "<MeshGmshLoader name=\"l\" filename=\"nothere.msh\"/><TetrahedronSetTopologyContainer src=\"@l\"/><MechanicalObject/></Node>",
       "nothere.msh"},
      {"<Node name=\"root\">" + solver + "<MechanicalObject position=\"0 0 0 1 0 0 0 1 0 0 0 1\"/><TetrahedronSetTopologyContainer/><FastTetrahedralCorotationalForceField/></Node>",
       "no tetrahedra"},
  };
  for (const auto& [text, needle] : cases) {
    const auto result = run_fastcorot("run " + write_scene(dir, text) + " --steps 1");
    EXPECT_EQ(result.status, 2) << text << "\n" << result.output;
    EXPECT_NE(result.output.find(needle), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("scene.scn"), std::string::npos) << result.output;
  }
  std::ofstream(dir / "corrupt.msh") << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n";
  const auto corrupt = run_fastcorot("run " + write_scene(dir, "<Node name=\"root\">" + solver +
                                                                   "<MeshGmshLoader name=\"l\" filename=\"corrupt.msh\"/>"
                                                                   "<TetrahedronSetTopologyContainer src=\"@l\"/><MechanicalObject/></Node>") +
                                     " --steps 1");
  EXPECT_EQ(corrupt.status, 2) << corrupt.output;
  EXPECT_NE(corrupt.output.find("corrupt.msh"), std::string::npos) << corrupt.output;
  EXPECT_EQ(run_fastcorot("run /nonexistent.scn").status, 2);
  EXPECT_EQ(run_fastcorot("run --steps -3").status, 2);
}

TEST(Run, DivergenceStopsWithTheStepAndKeepsTheDump) {
  const auto dir = output_dir("run_diverge");
  // An absurd stiffness overflows the forces at the first step.
  const std::string scene = write_scene(dir, R"(<Node name="root" dt="0.01">
  <Node name="blob">
    <EulerImplicitSolver/>
    <CGLinearSolver iterations="5"/>
    <RegularGridTopology name="grid" n="3 3 3" min="0 0 0" max="1 1 1"/>
    <MechanicalObject velocity="0 0 1e300"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets"/>
    <UniformMass totalMass="1"/>
    <FastTetrahedralCorotationalForceField youngModulus="1e300"/>
  </Node>
</Node>)");
  const auto dump = dir / "state.json";
  const auto result = run_fastcorot("run " + scene + " --steps 5 --dump-state " + dump.string());
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("diverged at step 1"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("root/blob"), std::string::npos) << result.output;
  std::ifstream in(dump);
  ASSERT_TRUE(in.good());
  const json state = json::parse(in);
  EXPECT_TRUE(state["steps"].contains("0"));
}

}  // namespace
}  // namespace fastcorot
