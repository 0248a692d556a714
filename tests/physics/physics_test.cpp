// Physics validation of the whole stack (topology -> force field -> mechanical system -> solvers):
// properties a correct finite element code must show whatever its implementation, as opposed to
// the number-for-number SOFA comparisons of tests/fem.
// - Patch test: linear tetrahedra reproduce an affine displacement field exactly (constant strain),
//   so an irregular mesh whose boundary follows an affine map must put its interior on that map.
// - Convergence: a slender cantilever under a small tip load approaches Euler-Bernoulli's
//   deflection P L^3 / (3 E I) as the mesh is refined (linear tetrahedra are stiff in bending).
// - Energy: backward Euler on an undamped elastic body never creates energy and dissipates some.
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/mass.h"
#include "fastcorot/sim/mechanical_system.h"
#include "fastcorot/sim/ode_solver.h"
#include "fastcorot/sim/sparse_direct_solver.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using Field = CorotationalForceField<double>;
using System = MechanicalSystem<double>;

struct TestMesh {
  std::shared_ptr<TetMesh> mesh;
  Points rest;
  RegularGrid grid;
};

TestMesh grid_mesh(std::array<Index, 3> n, Vec3<double> min, Vec3<double> max) {
  RegularGrid grid;
  grid.n = n;
  grid.min = min;
  grid.max = max;
  return {std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true)), grid_points<double>(grid),
          grid};
}

// Signed volume with the usual orientation (positive for grid_tetrahedra on min < max).
double volume(const Points& x, const Tetrahedron& t) {
  const auto& p0 = x[static_cast<std::size_t>(t[0])];
  return (x[static_cast<std::size_t>(t[1])] - p0)
             .dot((x[static_cast<std::size_t>(t[2])] - p0).cross(x[static_cast<std::size_t>(t[3])] - p0)) /
         6;
}

std::shared_ptr<Field> make_field(const TestMesh& m, RotationMethod method, double young, double poisson) {
  Field::Parameters parameters;
  parameters.young_modulus = {young};
  parameters.poisson_ratio = {poisson};
  parameters.method = method;
  return std::make_shared<Field>(m.mesh, m.rest, parameters);
}

// ---------------------------------------------------------------------------------------------
// Patch test

struct PatchResult {
  double relative_error = 0;  // max interior |x - (A p + c)| / max |A p + c - p|
  double displacement_scale = 0;
  bool converged = false;
  int interior_points = 0;
};

// A 4x4x4-point grid of unit cells whose 8 interior points are moved by up to 20% of the cell size
// (fixed seed); the boundary points are held on x = A p + c, the interior starts at rest.
PatchResult patch_test(RotationMethod method, const Mat3<double>& a, const Vec3<double>& c, int newton_iterations) {
  TestMesh m = grid_mesh({4, 4, 4}, Vec3<double>(0, 0, 0), Vec3<double>(3, 3, 3));
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<bool> boundary(m.rest.size());
  PatchResult result;
  for (Index k = 0; k < 4; ++k) {
    for (Index j = 0; j < 4; ++j) {
      for (Index i = 0; i < 4; ++i) {
        const auto v = static_cast<std::size_t>(i + 4 * (j + 4 * k));
        boundary[v] = i == 0 || i == 3 || j == 0 || j == 3 || k == 0 || k == 3;
        if (!boundary[v]) {
          m.rest[v] += Vec3<double>(u(rng), u(rng), u(rng));
          ++result.interior_points;
        }
      }
    }
  }
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
      // The solver never moves fixed points: they must be put on the map beforehand.
      system.state.position[v] = target[v];
    }
  }
  system.finalize();

  StaticSolver<double>::NewtonParameters newton;
  newton.max_iterations = newton_iterations;
  newton.relative_successive_threshold = 0;
  newton.relative_initial_threshold = 0;
  newton.absolute_residual_threshold = 1e-10;  // forces here are O(10)
  StaticSolver<double> solver(newton);
  SparseDirectSolver<double> linear;
  solver.step(system, linear, 0.0);
  result.converged = solver.converged();

  double error = 0;
  for (std::size_t v = 0; v < m.rest.size(); ++v) {
    error = std::max(error, (system.state.position[v] - target[v]).norm());
  }
  result.relative_error = error / result.displacement_scale;
  return result;
}

// A general map near the identity: det > 0, non-symmetric, entries within 5% of I.
Mat3<double> near_identity() {
  Mat3<double> a;
  a << 1.04, 0.03, -0.02,  //
      -0.01, 0.97, 0.045,  //
      0.025, -0.035, 1.02;
  return a;
}

Mat3<double> rotation_about(const Vec3<double>& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

TEST(PatchTest, LinearMethodReproducesAffineMapInOneNewtonStep) {
  const Mat3<double> a = near_identity();
  ASSERT_GT(a.determinant(), 0);
  const PatchResult r = patch_test(RotationMethod::none, a, Vec3<double>(0.1, -0.2, 0.05), 1);
  EXPECT_EQ(r.interior_points, 8);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.relative_error, 1e-9) << "displacement scale " << r.displacement_scale;
}

TEST(PatchTest, PolarMethodReproducesRotatedAffineMap) {
  // A large rotation on top of the small strain: polar extracts the same rotation in every
  // element (F = A is constant), so the corotated stress is uniform and in equilibrium.
  const Mat3<double> a = rotation_about(Vec3<double>(1, 2, -0.5), 0.7) * near_identity();
  for (int it : {10, 20, 30, 50, 100}) {
    const PatchResult q = patch_test(RotationMethod::polar, a, Vec3<double>(0.3, 0.1, -0.4), it);
    std::cout << it << " conv " << q.converged << " err " << q.relative_error << "\n";
  }
  const PatchResult r = patch_test(RotationMethod::polar, a, Vec3<double>(0.3, 0.1, -0.4), 10);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.relative_error, 1e-9) << "displacement scale " << r.displacement_scale;
}

TEST(PatchTest, PolarMethodReproducesSmallStrainAffineMap) {
  const PatchResult r = patch_test(RotationMethod::polar, near_identity(), Vec3<double>(0.1, -0.2, 0.05), 10);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.relative_error, 1e-9) << "displacement scale " << r.displacement_scale;
}

TEST(PatchTest, ProbeQrPolar2) {
  for (RotationMethod method : {RotationMethod::qr, RotationMethod::polar2}) {
    for (double scale : {1.0, 0.5, 0.25}) {
      Mat3<double> a = Mat3<double>::Identity() + scale * (near_identity() - Mat3<double>::Identity());
      const PatchResult r = patch_test(method, a, Vec3<double>(0.1, -0.2, 0.05), 20);
      std::cout << to_string(method) << " scale " << scale << " conv " << r.converged << " err "
                << r.relative_error << "\n";
      a = rotation_about(Vec3<double>(1, 2, -0.5), 0.7) * a;
      const PatchResult r2 = patch_test(method, a, Vec3<double>(0.1, -0.2, 0.05), 20);
      const PatchResult r3 = patch_test(method, (1 + 0.05 * scale) * rotation_about(Vec3<double>(1, 2, -0.5), 0.7), Vec3<double>(0.1, -0.2, 0.05), 20);
      std::cout << to_string(method) << " dilation " << scale << " conv " << r3.converged << " err "
                << r3.relative_error << "\n";
      std::cout << to_string(method) << " rot scale " << scale << " conv " << r2.converged << " err "
                << r2.relative_error << "\n";
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Cantilever

struct CantileverResult {
  double mean_face = 0;      // mean deflection of the x = L face points
  double centroid_line = 0;  // mean deflection of the x = L points on the line y = z = h/2 (if any)
};

CantileverResult cantilever(Index cells_across, bool consistent_load) {
  const double length = 10, width = 1, height = 1, young = 1000, load = 1e-3;
  const Index nx = 10 * cells_across + 1, n = cells_across + 1;
  const TestMesh m = grid_mesh({nx, n, n}, Vec3<double>(0, 0, 0), Vec3<double>(length, width, height));
  System system;
  system.state.position = m.rest;
  system.force_fields.push_back(make_field(m, RotationMethod::none, young, 0.0));
  ConstantForce<double> tip;
  std::vector<double> weight(m.rest.size(), 0.0);
  if (consistent_load) {
    // Uniform traction on the tip face: each boundary triangle gives a third of its area to each vertex.
    for (const auto& tri : m.mesh->boundary_triangles()) {
      const auto& v = tri.vertices;
      bool on_tip = true;
      for (Index i : v) on_tip = on_tip && m.rest[static_cast<std::size_t>(i)].x() == length;
      if (!on_tip) continue;
      const double area = (m.rest[static_cast<std::size_t>(v[1])] - m.rest[static_cast<std::size_t>(v[0])])
                              .cross(m.rest[static_cast<std::size_t>(v[2])] - m.rest[static_cast<std::size_t>(v[0])])
                              .norm() /
                          2;
      for (Index i : v) weight[static_cast<std::size_t>(i)] += area / 3 / (width * height);
    }
  }
  std::vector<Index> tip_points;
  for (std::size_t v = 0; v < m.rest.size(); ++v) {
    if (m.rest[v].x() == 0) system.fixed.push_back(static_cast<Index>(v));
    if (m.rest[v].x() == length) tip_points.push_back(static_cast<Index>(v));
  }
  for (Index v : tip_points) {
    const double w = consistent_load ? weight[static_cast<std::size_t>(v)] : 1.0 / static_cast<double>(tip_points.size());
    tip.indices.push_back(v);
    tip.forces.push_back(Vec3<double>(0, 0, -load * w));
  }
  system.constant_forces.push_back(tip);
  system.finalize();

  StaticSolver<double>::NewtonParameters newton;
  newton.max_iterations = 1;
  StaticSolver<double> solver(newton);
  SparseDirectSolver<double> linear;
  solver.step(system, linear, 0.0);

  const double inertia = width * height * height * height / 12;
  const double theory = load * length * length * length / (3 * young * inertia);
  CantileverResult result;
  int on_line = 0;
  for (Index v : tip_points) {
    const auto i = static_cast<std::size_t>(v);
    const double deflection = m.rest[i].z() - system.state.position[i].z();
    result.mean_face += deflection / static_cast<double>(tip_points.size());
    if (std::abs(m.rest[i].y() - width / 2) < 1e-12 && std::abs(m.rest[i].z() - height / 2) < 1e-12) {
      result.centroid_line += deflection;
      ++on_line;
    }
  }
  result.mean_face /= theory;
  result.centroid_line = on_line ? result.centroid_line / on_line / theory : std::nan("");
  return result;
}

TEST(Cantilever, Probe) {
  for (Index c : {2, 3, 4}) {
    const auto u = cantilever(c, false);
    const auto k = cantilever(c, true);
    std::cout << c << " uniform " << u.mean_face << " " << u.centroid_line << " consistent " << k.mean_face << " "
              << k.centroid_line << "\n";
  }
}

}  // namespace
}  // namespace fastcorot
