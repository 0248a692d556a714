// Google Benchmarks of whole time steps on the benchmark beams, as the scenes
// examples/cantilever_beam_*.scn pose them (implicit Euler with Rayleigh damping 0.1/0.1, CG with 20
// iterations, DiagonalMass of 50 in all, the x = 0 end clamped, gravity -9 along y, dt 0.01), for
// every method, float and double, 1 and 2 threads. The steps start from rest and the beam keeps
// bending as they run, so each iteration is a different step: the counter is steps per second.
// step_pcg: the same steps with examples/cantilever_beam_40x10x10_pcg.scn's solver instead (SOFA's
// PCGLinearSolver, 30 iterations, block-Jacobi), method qr.
//   build-release/bench/fastcorot_bench_step --benchmark_filter='76x16x16/qr/double'
#include "beams.h"

#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/sim/mechanical_system.h"
#include "fastcorot/sim/ode_solver.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"

#include <benchmark/benchmark.h>

namespace fastcorot::bench {
namespace {

template <class Real>
struct BeamStep {
  MechanicalSystem<Real> system;
  ImplicitEulerSolver<Real> ode{{Real(0.1), Real(0.1), Real(0), false, false}};
  std::unique_ptr<LinearSolver<Real>> solver;
};

template <class Real>
std::unique_ptr<BeamStep<Real>> make_step(const Beam& beam, RotationMethod method, int threads, bool pcg) {
  BeamField<Real> b = make_beam_field<Real>(beam, method, threads);
  auto step = std::make_unique<BeamStep<Real>>();
  auto& system = step->system;
  system.state.position = b.rest;
  system.force_fields.push_back(std::shared_ptr<CorotationalForceField<Real>>(std::move(b.field)));
  // DiagonalMass totalMass = 50: masses proportional to the lumped volumes.
  std::vector<Real> masses = tetrahedral_lumped_masses<Real>(*b.mesh, b.rest, Real(1));
  Real volume = 0;
  for (Real m : masses) volume += m;
  for (Real& m : masses) m *= Real(50) / volume;
  system.mass = Mass<Real>::lumped(std::move(masses));
  for (std::size_t i = 0; i < b.rest.size(); ++i) {
    if (b.rest[i].x() < Real(0.1)) system.fixed.push_back(static_cast<Index>(i));
  }
  system.gravity = Vec3<Real>(0, -9, 0);
  system.finalize();
  system.set_threads(threads);
  if (pcg) {
    step->solver = std::make_unique<PreconditionedConjugateGradientSolver<Real>>(
        typename PreconditionedConjugateGradientSolver<Real>::Parameters{30, Real(1e-12), Preconditioner::block_jacobi, 1},
        system.size());
  } else {
    step->solver = std::make_unique<ConjugateGradientSolver<Real>>(
        typename ConjugateGradientSolver<Real>::Parameters{20, Real(1e-6), Real(1e-6)});
  }
  return step;
}

template <class Real>
void run_steps(benchmark::State& state, const Beam& beam, RotationMethod method, int threads, bool pcg) {
  auto step = make_step<Real>(beam, method, threads, pcg);
  for (int warmup = 0; warmup < 3; ++warmup) step->ode.step(step->system, *step->solver, Real(0.01));
  for (auto _ : state) {
    step->ode.step(step->system, *step->solver, Real(0.01));
    benchmark::DoNotOptimize(step->system.state.position.data());
  }
  state.counters["steps_per_s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
}

template <class Real>
void register_all(const char* real_name) {
  for (const Beam& beam : beams()) {
    for (const RotationMethod method : kMethods) {
      for (const bool pcg : {false, true}) {
        if (pcg && method != RotationMethod::qr) continue;
        for (const int threads : {1, 2}) {
          const std::string name = benchmark_name(pcg ? "step_pcg" : "step", beam, method, real_name, threads);
          benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
            run_steps<Real>(state, beam, method, threads, pcg);
          })->Unit(benchmark::kMillisecond)->UseRealTime();
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
  });
}
