// `fastcorot run --dump-state`: every MechanicalObject under its node path and object name, with
// velocities; mapped states (BarycentricMapping, IdentityMapping) follow their parent; SOFA's
// sphere files (SphereLoader). Expected values come from relations the dump must satisfy, computed
// here independently: implicit Euler's x_{n+1} = x_n + h v_{n+1}, barycentric coordinates solved
// from the rest tetrahedra, the identity.
#include "support/command.h"
#include "support/sofa_reference.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fastcorot {
namespace {

using nlohmann::json;
using testing::json_points;
using testing::run_fastcorot;

std::filesystem::path output_dir(const std::string& name) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A 2×1×1 box of 12 points cut into 12 tetrahedra (six around each cube's diagonal), its x = 0
// face fixed, with three markers mapped barycentrically onto the tetrahedra and an unnamed copy of
// its points (IdentityMapping).
constexpr const char* kTetrahedra =
    "0 1 4 10 0 7 1 10 0 4 3 10 0 3 9 10 0 6 7 10 0 9 6 10 1 2 5 11 1 8 2 11 1 5 4 11 1 4 10 11 1 7 8 11 1 10 7 11";
constexpr const char* kBeamWithMarkers = R"(<Node name="root" dt="0.01" gravity="0 -9.81 0">
  <Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    <SparseLDLSolver/>
    <TetrahedronSetTopologyContainer name="tetra" position="0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1 0  0 0 1  1 0 1  2 0 1  0 1 1  1 1 1  2 1 1"
      tetrahedra="0 1 4 10 0 7 1 10 0 4 3 10 0 3 9 10 0 6 7 10 0 9 6 10 1 2 5 11 1 8 2 11 1 5 4 11 1 4 10 11 1 7 8 11 1 10 7 11"/>
    <MechanicalObject name="dofs"/>
    <TetrahedronFEMForceField youngModulus="3000" poissonRatio="0.3"/>
    <UniformMass totalMass="1"/>
    <FixedProjectiveConstraint indices="0 3 6 9"/>
    <Node name="markers">
      <MechanicalObject name="points" position="0.5 0.5 0.5  1.9 0.1 0.9  1.25 0.75 0.2"/>
      <BarycentricMapping input="@../dofs" output="@points"/>
    </Node>
    <Node name="copy">
      <MechanicalObject/>
      <IdentityMapping/>
    </Node>
  </Node>
</Node>
)";

nlohmann::ordered_json run_and_read(const std::filesystem::path& dir, const std::string& scene_text, const std::string& options) {
  const auto scene = dir / "scene.scn";
  std::ofstream(scene) << scene_text;
  const auto dump = dir / "state.json";
  const auto result = run_fastcorot("run " + scene.string() + " --quiet --dump-state " + dump.string() + " " + options);
  EXPECT_EQ(result.status, 0) << result.output;
  std::ifstream in(dump);
  return nlohmann::ordered_json::parse(in);
}

TEST(StateDump, EveryStateUnderItsNodePathAndNameInSceneOrder) {
  const nlohmann::ordered_json dump = run_and_read(output_dir("dump_names"), kBeamWithMarkers, "--steps 2 --dump-steps 2");
  const auto& states = dump["states"]["2"];
  std::vector<std::string> keys;
  for (const auto& [key, state] : states.items()) keys.push_back(key);
  // SOFA's XML loader names an unnamed object by its type and rank in its node.
  EXPECT_EQ(keys, (std::vector<std::string>{"root/beam/dofs", "root/beam/markers/points", "root/beam/copy/MechanicalObject1"}));
  EXPECT_EQ(states["root/beam/dofs"]["node"], "root/beam");
  EXPECT_EQ(states["root/beam/dofs"]["object"], "dofs");
  EXPECT_EQ(states["root/beam/dofs"]["mapped"], false);
  EXPECT_EQ(states["root/beam/markers/points"]["mapped"], true);
  EXPECT_EQ(states["root/beam/markers/points"]["position"].size(), 3u);
  // The first format stays: positions of each simulated object under its path.
  EXPECT_EQ(json_points(dump["steps"]["2"]["root/beam"]), json_points(states["root/beam/dofs"]["position"]));
}

TEST(StateDump, VelocitiesAreImplicitEulersStepOverH) {
  const auto dump = run_and_read(output_dir("dump_velocity"), kBeamWithMarkers, "--steps 10 --dump-steps 9,10");
  const double h = dump["dt"];
  const auto x9 = json_points(dump["states"]["9"]["root/beam/dofs"]["position"]);
  const auto x10 = json_points(dump["states"]["10"]["root/beam/dofs"]["position"]);
  const auto v10 = json_points(dump["states"]["10"]["root/beam/dofs"]["velocity"]);
  ASSERT_EQ(v10.size(), 12u);
  double largest = 0;
  for (const auto& v : v10) largest = std::max(largest, v.norm());
  ASSERT_GT(largest, 1e-3);  // the beam moves
  for (std::size_t i = 0; i < v10.size(); ++i) {
    EXPECT_LT((x10[i] - (x9[i] + h * v10[i])).norm(), 1e-12 * (1 + x10[i].norm())) << "point " << i;
  }
  for (std::size_t i : {0u, 3u, 6u, 9u}) EXPECT_EQ(v10[i], Vec3<double>::Zero()) << "fixed point " << i;
}

// The barycentric coordinates of `p` in the first rest tetrahedron (of the grid's six per cell,
// SOFA's Hexa2Tetra split) that holds it, found here by solving each tetrahedron's 3×3 system.
std::pair<std::array<int, 4>, Eigen::Vector4d> locate(const std::vector<Vec3<double>>& rest,
                                                     const std::vector<std::array<int, 4>>& tetrahedra, const Vec3<double>& p) {
  for (const auto& t : tetrahedra) {
    Eigen::Matrix3d m;
    for (int k = 0; k < 3; ++k) m.col(k) = rest[static_cast<std::size_t>(t[k + 1])] - rest[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d f = m.lu().solve(p - rest[static_cast<std::size_t>(t[0])]);
    const Eigen::Vector4d w(1 - f.sum(), f.x(), f.y(), f.z());
    if (w.minCoeff() >= -1e-12) return {t, w};
  }
  ADD_FAILURE() << "no tetrahedron holds the point";
  return {};
}

TEST(StateDump, MappedStatesFollowTheirParentThroughTheMapping) {
  const auto dump = run_and_read(output_dir("dump_mapped"), kBeamWithMarkers, "--steps 5 --dump-steps 0,5");
  const auto rest = json_points(dump["states"]["0"]["root/beam/dofs"]["position"]);
  std::vector<std::array<int, 4>> tetrahedra;
  std::istringstream in(kTetrahedra);
  for (std::array<int, 4> t; in >> t[0] >> t[1] >> t[2] >> t[3];) tetrahedra.push_back(t);
  ASSERT_EQ(tetrahedra.size(), 12u);
  const auto parent_x = json_points(dump["states"]["5"]["root/beam/dofs"]["position"]);
  const auto parent_v = json_points(dump["states"]["5"]["root/beam/dofs"]["velocity"]);
  const auto marker_rest = json_points(dump["states"]["0"]["root/beam/markers/points"]["position"]);
  const auto marker_x = json_points(dump["states"]["5"]["root/beam/markers/points"]["position"]);
  const auto marker_v = json_points(dump["states"]["5"]["root/beam/markers/points"]["velocity"]);
  ASSERT_EQ(marker_rest.size(), 3u);
  EXPECT_LT((marker_rest[1] - Vec3<double>(1.9, 0.1, 0.9)).norm(), 1e-15);
  for (std::size_t m = 0; m < 3; ++m) {
    const auto [t, w] = locate(rest, tetrahedra, marker_rest[m]);
    Vec3<double> x = Vec3<double>::Zero(), v = Vec3<double>::Zero();
    for (int k = 0; k < 4; ++k) {
      x += w[k] * parent_x[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
      v += w[k] * parent_v[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
    }
    EXPECT_GT((marker_x[m] - marker_rest[m]).norm(), 1e-4) << "marker " << m << " moves";
    EXPECT_LT((marker_x[m] - x).norm(), 1e-13 * x.norm()) << "marker " << m;
    EXPECT_LT((marker_v[m] - v).norm(), 1e-12 * v.norm()) << "marker " << m;
  }
  EXPECT_EQ(json_points(dump["states"]["5"]["root/beam/copy/MechanicalObject1"]["position"]), parent_x);
  EXPECT_EQ(json_points(dump["states"]["5"]["root/beam/copy/MechanicalObject1"]["velocity"]), parent_v);
}

TEST(StateDump, SphereLoaderGivesTheCollisionSpheresOfAMappedState) {
  const auto dir = output_dir("dump_spheres");
  std::ofstream(dir / "balls.sph") << "sph 1.0\n#nums 2\nnums 2\n# a comment\nsphe 1 0.5 0.5 0.5 0.2\nsphe 2 1.5 0.5 0.5 0.3\nwhat 1 2\n";
  const std::string scene = std::string(kBeamWithMarkers).replace(
      std::string(kBeamWithMarkers).find("<Node name=\"copy\">"), 0,
      "<Node name=\"spheres\"><SphereLoader name=\"loader\" filename=\"balls.sph\" translation=\"0 0.1 0\"/>"
      "<MechanicalObject name=\"centres\" position=\"@loader.position\"/><SphereCollisionModel listRadius=\"@loader.listRadius\"/>"
      "<BarycentricMapping input=\"@../dofs\" output=\"@centres\"/></Node>\n");
  const auto scene_path = dir / "scene.scn";
  std::ofstream(scene_path) << scene;
  const auto dump = dir / "state.json";
  const auto result = run_fastcorot("run " + scene_path.string() + " --steps 1 --dump-steps 0 --dump-state " + dump.string());
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("unknown keyword 'what'"), std::string::npos) << result.output;
  std::ifstream in(dump);
  const auto centres = json_points(json::parse(in)["states"]["0"]["root/beam/spheres/centres"]["position"]);
  ASSERT_EQ(centres.size(), 2u);
  EXPECT_LT((centres[0] - Vec3<double>(0.5, 0.6, 0.5)).norm(), 1e-14);
  EXPECT_LT((centres[1] - Vec3<double>(1.5, 0.6, 0.5)).norm(), 1e-14);
}

TEST(StateDump, MalformedSphereFileIsOneLineNamingFileAndLine) {
  const auto dir = output_dir("dump_bad_spheres");
  std::ofstream(dir / "balls.sph") << "sph 1.0\nsphe 1 0.5 0.5\n";
  std::ofstream(dir / "scene.scn") << R"(<Node name="root"><Node name="b"><EulerImplicitSolver/><CGLinearSolver/>
    <SphereLoader name="loader" filename="balls.sph"/><MechanicalObject position="@loader.position"/><UniformMass/></Node></Node>)";
  const auto result = run_fastcorot("run " + (dir / "scene.scn").string() + " --steps 1");
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("balls.sph:2: sphe: expected index x y z radius"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace fastcorot
