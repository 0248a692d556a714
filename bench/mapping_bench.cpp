// The cost of a visual surface: placing its points (BarycentricMapping's init, once) and mapping
// them (each drawn or written frame), on the benchmark beams with as many surface points as the
// beam's boundary has, spread over and just outside the beam. Counters: ns per surface point.
#include "beams.h"

#include "fastcorot/sim/visual_surface.h"

#include <random>

namespace fastcorot::bench {
namespace {

struct Surface {
  std::shared_ptr<TetMesh> mesh;
  std::vector<Vec3<double>> rest, points;
  RegularGrid grid;
};

Surface make_surface(const Beam& beam) {
  Surface s;
  s.grid.n = beam.n;
  s.grid.min = Vec3<double>(0, 6, -2);
  s.grid.max = Vec3<double>(16, 10, 2);
  s.rest = grid_points<double>(s.grid);
  s.mesh = std::make_shared<TetMesh>(s.grid.num_points(), grid_tetrahedra(s.grid, true));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> x(-0.1, 16.1), y(5.9, 10.1), z(-2.1, 2.1);
  const std::size_t count = s.mesh->boundary_triangles().size() / 2;
  for (std::size_t i = 0; i < count; ++i) s.points.emplace_back(x(rng), y(rng), z(rng));
  return s;
}

void register_all() {
  for (const Beam& beam : beams()) {
    benchmark::RegisterBenchmark(("mapping_init/" + beam.name + "/tetrahedra").c_str(), [beam](benchmark::State& state) {
      const Surface s = make_surface(beam);
      for (auto _ : state) benchmark::DoNotOptimize(map_onto_tetrahedra<double>(*s.mesh, s.rest, s.points));
      state.counters["ns_per_point"] = benchmark::Counter(
          static_cast<double>(s.points.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    })->Unit(benchmark::kMillisecond);
    for (const char* kind : {"tetrahedra", "trilinear"}) {
      benchmark::RegisterBenchmark(("mapping_apply/" + beam.name + "/" + kind).c_str(), [beam, kind](benchmark::State& state) {
        const Surface s = make_surface(beam);
        const auto map = std::string(kind) == "trilinear"
                             ? PointMapping<double>::trilinear(s.grid, s.points)
                             : PointMapping<double>::from_barycentric(*s.mesh, map_onto_tetrahedra<double>(*s.mesh, s.rest, s.points));
        std::vector<Vec3<double>> out(s.points.size());
        for (auto _ : state) {
          map.apply(s.rest, out);
          benchmark::DoNotOptimize(out.data());
        }
        state.counters["ns_per_point"] = benchmark::Counter(
            static_cast<double>(s.points.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
      });
    }
  }
}

}  // namespace
}  // namespace fastcorot::bench

int main(int argc, char** argv) {
  fastcorot::bench::register_all();
  return fastcorot::bench::run_registered_benchmarks(argc, argv);
}
