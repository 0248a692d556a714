// Carrying a running simulation into the same scene built again with a node added
// (include/fastcorot/io/carried_state.h): what was running carries on bitwise as in an uninterrupted
// run, the new node starts from its scene data, and an object cut while running is refused by name.
#include "fastcorot/io/carried_state.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

const std::string kBeam = R"(<Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    <CGLinearSolver iterations="30" tolerance="1e-10" threshold="1e-20"/>
    <RegularGridTopology name="grid" n="3 3 3" min="0 0 0" max="1 1 2"/>
    <MechanicalObject/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets"/>
    <DiagonalMass massDensity="100"/>
    <FastTetrahedralCorotationalForceField youngModulus="2000" poissonRatio="0.3" method="large"/>
    <FixedProjectiveConstraint indices="0 1 2"/>
  </Node>
  <Node name="ball">
    <EulerImplicitSolver/>
    <EigenSimplicialLDLT/>
    <MechanicalObject template="Rigid3d" position="3 0 0  0 0 0.2588190451 0.9659258263" velocity="0 0 0  0 1 2"/>
    <UniformMass totalMass="1"/>
  </Node>)";
const std::string kDrop = R"(<Node name="drop">
    <EulerImplicitSolver/>
    <CGLinearSolver iterations="10" tolerance="1e-30" threshold="1e-30"/>
    <MechanicalObject position="5 5 5"/>
    <UniformMass totalMass="1"/>
  </Node>)";

LoadedScene build(const std::string& nodes) {
  return build_scene(parse_scene_text(R"(<Node name="root" dt="0.01" gravity="0 0 -9.81">)" + nodes + "</Node>", "carry.scn"));
}

TEST(CarriedState, ANodeAddedWhileRunningLeavesTheRestBitwiseAsUninterrupted) {
  LoadedScene running = build(kBeam), uninterrupted = build(kBeam);
  for (int s = 0; s < 7; ++s) running.simulation.step();
  LoadedScene grown = build(kBeam + kDrop);
  const CarriedState carried = carry_state(running.simulation, grown.simulation);
  EXPECT_EQ(carried.carried, (std::vector<std::string>{"root/beam", "root/ball"}));
  EXPECT_EQ(carried.fresh, (std::vector<std::string>{"root/drop"}));
  EXPECT_TRUE(carried.notes.empty());
  EXPECT_EQ(grown.simulation.steps_done(), 7);
  EXPECT_EQ(grown.simulation.objects[2].system.state.position[0], Vec3<double>(5, 5, 5));
  for (int s = 0; s < 7 + 8; ++s) uninterrupted.simulation.step();
  for (int s = 0; s < 8; ++s) grown.simulation.step();
  for (std::size_t o = 0; o < 2; ++o) {
    EXPECT_EQ(grown.simulation.objects[o].system.state.position, uninterrupted.simulation.objects[o].system.state.position) << o;
    EXPECT_EQ(grown.simulation.objects[o].system.state.velocity, uninterrupted.simulation.objects[o].system.state.velocity) << o;
  }
  EXPECT_EQ(grown.simulation.objects[1].system.rigids->orientation[0].coeffs(),
            uninterrupted.simulation.objects[1].system.rigids->orientation[0].coeffs());
  EXPECT_DOUBLE_EQ(grown.simulation.time(), uninterrupted.simulation.time());
}

TEST(CarriedState, AnObjectCutWhileRunningIsRefusedByName) {
  LoadedScene running = build(kBeam);
  running.simulation.step();
  auto& beam = running.simulation.objects[0];
  const std::vector<Index> cut{0};
  beam.system.remove_tetrahedra(*beam.mesh, cut);
  LoadedScene grown = build(kBeam + kDrop);
  try {
    carry_state(running.simulation, grown.simulation);
    ADD_FAILURE() << "a cut object was carried";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("root/beam: the scene was built again while running"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fastcorot
