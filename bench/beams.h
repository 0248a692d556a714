// The benchmark beams of issue 5 (examples/cantilever_beam_*.scn): a RegularGrid split into
// tetrahedra as Hexa2TetraTopologicalMapping does, E = 2000, nu = 0.3, deformed as a bent beam so
// that rotations are not trivial.
#pragma once

#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/topology/regular_grid.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace fastcorot::bench {

struct Beam {
  std::string name;
  std::array<Index, 3> n;
};

inline const std::vector<Beam>& beams() {
  static const std::vector<Beam> all = {{"40x10x10", {40, 10, 10}}, {"76x16x16", {76, 16, 16}}};
  return all;
}

inline constexpr RotationMethod kMethods[] = {RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2,
                                              RotationMethod::none};

// "what/beam/method/real/threads:N": the names the README's filters select on.
inline std::string benchmark_name(const std::string& what, const Beam& beam, RotationMethod method,
                                  const char* real_name, int threads) {
  return what + "/" + beam.name + "/" + to_string(method) + "/" + real_name + "/threads:" + std::to_string(threads);
}

// main() of a benchmark program once its benchmarks are registered.
inline int run_registered_benchmarks(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// main() of a benchmark program whose register_all<Real>(real_name) registers its benchmarks.
template <class Registrar>
int run_benchmarks(int argc, char** argv, Registrar register_all) {
  register_all(double(), "double");
  register_all(float(), "float");
  return run_registered_benchmarks(argc, argv);
}

template <class Real>
struct BeamField {
  std::shared_ptr<TetMesh> mesh;
  std::vector<Vec3<Real>> rest, x, dx, out;
  std::unique_ptr<CorotationalForceField<Real>> field;
};

template <class Real>
BeamField<Real> make_beam_field(const Beam& beam, RotationMethod method, int threads) {
  RegularGrid grid;
  grid.n = beam.n;
  grid.min = Vec3<double>(0, 6, -2);
  grid.max = Vec3<double>(16, 10, 2);
  BeamField<Real> b;
  b.mesh = std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true));
  b.rest = grid_points<Real>(grid);
  typename CorotationalForceField<Real>::Parameters parameters;
  parameters.young_modulus = {Real(2000)};
  parameters.poisson_ratio = {Real(0.3)};
  parameters.method = method;
  b.field = std::make_unique<CorotationalForceField<Real>>(b.mesh, b.rest, parameters);
  b.field->set_threads(threads);
  // Bend the beam about z (a quarter of a radian at the free end) with a small twist.
  b.x = b.rest;
  for (auto& p : b.x) {
    const Real angle = Real(0.25) * p.x() / Real(16);
    const Real radius = Real(64) + p.y();
    p = Vec3<Real>(radius * std::sin(angle), radius * std::cos(angle) - Real(58), p.z() * (1 + Real(0.01) * angle));
  }
  b.dx.resize(b.x.size());
  for (std::size_t i = 0; i < b.dx.size(); ++i) {
    b.dx[i] = Vec3<Real>(Real(std::sin(0.1 * i)), Real(std::cos(0.3 * i)), Real(std::sin(0.7 * i)));
  }
  b.out.assign(b.x.size(), Vec3<Real>::Zero());
  return b;
}

}  // namespace fastcorot::bench
