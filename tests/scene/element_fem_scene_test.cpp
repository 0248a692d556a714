// SOFA master's element FEM family in scenes (CorotationalFEMForceField, LinearSmallStrainFEMForceField,
// FEMMass, NodalMassDensity, ConstantSparsityPatternSystem), through the real parser and builder, on
// small versions of SOFA's examples/Validation/cantilever_beam scenes (SOFA commit 2a278d891f): the
// force field in a child node without a MechanicalObject, the mass on the grid's hexahedra.
#include "fastcorot/fem/element_fem_force_field.h"
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const std::string kDirect = R"(<ConstantSparsityPatternSystem template="CompressedRowSparseMatrix" name="A" checkIndices="false"/>
    <NaturalOrderingMethod/>
    <SparseLDLSolver name="linear_solver" template="CompressedRowSparseMatrix"/>)";
const std::string kIterative = R"(<CGLinearSolver iterations="5000" tolerance="1e-30" threshold="1e-30"/>)";

std::string beam(const std::string& solver, const std::string& field, const std::string& mass = "") {
  return R"(<EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    <RegularGridTopology name="grid" min="-0.01 -0.01 0" max="0.01 0.01 0.2" n="3 3 6"/>
    <MechanicalObject template="Vec3" name="state"/>
    )" + (mass.empty() ? std::string(R"(<NodalMassDensity property="1100"/>
    <FEMMass template="Vec3,Hexahedron"/>)") : mass) + R"(
    <BoxROI name="box_roi" box="-0.011 -0.011 -0.0001 0.011 0.011 0.0001"/>
    <FixedProjectiveConstraint indices="@box_roi.indices"/>
    )" + solver + field;
}

std::string tetrahedra(const std::string& attributes, const std::string& type = "CorotationalFEMForceField") {
  return R"(<Node name="fem">
      <TetrahedronSetTopologyContainer name="Tetra_topo"/>
      <TetrahedronSetTopologyModifier name="Modifier"/>
      <Hexa2TetraTopologicalMapping input="@grid" output="@Tetra_topo" swapping="true"/>
      <)" + type + R"( name="FEM" template="Vec3,Tetrahedron" youngModulus="2e6" poissonRatio="0.45"
          topology="@Tetra_topo" )" + attributes + R"(/>
    </Node>)";
}

std::string hexahedra(const std::string& attributes, const std::string& type = "CorotationalFEMForceField") {
  return "<" + type + R"( name="FEM" template="Vec3,Hexahedron" youngModulus="2e6" poissonRatio="0.45" topology="@grid" )" +
         attributes + "/>";
}

std::vector<Vec3<double>> run(const std::string& body, int steps = 10) {
  LoadedScene scene = build_scene_text(body, R"(dt="0.01" gravity="0 -9.81 0")");
  for (int s = 0; s < steps; ++s) scene.simulation.step();
  return scene.simulation.objects.at(0).system.state.position;
}

double difference(const std::vector<Vec3<double>>& a, const std::vector<Vec3<double>>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

TEST(ElementFemScene, BuildsSofasValidationLayout) {
  LoadedScene scene = build_scene_text(beam(kDirect, tetrahedra(R"(computeForceStrategy="parallel")")));
  const auto& system = scene.simulation.objects.at(0).system;
  ASSERT_EQ(system.force_fields.size(), 1u);
  EXPECT_EQ(system.force_fields[0]->component(), "CorotationalFEMForceField");
  EXPECT_EQ(system.force_fields[0]->method_name(), "triangle");
  EXPECT_EQ(system.force_fields[0]->mesh().num_tetrahedra(), 2 * 2 * 5 * 6);
  // FEMMass on the grid: rho x the beam's volume.
  EXPECT_NEAR(system.mass.total_mass(), 1100 * 0.02 * 0.02 * 0.2, 1e-12);
  EXPECT_FALSE(system.mass.is_lumped());
  LoadedScene hex = build_scene_text(beam(kDirect, hexahedra("", "LinearSmallStrainFEMForceField")));
  EXPECT_EQ(hex.simulation.objects.at(0).system.force_fields[0]->component(), "LinearSmallStrainFEMForceField");
}

TEST(ElementFemScene, SequencedAndParallelGiveTheSameBits) {
  for (const auto& field : {std::string("tetrahedra"), std::string("hexahedra")}) {
    const auto make = [&](const std::string& strategy) {
      const std::string a = "computeForceStrategy=\"" + strategy + "\" computeForceDerivStrategy=\"" + strategy + "\"";
      return beam(kIterative, field == "tetrahedra" ? tetrahedra(a) : hexahedra(a));
    };
    EXPECT_EQ(difference(run(make("sequenced"), 3), run(make("parallel"), 3)), 0.0) << field;
  }
}

TEST(ElementFemScene, AssembledAndMatrixFreeAgree) {
  // SparseLDLSolver solves with the assembled R K R^T; CG with add_dforce (run to convergence).
  for (const auto& type : {std::string("CorotationalFEMForceField"), std::string("LinearSmallStrainFEMForceField")}) {
    const auto direct = run(beam(kDirect, hexahedra("", type)), 5);
    const auto iterative = run(beam(kIterative, hexahedra("", type)), 5);
    EXPECT_LT(difference(direct, iterative), 1e-10) << type;
    const auto tet_direct = run(beam(kDirect, tetrahedra("", type)), 5);
    const auto tet_iterative = run(beam(kIterative, tetrahedra("", type)), 5);
    EXPECT_LT(difference(tet_direct, tet_iterative), 1e-10) << type;
  }
}

TEST(ElementFemScene, BadInputNamesTheComponentAndAttribute) {
  const std::string half = R"(<CorotationalFEMForceField template="Vec3,Hexahedron" poissonRatio="0.5" topology="@grid"/>)";
  const std::string half_error = scene_error(beam(kDirect, half));
  EXPECT_NE(half_error.find("CorotationalFEMForceField"), std::string::npos) << half_error;
  EXPECT_NE(half_error.find("oisson"), std::string::npos) << half_error;
  const std::string wrong_template =
      R"(<CorotationalFEMForceField template="Vec3,Triangle" youngModulus="1e6" poissonRatio="0.3" topology="@grid"/>)";
  EXPECT_NE(scene_error(beam(kDirect, wrong_template)).find("template \"Vec3,Triangle\""), std::string::npos);
  const std::string no_template = R"(<CorotationalFEMForceField youngModulus="1e6" poissonRatio="0.3"/>)";
  EXPECT_NE(scene_error(beam(kDirect, no_template)).find("template is missing"), std::string::npos);
  // Hexahedra asked of a tetrahedral topology.
  const std::string hex_on_tets = R"(<Node name="fem"><TetrahedronSetTopologyContainer name="t"/>
      <Hexa2TetraTopologicalMapping input="@grid" output="@t"/>
      <CorotationalFEMForceField template="Vec3,Hexahedron" topology="@t"/></Node>)";
  EXPECT_NE(scene_error(beam(kDirect, hex_on_tets)).find("no hexahedra"), std::string::npos);
  EXPECT_NE(scene_error(beam(kDirect, hexahedra(R"(rotationMethod="triangle")"))).find("rotationMethod"), std::string::npos);
  EXPECT_NE(scene_error(beam(kDirect, hexahedra(R"(computeForceStrategy="gpu")"))).find("computeForceStrategy"),
            std::string::npos);
  // FEMMass without a NodalMassDensity.
  EXPECT_NE(scene_error(beam(kDirect, hexahedra(""), R"(<FEMMass template="Vec3,Hexahedron"/>)")).find("NodalMassDensity"),
            std::string::npos);
}

TEST(ElementFemScene, NodalDensitiesPerNode) {
  // property shorter than the points: the last value for the others (SOFA's BaseNodalProperty).
  LoadedScene uniform = build_scene_text(
      beam(kDirect, hexahedra(""), R"(<NodalMassDensity name="rho" property="3"/><FEMMass template="Vec3,Hexahedron" nodalMassDensity="@rho"/>)"));
  LoadedScene listed = build_scene_text(
      beam(kDirect, hexahedra(""), R"(<NodalMassDensity name="rho" property="3 3 3"/><FEMMass template="Vec3,Hexahedron"/>)"));
  EXPECT_NEAR(uniform.simulation.objects[0].system.mass.total_mass(), 3 * 0.02 * 0.02 * 0.2, 1e-14);
  EXPECT_NEAR(listed.simulation.objects[0].system.mass.total_mass(), 3 * 0.02 * 0.02 * 0.2, 1e-14);
}

}  // namespace
}  // namespace fastcorot
