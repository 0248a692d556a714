// Simulation: SOFA's DefaultAnimationLoop over independent solver nodes (docs/sofa-solvers.md
// §5.2): each object integrated by its own ODE and linear solver, then time += dt; a non-finite or
// exploding state stops the run with an error naming the step, the time, the object and the vertex.
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/simulation.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/sim/sparse_direct_solver.h"
#include "support/deformations.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

using Field = CorotationalForceField<double>;
using Points = std::vector<Vec3<double>>;
using testing::flatten;

enum class Kind { euler_cg, euler_direct, static_direct };

std::shared_ptr<TetMesh> two_tets_mesh() {
  return std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{{0, 1, 2, 3}, {0, 2, 1, 4}});
}
Points two_tets_rest() {
  return {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1),
          Vec3<double>(0, 0, -2)};
}

// Two tetrahedra, points 0 and 1 fixed, under gravity, starting deformed with a velocity.
SimulatedObject<double> make_object(const std::string& path, Kind kind, unsigned seed) {
  SimulatedObject<double> object;
  object.path = path;
  object.mesh = two_tets_mesh();
  Field::Parameters p;
  p.young_modulus = {500.0 + 100.0 * seed};
  p.poisson_ratio = {0.3};
  auto& system = object.system;
  std::mt19937 rng(seed);
  system.state.position = testing::perturbed(two_tets_rest(), 0.05, rng);
  system.state.velocity = testing::perturbed(Points(5, Vec3<double>::Zero()), 0.2, rng);
  system.state.rest_position = two_tets_rest();
  system.force_fields.push_back(std::make_shared<Field>(object.mesh, two_tets_rest(), p));
  system.mass = Mass<double>::lumped({0.75, 0.75, 0.75, 0.25, 0.5});
  system.gravity = Vec3<double>(0, -9.81, 0);
  // The static object needs its rigid motions held: with points 0 and 1 alone, the rotation about
  // their axis is free, its stiffness singular, and the Newton step throws point 4 some 1e15 away
  // (which the divergence bound reports).
  system.fixed = kind == Kind::static_direct ? std::vector<Index>{0, 1, 2} : std::vector<Index>{0, 1};
  system.finalize();
  ImplicitEulerSolver<double>::Parameters euler;
  euler.rayleigh_stiffness = 0.1;
  euler.rayleigh_mass = 0.1;
  switch (kind) {
    case Kind::euler_cg:
      object.ode_solver = std::make_unique<ImplicitEulerSolver<double>>(euler);
      object.linear_solver = std::make_unique<ConjugateGradientSolver<double>>();
      break;
    case Kind::euler_direct:
      object.ode_solver = std::make_unique<ImplicitEulerSolver<double>>(euler);
      object.linear_solver = std::make_unique<SparseDirectSolver<double>>();
      break;
    case Kind::static_direct:
      object.ode_solver = std::make_unique<StaticSolver<double>>(StaticSolver<double>::NewtonParameters{});
      object.linear_solver = std::make_unique<SparseDirectSolver<double>>();
      break;
  }
  return object;
}

Simulation<double> three_objects(int threads = 1) {
  Simulation<double> simulation;
  simulation.dt = 0.02;
  simulation.threads = threads;
  simulation.objects.push_back(make_object("root/a", Kind::euler_cg, 1));
  simulation.objects.push_back(make_object("root/b", Kind::euler_direct, 2));
  simulation.objects.push_back(make_object("root/c", Kind::static_direct, 3));
  return simulation;
}

std::string message_of(Simulation<double>& simulation) {
  try {
    simulation.step();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "step() did not throw";
  return {};
}

TEST(Simulation, StepAdvancesEveryObjectAndCountsSteps) {
  auto simulation = three_objects();
  // The reference: the same objects stepped by hand, each with its own fresh solvers.
  std::vector<SimulatedObject<double>> reference;
  reference.push_back(make_object("a", Kind::euler_cg, 1));
  reference.push_back(make_object("b", Kind::euler_direct, 2));
  reference.push_back(make_object("c", Kind::static_direct, 3));
  EXPECT_EQ(simulation.steps_done(), 0);
  EXPECT_EQ(simulation.time(), 0.0);
  for (int step = 1; step <= 3; ++step) {
    StepReport expected;
    for (auto& object : reference) {
      const StepReport r = object.ode_solver->step(object.system, *object.linear_solver, 0.02);
      expected.linear_solves += r.linear_solves;
      expected.linear_iterations += r.linear_iterations;
    }
    const StepReport report = simulation.step();
    EXPECT_EQ(report.linear_solves, expected.linear_solves);
    EXPECT_EQ(report.linear_iterations, expected.linear_iterations);
    EXPECT_GT(report.linear_iterations, 0);  // the CG object iterates
    EXPECT_EQ(simulation.steps_done(), step);
    EXPECT_DOUBLE_EQ(simulation.time(), 0.02 * step);
    for (std::size_t o = 0; o < 3; ++o) {
      EXPECT_EQ(flatten(simulation.objects[o].system.state.position), flatten(reference[o].system.state.position))
          << "object " << o << " step " << step;
      EXPECT_EQ(flatten(simulation.objects[o].system.state.velocity), flatten(reference[o].system.state.velocity))
          << "object " << o << " step " << step;
    }
  }
  // Each object moved.
  for (std::size_t o = 0; o < 3; ++o) {
    EXPECT_NE(flatten(simulation.objects[o].system.state.position),
              flatten(make_object("x", Kind::euler_cg, static_cast<unsigned>(o + 1)).system.state.position));
  }
}

TEST(Simulation, ResultsDoNotDependOnTheThreadCount) {
  auto serial = three_objects(1);
  for (const int threads : {2, 3, 8}) {
    auto parallel = three_objects(threads);
    auto reference = three_objects(1);
    for (int step = 0; step < 4; ++step) {
      const StepReport a = reference.step();
      const StepReport b = parallel.step();
      EXPECT_EQ(a.linear_solves, b.linear_solves);
      EXPECT_EQ(a.linear_iterations, b.linear_iterations);
    }
    for (std::size_t o = 0; o < 3; ++o) {
      EXPECT_EQ(flatten(parallel.objects[o].system.state.position), flatten(reference.objects[o].system.state.position))
          << threads << " threads, object " << o;
    }
  }
}

TEST(Simulation, EmptySimulationStillCountsSteps) {
  Simulation<double> simulation;
  const StepReport report = simulation.step();
  EXPECT_EQ(report.linear_solves, 0);
  EXPECT_EQ(simulation.steps_done(), 1);
  EXPECT_DOUBLE_EQ(simulation.time(), 0.01);  // SOFA's default dt (docs/sofa-solvers.md §5.1)
}

TEST(Simulation, ZeroVelocityPointsAreProjectedAfterTheStep) {
  // activate_projectVelocity (docs/sofa-components.md §4, docs/sofa-solvers.md §5.2 step 6): the
  // solver first moves the fixed point 0 by h v0 (its velocity is untouched by the solve), then its
  // velocity is zeroed, so it stops drifting from the second step on.
  Simulation<double> simulation;
  simulation.dt = 0.02;
  simulation.objects.push_back(make_object("root/a", Kind::euler_direct, 4));
  auto& state = simulation.objects[0].system.state;
  simulation.objects[0].system.zero_velocity = {0};
  const Vec3<double> x0 = state.position[0], v0 = state.velocity[0];
  ASSERT_GT(v0.norm(), 0.0);
  simulation.step();
  EXPECT_LT((state.position[0] - (x0 + 0.02 * v0)).norm(), 1e-15);
  EXPECT_EQ(state.velocity[0], Vec3<double>::Zero());
  EXPECT_NE(state.velocity[1], Vec3<double>::Zero());  // fixed, not projected: keeps its velocity
  const Vec3<double> x1 = state.position[0];
  simulation.step();
  EXPECT_EQ(state.position[0], x1);
}

TEST(Simulation, NonFiniteVelocityDivergesAtStepOneNamingTheObject) {
  auto simulation = three_objects();
  const Points before_a = simulation.objects[0].system.state.position;
  simulation.objects[1].system.state.velocity[3].y() = std::numeric_limits<double>::quiet_NaN();
  const std::string message = message_of(simulation);
  EXPECT_NE(message.find("diverged at step 1"), std::string::npos) << message;
  EXPECT_NE(message.find("root/b"), std::string::npos) << message;
  EXPECT_EQ(message.find("root/a"), std::string::npos) << message;
  EXPECT_EQ(simulation.steps_done(), 0);
  // The other objects were advanced (simulation.h: "others are advanced").
  EXPECT_NE(flatten(simulation.objects[0].system.state.position), flatten(before_a));
}

TEST(Simulation, NonFinitePositionDiverges) {
  auto simulation = three_objects();
  simulation.objects[0].system.state.position[4].x() = std::numeric_limits<double>::infinity();
  const std::string message = message_of(simulation);
  EXPECT_NE(message.find("diverged at step 1"), std::string::npos) << message;
  EXPECT_NE(message.find("root/a"), std::string::npos) << message;
}

TEST(Simulation, DivergenceAtALaterStepNamesThatStep) {
  auto simulation = three_objects();
  simulation.step();
  simulation.step();
  simulation.objects[2].system.state.position[3].z() = std::numeric_limits<double>::quiet_NaN();
  const std::string message = message_of(simulation);
  EXPECT_NE(message.find("diverged at step 3"), std::string::npos) << message;
  EXPECT_NE(message.find("root/c"), std::string::npos) << message;
  EXPECT_EQ(simulation.steps_done(), 2);
}

TEST(Simulation, FirstFailureInSceneOrderIsReported) {
  for (const int threads : {1, 3}) {
    auto simulation = three_objects(threads);
    simulation.objects[2].system.state.velocity[2].x() = std::numeric_limits<double>::quiet_NaN();
    simulation.objects[1].system.state.velocity[2].x() = std::numeric_limits<double>::quiet_NaN();
    const std::string message = message_of(simulation);
    EXPECT_NE(message.find("root/b"), std::string::npos) << message;
  }
}

TEST(Simulation, SolverErrorsAreReportedWithStepAndObject) {
  // A point with neither mass nor element makes the direct solve singular.
  Simulation<double> simulation;
  SimulatedObject<double> object;
  object.path = "root/loose";
  object.system.state.position = {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0)};
  object.system.mass = Mass<double>::lumped({1.0, 0.0});
  object.system.gravity = Vec3<double>(0, -9.81, 0);
  object.system.finalize();
  object.ode_solver = std::make_unique<ImplicitEulerSolver<double>>(ImplicitEulerSolver<double>::Parameters{});
  object.linear_solver = std::make_unique<SparseDirectSolver<double>>();
  simulation.objects.push_back(std::move(object));
  const std::string message = message_of(simulation);
  EXPECT_NE(message.find("diverged at step 1"), std::string::npos) << message;
  EXPECT_NE(message.find("root/loose"), std::string::npos) << message;
  EXPECT_NE(message.find("factoris"), std::string::npos) << message;  // the solver's own message follows
}

TEST(Simulation, NonFiniteStatesNameTheVertexAndTheTime) {
  auto simulation = three_objects();
  simulation.step();
  // The static solver leaves velocities alone: vertex 3 of object c is the only non-finite one.
  simulation.objects[2].system.state.velocity[3].y() = std::numeric_limits<double>::infinity();
  const std::string message = message_of(simulation);
  // Step 2 of dt = 0.02: t = 0.04.
  EXPECT_NE(message.find("diverged at step 2 (t = 0.04"), std::string::npos) << message;
  EXPECT_NE(message.find("root/c vertex 3 has a non-finite velocity ("), std::string::npos) << message;
  EXPECT_NE(message.find(", inf, "), std::string::npos) << message;
  EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
}

TEST(Simulation, SceneSizeIsTheDiagonalOfTheRestBoundingBox) {
  // two_tets_rest spans (0, 0, -2) to (1, 1, 1): diagonal sqrt(1 + 1 + 9).
  auto simulation = three_objects();
  EXPECT_DOUBLE_EQ(simulation.scene_size(), std::sqrt(11.0));
  Simulation<double> empty;
  EXPECT_EQ(empty.scene_size(), 1.0);
}

TEST(Simulation, AVelocityThatCarriesAPointBeyondTheBoundStopsTheRunNamingIt) {
  // The static solver leaves velocities alone, so vertex 3 of object c keeps the velocity given
  // here: 1e9 scene sizes per step, finite but far beyond the default 1e6 sizes.
  auto simulation = three_objects();
  const double size = simulation.scene_size();
  simulation.objects[2].system.state.velocity[3] = Vec3<double>(0, 0, 1e9 * size / simulation.dt);
  const std::string message = message_of(simulation);
  EXPECT_NE(message.find("diverged at step 1 (t = 0.02"), std::string::npos) << message;
  EXPECT_NE(message.find("root/c vertex 3 has velocity"), std::string::npos) << message;
  EXPECT_NE(message.find("divergence bound"), std::string::npos) << message;
  EXPECT_EQ(simulation.steps_done(), 0);
}

TEST(Simulation, TheBoundIsAFactorOfTheSceneSizeAndCanBeTurnedOff) {
  // A point displaced by 50 scene sizes before the step: an implicit Euler step with a fixed
  // neighbour and an elastic pull moves it back by much less than that in one step of 0.02 s.
  for (const double factor : {10.0, 1000.0, 0.0}) {
    auto simulation = three_objects();
    simulation.divergence_factor = factor;
    auto& x = simulation.objects[1].system.state.position;
    x[4] += Vec3<double>(50 * simulation.scene_size(), 0, 0);
    bool threw = false;
    try {
      simulation.step();
    } catch (const Error& error) {
      threw = true;
      EXPECT_NE(std::string(error.what()).find("root/b vertex 4"), std::string::npos)
          << error.what();
    }
    EXPECT_EQ(threw, factor == 10.0) << "factor " << factor;
  }
}

TEST(Simulation, SetStepsDoneSetsTheTime) {
  Simulation<double> simulation;
  simulation.dt = 0.02;
  simulation.set_steps_done(7);
  EXPECT_EQ(simulation.steps_done(), 7);
  EXPECT_EQ(simulation.time(), 7 * 0.02);
  simulation.step();
  EXPECT_EQ(simulation.steps_done(), 8);
  EXPECT_THROW(simulation.set_steps_done(-1), Error);
}

}  // namespace
}  // namespace fastcorot
