// Scenes fed as inline XML through the real parser and builder; every expectation is derived from
// SOFA's conventions (docs/sofa-components.md) by hand.
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/sim/sparse_direct_solver.h"

#include "fastcorot/scene/component_table.h"
#include "support/force_fields.h"

#include "support/scene_text.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace fastcorot {
namespace {

LoadedScene build(const std::string& body, const std::string& root_attributes = "") {
  return testing::build_scene_text(body, root_attributes);
}
std::string error_of(const std::string& body) { return testing::scene_error(body); }

// Two hexahedral cells along x (3×2×2 points) split into 12 tetrahedra, fixed at x = 0.
const std::string kSmallBeam = R"(
  <Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    <CGLinearSolver iterations="50" tolerance="1e-12" threshold="1e-20"/>
    <RegularGridTopology name="grid" n="3 2 2" min="0 0 0" max="2 1 1"/>
    <MechanicalObject name="state" translation="10 0 0"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
    <DiagonalMass massDensity="2"/>
    <FastTetrahedralCorotationalForceField youngModulus="1000" poissonRatio="0.3" method="large"/>
    <BoxROI name="roi" box="9.5 -1 -1 10 2 2"/>
    <FixedProjectiveConstraint indices="@roi.indices"/>
  </Node>)";

TEST(SceneBuilder, GridBeamFollowsSofaConventions) {
  const LoadedScene scene = build(kSmallBeam, "dt=\"0.02\" gravity=\"0 0 -5\"");
  const auto& simulation = scene.simulation;
  EXPECT_EQ(simulation.dt, 0.02);
  ASSERT_EQ(simulation.objects.size(), 1u);
  const auto& object = simulation.objects[0];
  EXPECT_EQ(object.path, "root/beam");
  const auto& system = object.system;
  // RegularGridTopology order (x fastest), then the MechanicalObject's translation.
  ASSERT_EQ(system.size(), 12);
  EXPECT_EQ(system.state.position[1], Vec3<double>(11, 0, 0));
  EXPECT_EQ(system.state.position[3], Vec3<double>(10, 1, 0));
  EXPECT_EQ(system.state.position[6], Vec3<double>(10, 0, 1));
  EXPECT_EQ(system.state.rest_position, system.state.position);
  EXPECT_EQ(system.gravity, Vec3<double>(0, 0, -5));
  // BoxROI is inclusive: x in [9.5, 10] selects the x = 10 face, points 0, 3, 6, 9.
  EXPECT_EQ(system.fixed, (std::vector<Index>{0, 3, 6, 9}));
  // 6 tetrahedra per cell; DiagonalMass: total = density × volume = 2 × 2.
  ASSERT_EQ(system.force_fields.size(), 1u);
  EXPECT_EQ(system.force_fields[0]->mesh().num_tetrahedra(), 12);
  EXPECT_EQ(testing::corotational(system.force_fields[0]).method(), RotationMethod::qr);
  EXPECT_NEAR(system.mass.total_mass(), 4.0, 1e-12);
  // A corner point belongs to the tetrahedra of one cell only, a middle point to two cells.
  const auto masses = system.mass.vertex_masses();
  EXPECT_NEAR(masses[1] + masses[4] + masses[7] + masses[10], 2.0, 1e-12);  // the middle plane x = 1 holds half
  EXPECT_NE(dynamic_cast<ConjugateGradientSolver<double>*>(object.linear_solver.get()), nullptr);
  EXPECT_NE(dynamic_cast<ImplicitEulerSolver<double>*>(object.ode_solver.get()), nullptr);
}

TEST(SceneBuilder, DefaultsAreSofas) {
  const LoadedScene scene = build(R"(
  <EulerImplicitSolver/>
  <EigenSimplicialLDLT/>
  <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <DiagonalMass/>
  <FastTetrahedralCorotationalForceField/>
  <FixedProjectiveConstraint/>)");
  const auto& simulation = scene.simulation;
  EXPECT_EQ(simulation.dt, 0.01);
  EXPECT_EQ(simulation.gravity, Vec3<double>(0, -9.81, 0));
  const auto& system = simulation.objects[0].system;
  EXPECT_EQ(simulation.objects[0].path, "root");
  EXPECT_EQ(system.fixed, std::vector<Index>{0});  // FixedProjectiveConstraint's default indices
  EXPECT_NEAR(system.mass.total_mass(), 1.0, 1e-15);  // DiagonalMass with nothing set: totalMass 1
  const auto& parameters = testing::corotational(system.force_fields[0]).parameters();
  EXPECT_EQ(parameters.young_modulus, std::vector<double>{5000});
  EXPECT_EQ(parameters.poisson_ratio, std::vector<double>{0.45});
  EXPECT_NE(dynamic_cast<SparseDirectSolver<double>*>(simulation.objects[0].linear_solver.get()), nullptr);
}

const std::string kTet = R"(
  <EulerImplicitSolver/>
  <CGLinearSolver/>
  <MechanicalObject name="state" position="0 0 0  1 0 0  0 1 0  0 0 1  1 1 1"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3  1 2 3 4"/>
  <FastTetrahedralCorotationalForceField youngModulus="100" poissonRatio="0.3"/>)";

TEST(SceneBuilder, MassesAndConstantForces) {
  auto system_of = [](const std::string& extra) { return build(kTet + extra).simulation.objects[0].system; };
  // UniformMass: totalMass wins over vertexMass and is shared equally.
  EXPECT_NEAR(system_of("<UniformMass totalMass=\"10\" vertexMass=\"7\"/>").mass.vertex_masses()[4], 2.0, 1e-15);
  EXPECT_NEAR(system_of("<UniformMass vertexMass=\"3\"/>").mass.total_mass(), 15.0, 1e-15);
  // MeshMatrixMass: consistent unless lumping; both weigh density × volume in total. The volumes
  // are 1/6 and 1/3 (vertices 1 2 3 4: |det| = 2), so the total is 3 × 1/2.
  const auto consistent = system_of("<MeshMatrixMass massDensity=\"3\"/>").mass;
  EXPECT_FALSE(consistent.is_lumped());
  EXPECT_NEAR(consistent.total_mass(), 1.5, 1e-14);
  const auto lumped = system_of("<MeshMatrixMass massDensity=\"3\" lumping=\"true\"/>").mass;
  EXPECT_TRUE(lumped.is_lumped());
  // Vertex 0 is only in the first tetrahedron: 3 × (1/6) / 4.
  EXPECT_NEAR(lumped.vertex_masses()[0], 0.125, 1e-15);
  // ConstantForceField: forces > force > totalForce; empty indices = every point.
  const auto all = system_of("<ConstantForceField totalForce=\"0 -10 0\"/>").constant_forces.at(0);
  ASSERT_EQ(all.indices.size(), 5u);
  EXPECT_EQ(all.forces[2], Vec3<double>(0, -2, 0));
  const auto per_index = system_of("<ConstantForceField indices=\"4 1\" forces=\"1 0 0  0 2 0\" force=\"9 9 9\"/>").constant_forces.at(0);
  EXPECT_EQ(per_index.indices, (std::vector<Index>{4, 1}));
  EXPECT_EQ(per_index.forces[1], Vec3<double>(0, 2, 0));
  const auto from_end = system_of("<ConstantForceField indices=\"0\" force=\"1 2 3\" indexFromEnd=\"1\"/>").constant_forces.at(0);
  EXPECT_EQ(from_end.indices, std::vector<Index>{4});
  EXPECT_EQ(system_of("<FixedProjectiveConstraint fixAll=\"true\"/>").fixed.size(), 5u);
}

TEST(SceneBuilder, LinksSearchUpwardAndFollowPaths) {
  const LoadedScene scene = build(R"(
  <RegularGridTopology name="grid" n="2 2 2" min="0 0 0" max="1 1 1"/>
  <Node name="object">
    <EulerImplicitSolver/>
    <CGLinearSolver/>
    <MechanicalObject position="@../grid.position" scale3d="2 2 2"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets"/>
    <UniformMass totalMass="1"/>
    <FastTetrahedralCorotationalForceField/>
    <BoxROI name="roi" box="-1 -1 -1 0.5 3 3"/>
    <FixedProjectiveConstraint indices="@/root/object/roi.indices"/>
  </Node>)");
  const auto& system = scene.simulation.objects[0].system;
  EXPECT_EQ(system.state.position[7], Vec3<double>(2, 2, 2));  // scaled grid corner
  EXPECT_EQ(system.fixed, (std::vector<Index>{0, 2, 4, 6}));    // x = 0 face
  EXPECT_EQ(system.force_fields[0]->mesh().num_tetrahedra(), 6);
}

TEST(SceneBuilder, RotationIsEulerXyzInDegrees) {
  // rotation="0 0 90": x axis → y axis.
  const LoadedScene scene = build(R"(
  <EulerImplicitSolver/>
  <CGLinearSolver/>
  <MechanicalObject position="1 0 0  0 0 0  0 1 0  0 0 1" rotation="0 0 90"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <UniformMass totalMass="1"/>)");
  const Vec3<double> p = scene.simulation.objects[0].system.state.position[0];
  EXPECT_LT((p - Vec3<double>(0, 1, 0)).norm(), 1e-15);
}

TEST(SceneBuilder, StaticSolverTakesItsNewtonSettings) {
  const LoadedScene scene = build(R"(
  <StaticSolver newtonSolver="@newton"/>
  <NewtonRaphsonSolver name="newton" maxNbIterationsNewton="7"/>
  <CGLinearSolver/>
  <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <FastTetrahedralCorotationalForceField/>)");
  EXPECT_NE(dynamic_cast<StaticSolver<double>*>(scene.simulation.objects[0].ode_solver.get()), nullptr);
}

TEST(SceneBuilder, IgnoredComponentsAndMappedNodesGetInfoLines) {
  const LoadedScene scene = build(kTet + R"(
  <UniformMass totalMass="1"/>
  <VisualStyle displayFlags="showBehaviorModels"/>
  <Node name="visual">
    <OglModel name="visual"/>
    <BarycentricMapping input="@.." output="@visual"/>
  </Node>)");
  ASSERT_GE(scene.info.size(), 2u);
  bool style = false, visual = false;
  for (const auto& line : scene.info) {
    style = style || (line.find("test.scn:") != std::string::npos && line.find("VisualStyle ignored") != std::string::npos);
    visual = visual || line.find("root/visual") != std::string::npos;
  }
  EXPECT_TRUE(style);
  EXPECT_TRUE(visual);
}

TEST(SceneBuilder, UnknownAttributesAreWarningsWithTheClosestNameOrErrorsWhenStrict) {
  const std::string body = kTet + "\n<UniformMass totalMass=\"1\" weight=\"3\" vertexMas=\"2\"/>";
  const std::string text = "<Node name=\"root\">\n" + body + "\n</Node>";
  const LoadedScene scene = build_scene(parse_scene_text(text, "test.scn"));
  ASSERT_EQ(scene.warnings.size(), 2u);
  // Attributes in name order: vertexMas, then weight.
  EXPECT_EQ(scene.warnings[0].rfind("test.scn:8: UniformMass: unknown attribute 'vertexMas' ignored (did you mean "
                                    "'vertexMass'?); supported: vertexMass, totalMass", 0), 0u) << scene.warnings[0];
  EXPECT_EQ(scene.warnings[1].find("did you mean"), std::string::npos) << scene.warnings[1];  // nothing close to weight
  // The attribute is ignored: the mass is totalMass's.
  EXPECT_DOUBLE_EQ(scene.simulation.objects[0].system.mass.vertex_masses()[0], 0.2);
  try {
    build_scene(parse_scene_text(text, "test.scn"), SceneOptions{true});
    ADD_FAILURE() << "strict checking accepted an unknown attribute";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("test.scn:8: UniformMass: unknown attribute 'vertexMas' (did you mean "
                                              "'vertexMass'?); supported: ", 0), 0u) << error.what();
  }
}

TEST(SceneBuilder, CollisionComponentsAreWarnedAsNotSimulated) {
  const std::string text = "<Node name=\"root\">\n<CollisionPipeline/>\n<Node name=\"b\">" + kTet +
                           "\n<UniformMass totalMass=\"1\"/>\n<TriangleCollisionModel/>\n</Node>\n</Node>";
  const LoadedScene scene = build_scene(parse_scene_text(text, "c.scn"));
  // A pipeline without its phases makes no contact in SOFA either: one warning saying so.
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0].rfind("c.scn:2: CollisionPipeline", 0), 0u) << scene.warnings[0];
  EXPECT_NE(scene.warnings[0].find("no broad phase: SOFA's pipeline makes no contact without it"), std::string::npos) << scene.warnings[0];
  // With its phases but no intersection method: each collision component says why nothing collides.
  const std::string phases = "<Node name=\"root\">\n<CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
                             "<CollisionResponse response=\"PenalityContactForceField\"/>\n<Node name=\"b\">" + kTet +
                             "\n<UniformMass totalMass=\"1\"/>\n<TriangleCollisionModel/>\n</Node>\n</Node>";
  const LoadedScene without = build_scene(parse_scene_text(phases, "c.scn"));
  ASSERT_EQ(without.warnings.size(), 5u);
  for (const auto& line : without.warnings) {
    EXPECT_NE(line.find("ignored: collisions and contacts are not simulated by fastcorot here: the scene has no intersection "
                        "method (MinProximityIntersection, NewProximityIntersection, LocalMinDistance or DiscreteIntersection)"),
              std::string::npos)
        << line;
  }
  EXPECT_THROW(build_scene(parse_scene_text(text, "c.scn"), SceneOptions{true}), Error);
}

TEST(SceneBuilder, ComponentsFastcorotDoesNotSimulateAreRefusedSayingWhy) {
  const std::string message = error_of(kTet + "\n<SparseGridTopology/>");
  EXPECT_NE(message.find("test.scn:8: SparseGridTopology: this scene needs what fastcorot does not have: "
                         "sparse grids (hexahedral FEM) are not simulated"),
            std::string::npos)
      << message;
  EXPECT_NE(error_of(kTet + "\n<HexahedronFEMForceField/>").find("HexahedronFEMForceField: its topology has no hexahedra"),
            std::string::npos);
  EXPECT_NE(error_of(kTet + "\n<StandardTetrahedralFEMForceField/>")
                .find("StandardTetrahedralFEMForceField: this scene needs what fastcorot does not have: hyperelastic FEM is not simulated"),
            std::string::npos);
  // SoftRobots.Inverse and ArticulatedSystemPlugin: one line naming what is missing, not the list of
  // every supported component.
  const std::string inverse = error_of(kTet + "\n<QPInverseProblemSolver/>");
  EXPECT_NE(inverse.find("QPInverseProblemSolver: this scene needs what fastcorot does not have: inverse models "
                         "(SoftRobots.Inverse) are not simulated: they need a QP solver"),
            std::string::npos)
      << inverse;
  EXPECT_EQ(inverse.find('\n'), std::string::npos) << inverse;
  EXPECT_NE(error_of(kTet + "\n<PositionEffector/>").find("inverse models (SoftRobots.Inverse)"), std::string::npos);
  EXPECT_NE(error_of(kTet + "\n<ArticulatedSystemMapping/>").find("articulated systems (ArticulatedSystemPlugin"),
            std::string::npos);
}

TEST(SceneBuilder, IndexListsTakeSofasRanges) {
  const LoadedScene scene = build(kTet + "\n<UniformMass totalMass=\"1\"/><FixedProjectiveConstraint indices=\"4-3 0-2-2\"/>");
  EXPECT_EQ(scene.simulation.objects[0].system.fixed, (std::vector<Index>{0, 2, 3, 4}));  // sorted
  EXPECT_NE(error_of(kTet + "\n<FixedProjectiveConstraint indices=\"1-x\"/>").find("'1-x' is not an index range"),
            std::string::npos);
}

TEST(SceneBuilder, UnknownComponentsSuggestTheClosestName) {
  const std::string message = error_of(kTet + "\n<TetrahedronFEMForcefield/>");
  EXPECT_NE(message.find("unknown component 'TetrahedronFEMForcefield' (did you mean 'TetrahedronFEMForceField'?)"),
            std::string::npos) << message;
}

TEST(SceneBuilder, BadScenesNameTheProblemAndTheLine) {
  auto expect = [](const std::string& body, std::initializer_list<std::string> needles) {
    const std::string message = error_of(body);
    for (const auto& needle : needles) EXPECT_NE(message.find(needle), std::string::npos) << "message: " << message << "\nlacks: " << needle;
  };
  expect(kTet + "\n<PolynomialSpringsForceField/>", {"test.scn:8", "unknown component 'PolynomialSpringsForceField'", "supported:"});
  expect(kTet + "\n<FixedProjectiveConstraint indices=\"@nowhere.indices\"/>", {"broken link '@nowhere.indices'", "test.scn:8"});
  expect(kTet + "\n<FixedProjectiveConstraint indices=\"9\"/>", {"index 9 out of range"});
  expect(R"(<EulerImplicitSolver/><CGLinearSolver/><MeshGmshLoader name="l" filename="absent.msh"/>
            <TetrahedronSetTopologyContainer src="@l"/><MechanicalObject/>)",
         {"MeshGmshLoader 'l'", "absent.msh"});
  expect(R"(<EulerImplicitSolver/><CGLinearSolver/><MechanicalObject position="0 0 0 1 0 0 0 1 0 0 0 1"/>
            <TetrahedronSetTopologyContainer/><FastTetrahedralCorotationalForceField/>)",
         {"has no tetrahedra"});
  expect(R"(<EulerImplicitSolver/><MechanicalObject position="0 0 0"/>)", {"no linear solver"});
  expect(R"(<MechanicalObject position="0 0 0"/>)", {"nothing to simulate"});
  expect(kTet + "<UniformMass totalMass=\"1\"/><FastTetrahedralCorotationalForceField method=\"svd\"/>", {"method = \"svd\""});
  expect(R"(<EulerImplicitSolver/><CGLinearSolver/><MechanicalObject position="0 0 x"/>)", {"'x' is not a finite number"});
  expect(R"(<EulerImplicitSolver/><CGLinearSolver/><MechanicalObject position="0 0 0  1 0 0  0 1 0  2 0 0"/>
            <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/><FastTetrahedralCorotationalForceField/>)",
         {"degenerate"});
}

// SOFA prunes a node whose `activated` is false from every visitor (Node::executeVisitor): its
// subtree is not initialised, simulated, collided or drawn, yet its components exist, so that a
// link into it still reads their data (TorusFall.scn deactivates five of its ten tori).
TEST(SceneBuilder, DeactivatedNodesAreLeftOutAsSofaPrunesThem) {
  std::string off = kSmallBeam, off_too = kSmallBeam;
  off.replace(off.find("name=\"beam\""), 11, "name=\"off\" activated=\"0\"");
  off.insert(off.find("</Node>"), "<CudaTetrahedronFEMForceField/><UniformMass totalMas=\"1\"/>");
  off_too.replace(off_too.find("name=\"beam\""), 11, "name=\"off_too\" activated=\"false\"");
  const std::string reader = R"(
  <Node name="reader">
    <EulerImplicitSolver/>
    <CGLinearSolver/>
    <MechanicalObject position="@../off/grid.position"/>
    <UniformMass totalMass="1"/>
  </Node>)";
  const std::string body = off + kSmallBeam + off_too + reader;
  for (const bool strict : {false, true}) {
    const LoadedScene scene = build_scene(parse_scene_text("<Node name=\"root\">" + body + "</Node>", "test.scn"),
                                          SceneOptions{strict});
    ASSERT_EQ(scene.simulation.objects.size(), 2u);
    EXPECT_EQ(scene.simulation.objects[0].path, "root/beam");
    EXPECT_EQ(scene.simulation.objects[1].path, "root/reader");
    // The link reads the deactivated node's grid: 3×2×2 points.
    EXPECT_EQ(scene.simulation.objects[1].system.state.position.size(), 12u);
    // Ranks count every object of the file, the deactivated ones included (as the Python layer
    // and the dumps number them): twelve in the deactivated node, then the beam's fourth.
    EXPECT_EQ(scene.state_objects.front(), 15u);
    EXPECT_TRUE(scene.warnings.empty());
    int deactivated = 0, lacking = 0;
    for (const auto& line : scene.info) {
      deactivated += line.find("node root/off is deactivated") != std::string::npos ||
                     line.find("node root/off_too is deactivated") != std::string::npos;
      lacking += line.find("CudaTetrahedronFEMForceField") != std::string::npos &&
                 line.find("(in a deactivated node)") != std::string::npos;
    }
    EXPECT_EQ(deactivated, 2);
    EXPECT_EQ(lacking, 1);
  }
  const std::string message = error_of(kSmallBeam + "<Node name=\"odd\" activated=\"maybe\"/>");
  EXPECT_NE(message.find("test.scn:"), std::string::npos) << message;
  EXPECT_NE(message.find("activated = \"maybe\""), std::string::npos) << message;
  EXPECT_THROW(build_scene(parse_scene_text("<Node name=\"root\" activated=\"0\">" + kSmallBeam + "</Node>", "t.scn")),
               Error);
}

}  // namespace
}  // namespace fastcorot

namespace fastcorot {
namespace {

TEST(ComponentTable, DocumentationFileIsUpToDate) {
  // docs/components.md is generated by `fastcorot components`; regenerate it when the table changes.
  std::ifstream in(std::string(FASTCOROT_SOURCE_DIR) + "/docs/components.md");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, component_documentation());
}

TEST(SceneBuilder, FixedPointsKeepTheirVelocityUnlessProjected) {
  // SOFA: a fixed point's velocity increment is zero, so an initial velocity persists (and moves it)
  // unless activate_projectVelocity zeroes it after each step (docs/sofa-solvers.md §5.3).
  const std::string body = R"(
  <EulerImplicitSolver/>
  <CGLinearSolver/>
  <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1" velocity="0 0 1"/>
  <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
  <UniformMass totalMass="1"/>
  <FastTetrahedralCorotationalForceField/>)";
  LoadedScene drifting = build(body + R"(<FixedProjectiveConstraint indices="0"/>)", "gravity=\"0 0 0\"");
  drifting.simulation.step();
  EXPECT_EQ(drifting.simulation.objects[0].system.state.velocity[0], Vec3<double>(0, 0, 1));
  EXPECT_EQ(drifting.simulation.objects[0].system.state.position[0], Vec3<double>(0, 0, 0.01));
  LoadedScene held = build(body + R"(<FixedProjectiveConstraint indices="0" activate_projectVelocity="true"/>)",
                           "gravity=\"0 0 0\"");
  held.simulation.step();
  EXPECT_EQ(held.simulation.objects[0].system.state.velocity[0], Vec3<double>(0, 0, 0));
}

// state_objects ranks every object of the tree in document order: here the root's VisualStyle is 0,
// the first beam's objects are 1..10 (its MechanicalObject 4th, rank 4), the second beam's 11..20.
TEST(SceneBuilder, StateObjectsRankTheMechanicalObjectInDocumentOrder) {
  std::string second = kSmallBeam;
  second.replace(second.find("name=\"beam\""), 11, "name=\"other\"");
  const LoadedScene scene = build("<VisualStyle/>" + kSmallBeam + second);
  ASSERT_EQ(scene.simulation.objects.size(), 2u);
  EXPECT_EQ(scene.simulation.objects[1].path, "root/other");
  EXPECT_EQ(scene.state_objects, (std::vector<std::size_t>{4, 14}));
}

TEST(SceneBuilder, CheckSceneObjectGivesTheBuildersMessages) {
  SceneObject object{"UniformMass", {{"totalMass", "1"}, {"weight", "3"}}, {"made.py", 12}};
  try {
    check_scene_object(object);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("made.py:12: UniformMass: unknown attribute 'weight'; supported: ", 0), 0u)
        << error.what();
  }
  object.type = "VisualStyle";  // ignored components take any attribute
  EXPECT_EQ(check_scene_object(object), nullptr);
  object = {"FixedConstraint", {{"indices", "0"}, {"drawSize", "2"}}, {}};  // an alias; a display option
  EXPECT_EQ(check_scene_object(object), find_component("FixedProjectiveConstraint"));
}

}  // namespace
}  // namespace fastcorot

namespace fastcorot {
namespace {

// A beam of 2×1×1 cells with a visual child node: an OBJ quad over the beam's top face (points
// inside the mesh's top face and one above it), placed by the OglModel's dx.
std::string visual_scene(const std::filesystem::path& dir, const std::string& first_topology,
                         const std::string& mapping) {
  std::ofstream(dir / "lid.obj") << "v 0.5 1 0.25\nv 1.5 1 0.25\nv 1.5 1 0.75\nv 0.5 1 0.75\nv 1 1.5 0.5\nf 1 2 3 4\nf 1 2 5\n";
  const std::string grid = R"(<RegularGridTopology name="grid" n="3 2 2" min="0 0 0" max="2 1 1"/>)";
  const std::string tets = R"(<TetrahedronSetTopologyContainer name="tets"/>)";
  return R"(<Node name="root" gravity="0 -10 0" dt="0.01">
  <Node name="beam">
    <EulerImplicitSolver/><EigenSimplicialLDLT/>
    )" + (first_topology == "grid" ? grid + tets : tets + grid) + R"(
    <MechanicalObject name="state"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
    <DiagonalMass massDensity="1" topology="@tets"/>
    <TetrahedronFEMForceField youngModulus="500" poissonRatio="0.3" topology="@tets"/>
    <FixedProjectiveConstraint indices="0 3 6 9"/>
    <Node name="Visu">
      <MeshOBJLoader name="loader" filename="lid.obj" translation="0 0 0"/>
      <OglModel name="Visual" src="@loader" color="red" dx="0" material="Default Diffuse 1 0 0.5 0 1"/>
      <)" + mapping + R"( input="@.." output="@Visual"/>
    </Node>
  </Node>
</Node>)";
}

class VisualSurfaces : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("fastcorot_visual_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  LoadedScene load(const std::string& text) {
    std::ofstream(dir_ / "scene.scn") << text;
    return load_scene_file(dir_ / "scene.scn");
  }
  std::filesystem::path dir_;
};

TEST_F(VisualSurfaces, AnOglModelFollowsItsObjectThroughTheMappingSofaWouldChoose) {
  for (const std::string first : {"tets", "grid"}) {
    SCOPED_TRACE(first);
    LoadedScene scene = load(visual_scene(dir_, first, "BarycentricMapping"));
    auto& object = scene.simulation.objects.at(0);
    ASSERT_EQ(object.visual_surfaces.size(), 1u);
    const VisualSurface& surface = object.visual_surfaces[0];
    EXPECT_EQ(surface.path, "root/beam/Visu/Visual");
    EXPECT_EQ(surface.mapping, first == "grid" ? "BarycentricMapping (trilinear, RegularGridTopology)"
                                               : "BarycentricMapping (tetrahedra)");
    ASSERT_EQ(surface.rest_points.size(), 5u);
    EXPECT_EQ(surface.triangles.size(), 3u);  // the quad as two triangles, then the triangle
    EXPECT_EQ(surface.color, (std::array<float, 4>{1, 0, 0, 1}));  // color wins over material
    // At rest the mapped points are the surface's own, inside and outside the beam.
    const auto rest = surface.points(object.system.state.position);
    for (std::size_t i = 0; i < rest.size(); ++i) EXPECT_LT((rest[i] - surface.rest_points[i]).norm(), 1e-12);
    // After steps they are the mapping of the state.
    for (int s = 0; s < 5; ++s) scene.simulation.step();
    const auto moved = surface.points(object.system.state.position);
    std::vector<Vec3<double>> expected(5);
    surface.map.apply(object.system.state.position, expected);
    EXPECT_EQ(moved, expected);
    EXPECT_GT((moved[1] - rest[1]).norm(), 1e-6);  // the free end moved, and the surface with it
  }
}

TEST_F(VisualSurfaces, AStateReadsASurfaceLoaderAndAStaticSurfaceUnderASolverStaysPut) {
  // SOFA's FrictionContact scenes: a box's surface (MechanicalObject src="@loader", no mass, no
  // force field) in the node of the solver that moves a falling body beside it.
  std::ofstream(dir_ / "box.obj") << "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nf 1 2 3\nf 1 3 4\n";
  LoadedScene scene = load(R"(<Node name="root" dt="0.01" gravity="0 -10 0">
  <Node name="solver"><EulerImplicitSolver/><CGLinearSolver iterations="50" tolerance="1e-12" threshold="1e-12"/>
    <Node name="body"><MechanicalObject position="5 5 5"/><UniformMass totalMass="1"/></Node>
    <Node name="BOX">
      <MeshOBJLoader name="loader" filename="box.obj" translation="1 0 0" scale="0.5"/>
      <MeshTopology src="@loader"/>
      <MechanicalObject name="surface" src="@loader"/>
    </Node>
  </Node>
</Node>)");
  ASSERT_EQ(scene.simulation.objects.size(), 1u);
  const auto& state = scene.simulation.objects[0].system.state;
  ASSERT_EQ(state.position.size(), 5u);  // the body's point, then the box's four, scaled then moved
  EXPECT_EQ(state.position[2], Vec3<double>(2, 0, 0));
  EXPECT_EQ(state.position[4], Vec3<double>(1, 0, 1));
  for (int step = 0; step < 10; ++step) scene.simulation.step();
  EXPECT_LT(state.position[0].y(), 5 - 0.04) << "the body falls (g t² / 2 = 0.05)";
  for (std::size_t i = 1; i < 5; ++i) EXPECT_EQ(state.velocity[i], Vec3<double>::Zero()) << "the box stays put";
  EXPECT_EQ(state.position[2], Vec3<double>(2, 0, 0));
  // A massless part something acts on is no still surface: refused as before (a force on it, or a
  // spring that ties it to the body).
  const std::string body = R"(<Node name="root" dt="0.01"><Node name="solver"><EulerImplicitSolver/><CGLinearSolver/>
    <Node name="body"><MechanicalObject name="p" position="5 5 5"/><UniformMass totalMass="1"/></Node>
    <Node name="handle"><MechanicalObject name="p" position="0 0 0"/>)";
  for (const std::string acting : {std::string(R"(<ConstantForceField force="1 0 0"/></Node>)"),
                                   std::string(R"(</Node><SpringForceField object1="@body/p" object2="@handle/p" spring="0 0 10 0 1"/>)"),
                                   // object1 by default the spring's own node's state (the handle's)
                                   std::string(R"(<StiffSpringForceField object2="@../body/p" spring="0 0 10 0 1"/></Node>)")}) {
    try {
      load(body + acting + "</Node></Node>");
      ADD_FAILURE() << acting;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("a mass on some of the objects"), std::string::npos) << e.what();
    }
  }
}

TEST_F(VisualSurfaces, IdentityMappingNeedsOnePointPerPointAndBadSurfacesAreErrors) {
  try {
    load(visual_scene(dir_, "tets", "IdentityMapping"));
    ADD_FAILURE() << "an identity mapping of 5 points onto 12 was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("the visual model has 5 points, the object 12"), std::string::npos)
        << error.what();
  }
  std::string missing = visual_scene(dir_, "tets", "BarycentricMapping");
  missing.replace(missing.find("lid.obj"), 7, "gone.obj");
  try {
    load(missing);
    ADD_FAILURE() << "a missing surface file was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("gone.obj: no such file"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fastcorot
