// Small scenes the render tests draw, as inline SOFA XML fed through the real parser.
#pragma once

#include "fastcorot/scene/scene_builder.h"

#include <unistd.h>

#include <filesystem>
#include <string>

namespace fastcorot::testing {

// One tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1) with drawing on and four clearly different
// colours, point 0 fixed, and a BoxROI around point 0.
inline const std::string kDrawnTetrahedron = R"(
  <Node name="tet">
    <EulerImplicitSolver/>
    <EigenSimplicialLDLT/>
    <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
    <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
    <UniformMass vertexMass="1"/>
    <FastTetrahedralCorotationalForceField youngModulus="1000" poissonRatio="0.3" drawing="true"
        drawColor1="1 0 0 1" drawColor2="0 1 0" drawColor3="#0000ff" drawColor4="yellow"/>
    <BoxROI name="corner" box="-0.1 -0.1 -0.1 0.1 0.1 0.1"/>
    <FixedProjectiveConstraint indices="@corner.indices"/>
  </Node>)";

// Two hexahedral cells (3×2×2 grid points, 12 tetrahedra), drawing as `drawing` says.
inline std::string small_beam(const std::string& drawing = "false") {
  return R"(
  <Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    <EigenSimplicialLDLT/>
    <RegularGridTopology name="grid" n="3 2 2" min="0 0 0" max="2 1 1"/>
    <MechanicalObject name="state"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
    <DiagonalMass massDensity="2"/>
    <FastTetrahedralCorotationalForceField youngModulus="1000" poissonRatio="0.3" drawing=")" +
         drawing + R"("/>
    <BoxROI name="roi" box="-0.1 -0.1 -0.1 0.1 1.1 1.1"/>
    <FixedProjectiveConstraint indices="@roi.indices"/>
  </Node>)";
}

inline LoadedScene build_test_scene(const std::string& body,
                                    const std::string& root_attributes = "gravity=\"0 -9.81 0\"") {
  return build_scene(parse_scene_text(
      "<Node name=\"root\" " + root_attributes + ">\n" + body + "\n</Node>", "test.scn"));
}

// A path in the temporary folder that no other test process uses (tests run in parallel, and other
// build folders may run the same tests at the same time).
inline std::filesystem::path unique_temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("fastcorot_" + std::to_string(getpid()) + "_" + name);
}

}  // namespace fastcorot::testing
