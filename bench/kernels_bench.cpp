// Google Benchmarks of the force-field kernels on the benchmark beams: add_force (forces and the
// stiffness refresh), add_force_only (forces alone: the refresh costs the difference), add_dforce,
// for every method, float and double, 1 and 2 threads. Counters: ns per tetrahedron (add_force) or
// per edge (add_dforce). TetrahedronFEMForceField's add_force and add_force_only on the same bent
// beams, for each of its methods ("tetrahedron_fem_add_force/40x10x10/polar/double/threads:1"), and
// its add_dforce (the assembled product, the same for every method) on them and on the 5×5×5-point
// cube of SOFA's TriangleModel.scn ("tetrahedron_fem_add_dforce/5x5x5/double/threads:1").
//   build-release/bench/fastcorot_bench_kernels --benchmark_filter='qr/double/.*threads:1'
#include "beams.h"

#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include <benchmark/benchmark.h>

namespace fastcorot::bench {
namespace {

enum class Kernel { add_force, add_force_only, add_dforce };

template <class Real>
void run_kernel(benchmark::State& state, const Beam& beam, RotationMethod method, int threads, Kernel kernel) {
  BeamField<Real> b = make_beam_field<Real>(beam, method, threads);
  b.field->add_force(b.x, b.out);
  for (auto _ : state) {
    switch (kernel) {
      case Kernel::add_force: b.field->add_force(b.x, b.out); break;
      case Kernel::add_force_only: b.field->add_force_only(b.x, b.out); break;
      case Kernel::add_dforce: b.field->add_dforce(b.dx, b.out, Real(-0.01)); break;
    }
    benchmark::DoNotOptimize(b.out.data());
    benchmark::ClobberMemory();
  }
  const double items = kernel == Kernel::add_dforce ? b.mesh->num_edges() : b.mesh->num_tetrahedra();
  // Seconds per item (printed with an SI prefix: "2.1n" is 2.1 ns).
  state.counters[kernel == Kernel::add_dforce ? "per_edge" : "per_tet"] = benchmark::Counter(
      items, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <class Real>
void run_tetrahedron_fem(benchmark::State& state, const Beam& beam, TetrahedronFEMMethod method, int threads,
                         Kernel kernel) {
  // The beam's mesh and bent positions, under TetrahedronFEMForceField instead.
  const BeamField<Real> b = make_beam_field<Real>(beam, RotationMethod::qr, threads);
  typename TetrahedronFEMForceField<Real>::Parameters parameters;
  parameters.young_modulus = {Real(2000)};
  parameters.poisson_ratio = {Real(0.3)};
  parameters.method = method;
  TetrahedronFEMForceField<Real> field(b.mesh, b.rest, parameters);
  field.set_threads(threads);
  std::vector<Vec3<Real>> out = b.out;
  if (kernel == Kernel::add_dforce) field.add_force(b.x, out);
  for (auto _ : state) {
    switch (kernel) {
      case Kernel::add_force: field.add_force(b.x, out); break;
      case Kernel::add_force_only: field.add_force_only(b.x, out); break;
      case Kernel::add_dforce: field.add_dforce(b.dx, out, Real(-0.01)); break;
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  const bool per_edge = kernel == Kernel::add_dforce;
  state.counters[per_edge ? "per_edge" : "per_tet"] =
      benchmark::Counter(static_cast<double>(per_edge ? b.mesh->num_edges() : b.mesh->num_tetrahedra()),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <class Real>
void register_tetrahedron_fem(const char* real_name) {
  for (const Beam& beam : beams()) {
    for (const TetrahedronFEMMethod method :
         {TetrahedronFEMMethod::small, TetrahedronFEMMethod::large, TetrahedronFEMMethod::polar, TetrahedronFEMMethod::svd}) {
      for (const auto& [kernel, kernel_name] : {std::pair{Kernel::add_force, "tetrahedron_fem_add_force"},
                                                std::pair{Kernel::add_force_only, "tetrahedron_fem_add_force_only"}}) {
        for (const int threads : {1, 2}) {
          const std::string name = std::string(kernel_name) + "/" + beam.name + "/" + to_string(method) + "/" + real_name +
                                   "/threads:" + std::to_string(threads);
          benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
            run_tetrahedron_fem<Real>(state, beam, method, threads, kernel);
          })->Unit(benchmark::kMicrosecond)->UseRealTime();
        }
      }
    }
  }
  std::vector<Beam> product_beams = beams();
  product_beams.push_back({"5x5x5", {5, 5, 5}});
  for (const Beam& beam : product_beams) {
    for (const int threads : {1, 2}) {
      const std::string name =
          "tetrahedron_fem_add_dforce/" + beam.name + "/" + real_name + "/threads:" + std::to_string(threads);
      benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
        run_tetrahedron_fem<Real>(state, beam, TetrahedronFEMMethod::large, threads, Kernel::add_dforce);
      })->Unit(benchmark::kMicrosecond)->UseRealTime();
    }
  }
}

template <class Real>
void register_all(const char* real_name) {
  const std::pair<Kernel, const char*> kernels[] = {
      {Kernel::add_force, "add_force"}, {Kernel::add_force_only, "add_force_only"}, {Kernel::add_dforce, "add_dforce"}};
  for (const Beam& beam : beams()) {
    for (const RotationMethod method : kMethods) {
      for (const auto& [kernel, kernel_name] : kernels) {
        if (kernel == Kernel::add_dforce && method != RotationMethod::qr) continue;  // independent of the method
        for (const int threads : {1, 2}) {
          const std::string name = benchmark_name(kernel_name, beam, method, real_name, threads);
          benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
            run_kernel<Real>(state, beam, method, threads, kernel);
          })->Unit(benchmark::kMicrosecond)->UseRealTime();
        }
      }
    }
  }
}

}  // namespace
}  // namespace fastcorot::bench

int main(int argc, char** argv) {
  return fastcorot::bench::run_benchmarks(argc, argv, [](auto real, const char* name) {
    fastcorot::bench::register_all<decltype(real)>(name);
    fastcorot::bench::register_tetrahedron_fem<decltype(real)>(name);
  });
}
