// Physics validation of the whole stack (topology -> force field -> mechanical system -> solvers):
// properties any correct linear-tetrahedron code must show, beside the number-for-number SOFA
// comparisons of tests/fem. See tests/physics/README.md for the measured figures.
// - Patch test: linear tetrahedra represent an affine displacement exactly (constant strain), so an
//   irregular mesh whose boundary follows x = A p + c must put its free interior on that map.
// - Convergence: a slender cantilever under a small tip load approaches Euler-Bernoulli's deflection
//   P L^3 / (3 E I) from below as the mesh is refined (linear tetrahedra are too stiff in bending).
// - Energy: backward Euler on an undamped elastic body never creates energy; it dissipates some.
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/mass.h"
#include "fastcorot/sim/mechanical_system.h"
#include "fastcorot/sim/ode_solver.h"
#include "fastcorot/sim/sparse_direct_solver.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using Field = CorotationalForceField<double>;
using System = MechanicalSystem<double>;

struct TestMesh {
  std::shared_ptr<TetMesh> mesh;
  Points rest;
};

// A box of n[0]-1 × n[1]-1 × n[2]-1 cells, six tetrahedra per cell (SOFA's split with swapping).
TestMesh grid_mesh(std::array<Index, 3> n, const Vec3<double>& min, const Vec3<double>& max) {
  RegularGrid grid;
  grid.n = n;
  grid.min = min;
  grid.max = max;
  return {std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true)), grid_points<double>(grid)};
}

const Vec3<double>& at(const Points& x, Index v) { return x[static_cast<std::size_t>(v)]; }

// dot(p1 - p0, (p2 - p0) × (p3 - p0)) / 6: positive for the grid's tetrahedra.
double volume(const Points& x, const Tetrahedron& t) {
  const Vec3<double>& p0 = at(x, t[0]);
  return (at(x, t[1]) - p0).dot((at(x, t[2]) - p0).cross(at(x, t[3]) - p0)) / 6;
}

std::shared_ptr<Field> make_field(const TestMesh& m, RotationMethod method, double young, double poisson) {
  Field::Parameters parameters;
  parameters.young_modulus = {young};
  parameters.poisson_ratio = {poisson};
  parameters.method = method;
  return std::make_shared<Field>(m.mesh, m.rest, parameters);
}

Mat3<double> rotation_about(const Vec3<double>& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// ---------------------------------------------------------------------------------------------
// Patch test

struct PatchResult {
  double relative_error = 0;      // max over all points |x - (A p + c)| / displacement_scale
  double displacement_scale = 0;  // max over all points |A p + c - p|
  bool converged = false;
  int newton_iterations = 0;
  int interior_points = 0;
};

// A 4×4×4-point grid of unit cells whose 8 interior points are moved by up to 20% of the cell size
// per axis (fixed seed). Boundary points are fixed on x = A p + c, interior points start at rest and
// are found by a static Newton solve (no mass, no gravity).
PatchResult patch_test(RotationMethod method, const Mat3<double>& a, const Vec3<double>& c, int max_newton) {
  TestMesh m = grid_mesh({4, 4, 4}, Vec3<double>(0, 0, 0), Vec3<double>(3, 3, 3));
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> perturbation(-0.2, 0.2);
  std::vector<bool> boundary(m.rest.size());
  PatchResult result;
  for (Index k = 0; k < 4; ++k) {
    for (Index j = 0; j < 4; ++j) {
      for (Index i = 0; i < 4; ++i) {
        const auto v = static_cast<std::size_t>(i + 4 * (j + 4 * k));
        boundary[v] = i == 0 || i == 3 || j == 0 || j == 3 || k == 0 || k == 3;
        if (!boundary[v]) {
          m.rest[v] += Vec3<double>(perturbation(rng), perturbation(rng), perturbation(rng));
          ++result.interior_points;
        }
      }
    }
  }
  // The perturbation keeps every tetrahedron well shaped (smallest volume of the unperturbed grid is 1/6).
  for (const auto& t : m.mesh->tetrahedra()) EXPECT_GT(volume(m.rest, t), 0.01);

  System system;
  system.state.position = m.rest;
  system.force_fields.push_back(make_field(m, method, 1000.0, 0.3));
  Points target(m.rest.size());
  for (std::size_t v = 0; v < m.rest.size(); ++v) {
    target[v] = a * m.rest[v] + c;
    result.displacement_scale = std::max(result.displacement_scale, (target[v] - m.rest[v]).norm());
    if (boundary[v]) {
      system.fixed.push_back(static_cast<Index>(v));
      system.state.position[v] = target[v];  // fixed points are held where they are: put them on the map
    }
  }
  system.finalize();

  StaticSolver<double>::NewtonParameters newton;
  newton.max_iterations = max_newton;
  newton.relative_successive_threshold = 0;
  newton.relative_initial_threshold = 0;
  newton.absolute_residual_threshold = 1e-10;  // element forces are O(10) here: ~1e-11 relative
  StaticSolver<double> solver(newton);
  SparseDirectSolver<double> linear;
  result.newton_iterations = solver.step(system, linear, 0.0).linear_solves;
  result.converged = solver.converged();

  double error = 0;
  for (std::size_t v = 0; v < m.rest.size(); ++v) {
    error = std::max(error, (system.state.position[v] - target[v]).norm());
  }
  result.relative_error = error / result.displacement_scale;
  return result;
}

// A general map near the identity: non-symmetric (stretch, shear and a small rotation), det > 0,
// every entry within 5% of the identity's.
Mat3<double> near_identity() {
  Mat3<double> a;
  a << 1.04, 0.03, -0.02,  //
      -0.01, 0.97, 0.045,  //
      0.025, -0.035, 1.02;
  return a;
}

const Vec3<double> kShift(0.1, -0.2, 0.05);

TEST(PatchTest, LinearMethodReproducesGeneralAffineMapInOneNewtonStep) {
  ASSERT_GT(near_identity().determinant(), 0);
  const PatchResult r = patch_test(RotationMethod::none, near_identity(), kShift, 1);
  EXPECT_EQ(r.interior_points, 8);
  EXPECT_EQ(r.newton_iterations, 1);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.relative_error, 1e-9) << "displacement scale " << r.displacement_scale;
}

TEST(PatchTest, PolarMethodReproducesGeneralAffineMap) {
  const PatchResult r = patch_test(RotationMethod::polar, near_identity(), kShift, 30);
  EXPECT_TRUE(r.converged) << r.newton_iterations << " Newton iterations";
  EXPECT_LT(r.relative_error, 1e-9) << "displacement scale " << r.displacement_scale;
}

TEST(PatchTest, PolarMethodReproducesLargelyRotatedAffineMap) {
  // F = A is the same in every element, so polar extracts the same rotation everywhere and the
  // corotated stress is uniform. The tangent ignores dR/dx, so Newton converges linearly from the
  // interior left at rest under a 0.7 rad boundary rotation (12 iterations here).
  const Mat3<double> a = rotation_about(Vec3<double>(1, 2, -0.5), 0.7) * near_identity();
  const PatchResult r = patch_test(RotationMethod::polar, a, Vec3<double>(0.3, 0.1, -0.4), 30);
  EXPECT_TRUE(r.converged) << r.newton_iterations << " Newton iterations";
  EXPECT_LT(r.relative_error, 1e-9) << "displacement scale " << r.displacement_scale;
}

TEST(PatchTest, EdgeFrameMethodsReproduceRotatedDilation) {
  // qr and polar2 take their rotation from edges of the element, not from F: they find the true
  // rotation (the same in every element) only when the deformation is a rotation times a uniform
  // dilation, so that is the affine map they must reproduce exactly.
  const Mat3<double> a = 1.05 * rotation_about(Vec3<double>(1, 2, -0.5), 0.7);
  for (RotationMethod method : {RotationMethod::qr, RotationMethod::polar2}) {
    SCOPED_TRACE(to_string(method));
    const PatchResult r = patch_test(method, a, kShift, 30);
    EXPECT_TRUE(r.converged) << r.newton_iterations << " Newton iterations";
    EXPECT_LT(r.relative_error, 1e-9) << "displacement scale " << r.displacement_scale;
  }
}

TEST(PatchTest, EdgeFrameMethodsApproachGeneralAffineMapAsStrainVanishes) {
  // Under a general stretch and shear the qr and polar2 rotations differ from element to element
  // (SOFA's formulation; see tests/physics/README.md), so these methods do not pass the patch test
  // exactly. They are consistent: the relative error must vanish faster than the strain (measured:
  // ~4.6e-4 at 5% strain for qr, ~3.6e-4 for polar2, dividing by ~3 each time the strain halves).
  for (RotationMethod method : {RotationMethod::qr, RotationMethod::polar2}) {
    SCOPED_TRACE(to_string(method));
    double previous = 0;
    for (double scale : {1.0, 0.5, 0.25}) {
      const Mat3<double> a = Mat3<double>::Identity() + scale * (near_identity() - Mat3<double>::Identity());
      const PatchResult r = patch_test(method, a, kShift, 30);
      EXPECT_TRUE(r.converged);
      EXPECT_LT(r.relative_error, 1e-3 * scale);
      if (previous > 0) {
        EXPECT_LT(r.relative_error, previous / 2.5);
      }
      previous = r.relative_error;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Cantilever

// Tip deflection of a 10 × 1 × 1 beam (E = 1000, nu = 0, method none) of cubic cells, `across`
// cells across its section, clamped at x = 0 (every point there fixed), under a total load P along
// -z shared equally by the points of the x = L face; returned as the mean deflection of those
// points over Euler-Bernoulli's P L^3 / (3 E I), I = b h^3 / 12.
double cantilever_ratio(Index across) {
  const double length = 10, width = 1, height = 1, young = 1000, load = 1e-3;
  const TestMesh m = grid_mesh({10 * across + 1, across + 1, across + 1}, Vec3<double>(0, 0, 0),
                               Vec3<double>(length, width, height));
  System system;
  system.state.position = m.rest;
  system.force_fields.push_back(make_field(m, RotationMethod::none, young, 0.0));
  std::vector<Index> tip;
  for (std::size_t v = 0; v < m.rest.size(); ++v) {
    if (m.rest[v].x() == 0) system.fixed.push_back(static_cast<Index>(v));
    if (m.rest[v].x() == length) tip.push_back(static_cast<Index>(v));
  }
  EXPECT_EQ(tip.size(), static_cast<std::size_t>((across + 1) * (across + 1)));
  ConstantForce<double> tip_load;
  tip_load.indices = tip;
  tip_load.forces.assign(tip.size(), Vec3<double>(0, 0, -load / static_cast<double>(tip.size())));
  system.constant_forces.push_back(tip_load);
  system.finalize();

  StaticSolver<double> solver(StaticSolver<double>::NewtonParameters{});  // one Newton step: linear
  SparseDirectSolver<double> linear;
  solver.step(system, linear, 0.0);

  double deflection = 0;
  for (Index v : tip) deflection += at(m.rest, v).z() - at(system.state.position, v).z();
  deflection /= static_cast<double>(tip.size());
  const double inertia = width * height * height * height / 12;
  return deflection / (load * length * length * length / (3 * young * inertia));
}

TEST(Cantilever, TipDeflectionConvergesToEulerBernoulli) {
  // across: cells across the section (and 10 × across along the length).
  // issue: the figures quoted in the issue (approximate).
  // reference: an independent B^T D B assembly of the same linear tetrahedra, same mesh, load and
  //   clamp, solved with Eigen's SimplicialLDLT (written for this test, not part of the library).
  struct Row {
    Index across;
    double issue, reference;
  };
  const std::array<Row, 3> rows{{{2, 0.55, 0.576432}, {3, 0.77, 0.756033}, {4, 0.87, 0.848266}}};
  std::ostringstream table;
  table << "cells (x,y,z)   tip deflection / (P L^3 / 3EI)\n";
  double previous = 0;
  for (const Row& row : rows) {
    const double ratio = cantilever_ratio(row.across);
    table << std::setw(3) << 10 * row.across << " x " << row.across << " x " << row.across << "       "
          << std::fixed << std::setprecision(4) << ratio << "\n";
    RecordProperty("ratio_" + std::to_string(row.across) + "x" + std::to_string(row.across),
                   std::to_string(ratio));
    EXPECT_NEAR(ratio, row.reference, 2e-4) << row.across << " cells across";
    EXPECT_NEAR(ratio, row.issue, 0.05) << row.across << " cells across";
    EXPECT_GT(ratio, previous) << "no convergence at " << row.across << " cells across";
    EXPECT_LT(ratio, 1.0) << "linear tetrahedra cannot be softer than the beam";
    previous = ratio;
  }
  std::cout << table.str();
}

// ---------------------------------------------------------------------------------------------
// Energy

// A 4 × 1 × 1 beam (8 × 2 × 2 cells, E = 1000, nu = 0.3, density 1, lumped mass) released at rest
// from its rest shape stretched by 10% along x, integrated without damping or gravity. Returns
// kinetic + potential energy before the first step and after each step.
std::vector<double> release_stretched_beam(RotationMethod method, bool clamp_one_end, int steps, double dt) {
  const TestMesh m = grid_mesh({9, 3, 3}, Vec3<double>(0, 0, 0), Vec3<double>(4, 1, 1));
  System system;
  system.state.position = m.rest;
  for (auto& x : system.state.position) x.x() *= 1.1;  // points at x = 0 stay on their rest place
  system.force_fields.push_back(make_field(m, method, 1000.0, 0.3));
  system.mass = Mass<double>::lumped(tetrahedral_lumped_masses<double>(*m.mesh, m.rest, 1.0));
  if (clamp_one_end) {
    for (std::size_t v = 0; v < m.rest.size(); ++v) {
      if (m.rest[v].x() == 0) system.fixed.push_back(static_cast<Index>(v));
    }
  }
  system.finalize();
  ImplicitEulerSolver<double> solver(ImplicitEulerSolver<double>::Parameters{});  // rs = rm = 0
  SparseDirectSolver<double> linear;
  std::vector<double> energy{system.kinetic_energy() + system.potential_energy(system.state.position)};
  for (int step = 0; step < steps; ++step) {
    solver.step(system, linear, dt);
    energy.push_back(system.kinetic_energy() + system.potential_energy(system.state.position));
  }
  return energy;
}

void expect_dissipative(const std::vector<double>& energy) {
  ASSERT_GT(energy.front(), 0);
  for (std::size_t i = 1; i < energy.size(); ++i) {
    ASSERT_TRUE(std::isfinite(energy[i])) << "step " << i;
    ASSERT_LE(energy[i], energy[i - 1] + 1e-12 * energy.front())
        << "energy grew at step " << i << ": " << energy[i - 1] << " -> " << energy[i];
  }
  EXPECT_LT(energy.back(), 0.9 * energy.front()) << "backward Euler must dissipate";
}

TEST(Energy, NeverGrowsUnderImplicitEulerLinear) {
  const std::vector<double> clamped = release_stretched_beam(RotationMethod::none, true, 200, 1e-3);
  // 1/2 (lambda + 2 mu) 0.1^2 × volume 4 for E = 1000, nu = 0.3 (uniaxial strain: no lateral motion).
  EXPECT_NEAR(clamped.front(), 0.5 * (1000 * 0.3 / (1.3 * 0.4) + 1000 / 1.3) * 0.01 * 4, 1e-9);
  expect_dissipative(clamped);
  SCOPED_TRACE("free beam");
  expect_dissipative(release_stretched_beam(RotationMethod::none, false, 200, 1e-3));
}

TEST(Energy, NeverGrowsUnderImplicitEulerCorotational) {
  for (RotationMethod method : {RotationMethod::polar, RotationMethod::qr, RotationMethod::polar2}) {
    SCOPED_TRACE(to_string(method));
    expect_dissipative(release_stretched_beam(method, true, 200, 1e-3));
  }
}

TEST(Energy, LinearImplicitEulerLosesExactlyTheBackwardEulerDissipation) {
  // For a linear system one backward Euler step loses exactly
  //   E_n - E_{n+1} = 1/2 |v_{n+1} - v_n|_M^2 + 1/2 |x_{n+1} - x_n|_{-K}^2
  // (expand E_{n+1} with v_{n+1} = v_n + h M^-1 f(x_{n+1}), x_{n+1} = x_n + h v_{n+1}).
  const TestMesh m = grid_mesh({9, 3, 3}, Vec3<double>(0, 0, 0), Vec3<double>(4, 1, 1));
  System system;
  system.state.position = m.rest;
  for (auto& x : system.state.position) x.x() *= 1.1;
  system.force_fields.push_back(make_field(m, RotationMethod::none, 1000.0, 0.3));
  system.mass = Mass<double>::lumped(tetrahedral_lumped_masses<double>(*m.mesh, m.rest, 1.0));
  for (std::size_t v = 0; v < m.rest.size(); ++v) {
    if (m.rest[v].x() == 0) system.fixed.push_back(static_cast<Index>(v));
  }
  system.finalize();
  ImplicitEulerSolver<double> solver(ImplicitEulerSolver<double>::Parameters{});
  SparseDirectSolver<double> linear;
  const std::size_t n = m.rest.size();
  Points dx(n), dv(n), k_dx(n);
  double energy = system.kinetic_energy() + system.potential_energy(system.state.position);
  const double initial = energy;
  for (int step = 0; step < 50; ++step) {
    const Points x0 = system.state.position, v0 = system.state.velocity;
    solver.step(system, linear, 2e-3);
    for (std::size_t i = 0; i < n; ++i) {
      dx[i] = system.state.position[i] - x0[i];
      dv[i] = system.state.velocity[i] - v0[i];
    }
    std::fill(k_dx.begin(), k_dx.end(), Vec3<double>::Zero());
    system.force_fields[0]->add_dforce(dx, k_dx, -1.0);  // -K dx (K = df/dx)
    double expected_loss = system.mass.kinetic_energy(dv);
    for (std::size_t i = 0; i < n; ++i) expected_loss += 0.5 * dx[i].dot(k_dx[i]);
    const double next = system.kinetic_energy() + system.potential_energy(system.state.position);
    EXPECT_GT(expected_loss, 0);
    EXPECT_NEAR(energy - next, expected_loss, 1e-12 * initial) << "step " << step;
    energy = next;
  }
}

}  // namespace
}  // namespace fastcorot
