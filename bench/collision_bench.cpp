// Collision detection's cost per step on a self-colliding surface of about 100,000 triangles: a
// square sheet of n × n points folded in two, its upper half a spacing above its lower half, with
// Triangle, Line and Point models (selfCollision) under MinProximityIntersection and the penalty
// response. One iteration is one detection (CollisionStage::begin_step: points, trees refitted,
// neighbourhoods, broad and narrow phases, responses) at the folded positions, on 1 and 2 threads,
// after one untimed detection that builds the trees.
// Counters: contacts kept, element pairs tested, ns per element pair.
#include "beams.h"

#include "fastcorot/core/parallel.h"
#include "fastcorot/scene/scene_builder.h"

#include <sstream>

namespace fastcorot::bench {
namespace {

// The folded sheet as a scene: `n` points per side, spacing h; the alarm distance 1.5 h, the
// contact distance 0.5 h, the layers h apart.
std::string folded_sheet(int n) {
  const double h = 1.0 / (n - 1);
  std::ostringstream points, triangles;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double u = static_cast<double>(i) / (n - 1);
      const bool upper = 2 * i >= n;
      points << (upper ? 1 - u : u) << ' ' << (upper ? h : 0.0) << ' ' << static_cast<double>(j) / (n - 1) << "  ";
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      triangles << a << ' ' << c << ' ' << b << "  " << b << ' ' << c << ' ' << d << "  ";
    }
  }
  std::ostringstream scene;
  scene << "<Node name=\"root\" dt=\"0.01\" gravity=\"0 0 0\"><CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>"
        << "<MinProximityIntersection alarmDistance=\"" << 1.5 * h << "\" contactDistance=\"" << 0.5 * h << "\"/>"
        << "<CollisionResponse response=\"PenalityContactForceField\"/><Node name=\"sheet\"><EulerImplicitSolver/>"
        << "<CGLinearSolver iterations=\"25\" tolerance=\"1e-9\" threshold=\"1e-9\"/><MeshTopology position=\"" << points.str()
        << "\" triangles=\"" << triangles.str() << "\"/><MechanicalObject/><UniformMass totalMass=\"1\"/>"
        << "<TriangleCollisionModel selfCollision=\"1\"/><LineCollisionModel selfCollision=\"1\"/>"
        << "<PointCollisionModel selfCollision=\"1\"/></Node></Node>";
  return scene.str();
}

void register_all() {
  for (const int n : {65, 225}) {
    for (const int threads : {1, 2}) {
      const std::string name = "detection/folded_sheet_" + std::to_string(2 * (n - 1) * (n - 1)) + "_triangles/threads:" + std::to_string(threads);
      benchmark::RegisterBenchmark(name.c_str(), [n, threads](benchmark::State& state) {
        set_yield_cores_to_other_processes(false);
        LoadedScene scene = build_scene(parse_scene_text(folded_sheet(n), "folded_sheet.scn"));
        auto& simulation = scene.simulation;
        CollisionReport report;
        simulation.collisions->set_threads(threads);
        report = simulation.collisions->begin_step(simulation.objects, simulation.dt, 0.0);  // the trees built, untimed
        for (auto _ : state) {
          report = simulation.collisions->begin_step(simulation.objects, simulation.dt, 0.0);
          benchmark::DoNotOptimize(report);
        }
        state.counters["contacts"] = report.contacts;
        state.counters["element_pairs"] = static_cast<double>(report.element_pairs);
        state.counters["ns_per_element_pair"] = benchmark::Counter(
            static_cast<double>(report.element_pairs), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
        set_yield_cores_to_other_processes(true);
      })->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace
}  // namespace fastcorot::bench

int main(int argc, char** argv) {
  fastcorot::bench::register_all();
  return fastcorot::bench::run_registered_benchmarks(argc, argv);
}
