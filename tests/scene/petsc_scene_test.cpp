// Scenes with fastcorot's PETScLinearSolver through the real parser and builder: its attributes
// reach the solver, bad values name the component, and the whole scene steps as the sparse direct
// solve does. Without PETSc in the build the component is a clear error.
#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/petsc_linear_solver.h"
#include "support/scene_text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

namespace fastcorot {
namespace {

std::string beam(const std::string& solver) {
  return R"(<Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    )" + solver + R"(
    <RegularGridTopology name="grid" n="5 2 2" min="0 0 0" max="4 1 1"/>
    <MechanicalObject name="state"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
    <DiagonalMass massDensity="2"/>
    <FastTetrahedralCorotationalForceField youngModulus="1000" poissonRatio="0.3" method="large"/>
    <BoxROI name="roi" box="-0.5 -1 -1 0.5 2 2"/>
    <FixedProjectiveConstraint indices="@roi.indices"/>
  </Node>)";
}

#ifdef FASTCOROT_WITH_PETSC

// The largest distance between the two scenes' first objects' points, and the largest
// displacement of the second's.
std::pair<double, double> compare(const LoadedScene& first, const LoadedScene& second) {
  const auto& a = first.simulation.objects.at(0).system.state;
  const auto& b = second.simulation.objects.at(0).system.state;
  double difference = 0, displacement = 0;
  for (std::size_t i = 0; i < a.position.size(); ++i) {
    difference = std::max(difference, (a.position[i] - b.position[i]).norm());
    displacement = std::max(displacement, (b.position[i] - b.rest_position[i]).norm());
  }
  return {difference, displacement};
}

TEST(PetscScene, AttributesReachTheSolver) {
  LoadedScene scene = testing::build_scene_text(
      beam(R"(<PETScLinearSolver ksp="minres" pc="jacobi" tolerance="1e-9" maxIterations="77" rebuildEvery="3" nearNullSpace="false"/>)"),
      R"(dt="0.02" gravity="0 0 -5")");
  const auto* solver = dynamic_cast<const PetscLinearSolver*>(scene.simulation.objects.at(0).linear_solver.get());
  ASSERT_NE(solver, nullptr);
  EXPECT_EQ(solver->parameters().ksp, "minres");
  EXPECT_EQ(solver->parameters().pc, "jacobi");
  EXPECT_EQ(solver->parameters().tolerance, 1e-9);
  EXPECT_EQ(solver->parameters().max_iterations, 77);
  EXPECT_EQ(solver->parameters().rebuild_every, 3);
  EXPECT_FALSE(solver->parameters().near_null_space);
}

TEST(PetscScene, StepsAsTheSparseDirectSolveDoes) {
  LoadedScene petsc = testing::build_scene_text(beam(R"(<PETScLinearSolver tolerance="1e-13"/>)"), R"(dt="0.02" gravity="0 0 -5")");
  LoadedScene direct = testing::build_scene_text(beam("<EigenSimplicialLDLT/>"), R"(dt="0.02" gravity="0 0 -5")");
  for (int step = 0; step < 10; ++step) {
    petsc.simulation.step();
    direct.simulation.step();
  }
  const auto [difference, displacement] = compare(petsc, direct);
  EXPECT_GT(displacement, 1e-3);
  EXPECT_LT(difference, 1e-9 * displacement);
}

// The static Newton-Raphson solve of examples/cylinder_static.scn with PETSc instead of the direct
// solver: the same equilibrium.
TEST(PetscScene, StaticNewtonRaphsonAsWithTheDirectSolver) {
  const std::string path = std::string(FASTCOROT_EXAMPLES_DIR) + "/cylinder_static.scn";
  std::ifstream file(path);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::string direct_line = R"(<EigenSimplicialLDLT template="CompressedRowSparseMatrixMat3x3d"/>)";
  std::string petsc_text = text;
  ASSERT_NE(petsc_text.find(direct_line), std::string::npos);
  petsc_text.replace(petsc_text.find(direct_line), direct_line.size(), R"(<PETScLinearSolver tolerance="1e-12"/>)");
  LoadedScene petsc = build_scene(parse_scene_text(petsc_text, path));
  LoadedScene direct = build_scene(parse_scene_text(text, path));
  petsc.simulation.step();
  direct.simulation.step();
  const auto [difference, displacement] = compare(petsc, direct);
  EXPECT_GT(displacement, 1e-3);
  EXPECT_LT(difference, 1e-8 * displacement);
}

TEST(PetscScene, BadValuesNameTheComponent) {
  for (const std::string& solver : {std::string(R"(<PETScLinearSolver maxIterations="0"/>)"),
                                    std::string(R"(<PETScLinearSolver tolerance="-1"/>)"),
                                    std::string(R"(<PETScLinearSolver pc="no_such_pc"/>)"),
                                    std::string(R"(<PETScLinearSolver rebuildEvery="-1"/>)"),
                                    std::string(R"(<PETScLinearSolver rebuildGrowth="0.5"/>)")}) {
    const std::string message = testing::scene_error(beam(solver));
    EXPECT_NE(message.find("test.scn:4: PETScLinearSolver"), std::string::npos) << solver << ": " << message;
  }
}

#else

TEST(PetscScene, IsAClearErrorWithoutPetsc) {
  const std::string message = testing::scene_error(beam("<PETScLinearSolver/>"));
  EXPECT_NE(message.find("built without PETSc"), std::string::npos) << message;
}

#endif

}  // namespace
}  // namespace fastcorot
