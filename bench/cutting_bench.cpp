// Cutting (issue 8): the time to remove 1 % of a beam's tetrahedra from a running system (mesh,
// force field and DiagonalMass following incrementally), against rebuilding the mesh, the force
// field and the mass from scratch without them (what an engine without incremental changes does).
// Two patterns: a cut (the 1 % nearest the beam's mid-plane, like a scalpel through it) and 1 %
// scattered at random. Double, qr, one thread. Neither side counts the next step's add_force, which
// both need (it rebuilds the edge blocks). Run: build-release/bench/fastcorot_bench_cutting.
#include "beams.h"

#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/mechanical_system.h"

#include <algorithm>
#include <numeric>
#include <random>

namespace fastcorot::bench {
namespace {

struct CutSystem {
  BeamField<double> beam;
  MechanicalSystem<double> system;
};

CutSystem make_system(const Beam& beam) {
  CutSystem s{make_beam_field<double>(beam, RotationMethod::qr, 1), {}};
  s.system.state.position = s.beam.x;
  s.system.state.rest_position = s.beam.rest;
  s.system.force_fields.push_back(std::shared_ptr<CorotationalForceField<double>>(std::move(s.beam.field)));
  s.system.mass = Mass<double>::lumped(tetrahedral_lumped_masses<double>(*s.beam.mesh, s.beam.rest, 1.0));
  s.system.mass.follow_tetrahedra(s.beam.mesh, 1.0);
  s.system.finalize();
  std::vector<Vec3<double>> f(s.beam.x.size(), Vec3<double>::Zero());
  s.system.compute_force(s.beam.x, f);  // a linearisation, as in a running simulation
  return s;
}

// 1 % of the tetrahedra: those nearest the mid-plane x = 8 (a cut), or a random 1 %.
std::vector<Index> one_percent(const TetMesh& mesh, const std::vector<Vec3<double>>& rest, bool cut, unsigned seed) {
  std::vector<Index> order(static_cast<std::size_t>(mesh.num_tetrahedra()));
  std::iota(order.begin(), order.end(), Index(0));
  const auto count = static_cast<std::ptrdiff_t>(order.size() / 100);
  if (cut) {
    std::vector<double> distance(order.size());
    for (std::size_t t = 0; t < order.size(); ++t) {
      double x = 0;
      for (Index v : mesh.tetrahedron(static_cast<Index>(t))) x += rest[static_cast<std::size_t>(v)].x() / 4;
      distance[t] = std::abs(x - 8.0);
    }
    std::partial_sort(order.begin(), order.begin() + count, order.end(),
                      [&](Index a, Index b) { return distance[static_cast<std::size_t>(a)] < distance[static_cast<std::size_t>(b)]; });
  } else {
    std::mt19937 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
  }
  order.resize(static_cast<std::size_t>(count));
  return order;
}

void incremental(benchmark::State& state, const Beam& beam, bool cut) {
  CutSystem s = make_system(beam);
  TetMesh& mesh = *s.beam.mesh;
  unsigned seed = 1;
  for (auto _ : state) {
    state.PauseTiming();
    const std::vector<Index> removed = one_percent(mesh, s.beam.rest, cut, seed++);
    state.ResumeTiming();
    const TopologyChange change = s.system.remove_tetrahedra(mesh, removed);
    state.PauseTiming();
    s.system.add_tetrahedra(mesh, change.removed_tetrahedron_vertices);  // back, for the next round
    state.ResumeTiming();
  }
  state.counters["removed"] = static_cast<double>(mesh.num_tetrahedra() / 100);
}

void readd(benchmark::State& state, const Beam& beam) {
  CutSystem s = make_system(beam);
  TetMesh& mesh = *s.beam.mesh;
  for (auto _ : state) {
    state.PauseTiming();
    const TopologyChange change = s.system.remove_tetrahedra(mesh, one_percent(mesh, s.beam.rest, true, 0));
    state.ResumeTiming();
    s.system.add_tetrahedra(mesh, change.removed_tetrahedron_vertices);
  }
}

void full_reinit(benchmark::State& state, const Beam& beam) {
  const CutSystem s = make_system(beam);
  const std::vector<Index> removed = one_percent(*s.beam.mesh, s.beam.rest, true, 0);
  std::vector<bool> gone(static_cast<std::size_t>(s.beam.mesh->num_tetrahedra()), false);
  for (Index t : removed) gone[static_cast<std::size_t>(t)] = true;
  std::vector<Tetrahedron> kept;
  for (Index t = 0; t < s.beam.mesh->num_tetrahedra(); ++t) {
    if (!gone[static_cast<std::size_t>(t)]) kept.push_back(s.beam.mesh->tetrahedron(t));
  }
  CorotationalForceField<double>::Parameters parameters =
      dynamic_cast<const CorotationalForceField<double>&>(*s.system.force_fields[0]).parameters();
  for (auto _ : state) {
    auto mesh = std::make_shared<TetMesh>(s.beam.mesh->num_points(), kept);
    CorotationalForceField<double> field(mesh, s.beam.rest, parameters);
    Mass<double> mass = Mass<double>::lumped(tetrahedral_lumped_masses<double>(*mesh, s.beam.rest, 1.0));
    benchmark::DoNotOptimize(field.memory_bytes());
    benchmark::DoNotOptimize(mass.total_mass());
  }
}

void register_all() {
  for (const Beam& beam : beams()) {
    benchmark::RegisterBenchmark(("cut_incremental/" + beam.name + "/cut").c_str(), incremental, beam, true)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("cut_incremental/" + beam.name + "/scattered").c_str(), incremental, beam, false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("cut_readd/" + beam.name + "/cut").c_str(), readd, beam)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("cut_full_reinit/" + beam.name + "/cut").c_str(), full_reinit, beam)
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace
}  // namespace fastcorot::bench

int main(int argc, char** argv) {
  fastcorot::bench::register_all();
  return fastcorot::bench::run_registered_benchmarks(argc, argv);
}
