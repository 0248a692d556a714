#include "bench_command.h"

#include "contact_figures.h"
#include "default_scene.h"
#include "json_io.h"
#include "run_command.h"
#include "thread_count.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/machine.h"
#include "fastcorot/core/phase_times.h"
#include "fastcorot/io/vtu_writer.h"
#include "fastcorot/scene/scene_builder.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <ostream>
#include <regex>

namespace fastcorot::cli {

std::string beam_scene_text(const std::string& grid) {
  static const std::regex pattern(R"(([0-9]{1,5})x([0-9]{1,5})x([0-9]{1,5}))");
  std::smatch match;
  if (!std::regex_match(grid, match, pattern) || std::stol(match[1]) < 2 || std::stol(match[2]) < 2 ||
      std::stol(match[3]) < 2) {
    throw make_error("--beam \"", grid, "\": expected NXxNYxNZ, three numbers of grid points >= 2 (e.g. 76x16x16)");
  }
  std::string text = kDefaultScene;
  const std::string original = "n=\"40 10 10\"";
  const auto at = text.find(original);
  if (at == std::string::npos) throw make_error("the built-in beam scene has no grid size to replace");
  text.replace(at, original.size(), "n=\"" + std::string(match[1]) + " " + std::string(match[2]) + " " +
                                        std::string(match[3]) + "\"");
  return text;
}

namespace {

double peak_memory_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // Linux reports KiB
}

struct SceneSize {
  long points = 0, tetrahedra = 0, edges = 0;
  long renumbered_force_fields = 0;  // force fields keeping their own point order (scattered meshes)
  double force_field_bytes = 0;
};

SceneSize measure(const Simulation<double>& simulation) {
  SceneSize size;
  for (const auto& object : simulation.objects) {
    size.points += object.system.size();
    for (const auto& field : object.system.force_fields) {
      size.tetrahedra += field->mesh().num_tetrahedra();
      size.edges += field->mesh().num_edges();
      size.force_field_bytes += static_cast<double>(field->memory_bytes());
      if (field->renumbers_points()) ++size.renumbered_force_fields;
    }
  }
  return size;
}

void write_frame(const std::string& dir, const Simulation<double>& simulation) {
  for (std::size_t o = 0; o < simulation.objects.size(); ++o) {
    const auto& object = simulation.objects[o];
    std::vector<VtuCellBlock> cells;
    if (object.mesh) cells.push_back(tetrahedron_cells(object.mesh->tetrahedra()));
    const std::string file = "object" + std::to_string(o) + "_" + std::to_string(simulation.steps_done()) + ".vtu";
    write_vtu(std::filesystem::path(dir) / file, object.system.state.position, cells, {});
  }
}

}  // namespace

void bench(const BenchOptions& options, std::ostream& out) {
  if (options.steps < 1) throw make_error("--steps ", options.steps, ": must be >= 1");
  if (options.warmup < 0) throw make_error("--warmup ", options.warmup, ": must be >= 0");
  check_threads_option(options.threads);
  if (!options.beam.empty() && !options.scene.empty()) throw make_error("--beam replaces SCENE: give one of them");
  LoadedScene scene = options.beam.empty()
                          ? load_scene_argument(options.scene, options.strict)
                          : build_scene(parse_scene_text(beam_scene_text(options.beam), "<built-in beam " + options.beam + ">"));
  for (const auto& line : scene.warnings) std::cerr << "warning: " << line << '\n';
  Simulation<double>& simulation = scene.simulation;
  const int threads = threads_to_run(options.threads, false, simulated_points(simulation));
  simulation.threads = threads;
  if (!options.vtu_dir.empty()) make_output_folder(options.vtu_dir, "--vtu");
  const std::string name = !options.beam.empty() ? "beam " + options.beam
                           : options.scene.empty() ? "built-in beam 40x10x10" : options.scene;

  // With threads, how far apart the system puts two of them just now (NaN: not measured, or no
  // round trip within the budget on a busy machine). Before the warm-up, while no worker of the
  // simulation's own spins beside the two.
  constexpr auto kRoundTripBudget = std::chrono::milliseconds(100);
  const double round_trip_ns = threads > 1 ? thread_round_trip_ns(20000, kRoundTripBudget)
                                                   : std::numeric_limits<double>::quiet_NaN();
  for (long step = 0; step < options.warmup; ++step) simulation.step();
  // Each object adds to its own phase times (objects may run concurrently).
  std::vector<PhaseTimes> times(simulation.objects.size());
  for (std::size_t o = 0; o < times.size(); ++o) simulation.objects[o].system.set_phase_times(&times[o]);
  PhaseTimes total;
  // Under a FreeMotionAnimationLoop: W's and the constraint solve's time, rows and iterations.
  double compliance_seconds = 0, constraint_solve_seconds = 0;
  long constraint_rows = 0, constraint_iterations = 0, unconverged = 0;
  // With a collision pipeline: contacts per step and the time in detection.
  ContactTally contacts;
  const auto start = std::chrono::steady_clock::now();
  for (long step = 0; step < options.steps; ++step) {
    simulation.step();
    if (simulation.constraints) {
      const ConstraintReport& r = simulation.constraint_report();
      compliance_seconds += r.compliance_seconds;
      constraint_solve_seconds += r.solve_seconds;
      constraint_rows += r.rows;
      constraint_iterations += r.iterations;
      unconverged += r.converged ? 0 : 1;
    }
    if (simulation.collisions) static_cast<void>(contacts.add(simulation.collision_report()));
    if (!options.vtu_dir.empty()) {
      const PhaseTimer timer(&total.output);
      write_frame(options.vtu_dir, simulation);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto& object : simulation.objects) object.system.set_phase_times(nullptr);
  for (const auto& t : times) {
    total.add_force += t.add_force;
    total.matrix_vector += t.matrix_vector;
    total.solver_vectors += t.solver_vectors;
    total.mass_constraints += t.mass_constraints;
  }
  // add_force computes the forces and refreshes the edge blocks in one pass; the forces alone are
  // timed here on the final positions, as many times as there were steps, and the refresh is the rest.
  double forces_only = 0;
  for (auto& object : simulation.objects) {
    std::vector<Vec3<double>> f(object.system.state.position.size(), Vec3<double>::Zero());
    const PhaseTimer timer(&forces_only);
    for (long step = 0; step < options.steps; ++step) {
      for (auto& field : object.system.force_fields) field->add_force_only(object.system.state.position, f);
    }
  }
  forces_only = std::min(forces_only, total.add_force);
  const double refresh = total.add_force - forces_only;
  // Whatever the phases do not cover (the step loop itself, concurrent objects' overlap).
  const double other =
      std::max(0.0, seconds - total.total() - compliance_seconds - constraint_solve_seconds - contacts.seconds);
  const SceneSize size = measure(simulation);
  const double per_step = 1e3 / static_cast<double>(options.steps);
  const double steps_per_second = static_cast<double>(options.steps) / seconds;

  if (options.json) {
    json result = {{"scene", name},
                   {"steps", options.steps},
                   {"warmup", options.warmup},
                   {"threads", threads},
                   {"points", size.points},
                   {"tetrahedra", size.tetrahedra},
                   {"edges", size.edges},
                   {"seconds", seconds},
                   {"steps_per_second", steps_per_second},
                   {"ms_per_step",
                    {{"total", seconds * per_step},
                     {"add_force", forces_only * per_step},
                     {"stiffness_refresh", refresh * per_step},
                     {"matrix_vector", total.matrix_vector * per_step},
                     {"solver_vectors", total.solver_vectors * per_step},
                     {"mass_constraints", total.mass_constraints * per_step},
                     {"output", total.output * per_step},
                     {"constraint_compliance", compliance_seconds * per_step},
                     {"constraint_solve", constraint_solve_seconds * per_step},
                     {"collision_detection", contacts.seconds * per_step},
                     {"other", other * per_step}}},
                   {"force_field_bytes", size.force_field_bytes},
                   {"force_field_bytes_per_tetrahedron",
                    size.tetrahedra > 0 ? size.force_field_bytes / static_cast<double>(size.tetrahedra) : 0.0},
                   {"renumbered_force_fields", size.renumbered_force_fields},
                   {"peak_memory_bytes", peak_memory_bytes()},
                   {"cpu", cpu_model()},
                   {"cpu_vector_instructions", cpu_vector_instructions()},
                   {"build_vector_instructions", build_vector_instructions()},
                   {"thread_round_trip_ns", std::isfinite(round_trip_ns) ? json(round_trip_ns) : json(nullptr)}};
    if (simulation.constraints) {
      result["constraints"] = {{"solver", simulation.constraints->solver_name()},
                               {"rows_per_step", static_cast<double>(constraint_rows) / static_cast<double>(options.steps)},
                               {"iterations_per_step", static_cast<double>(constraint_iterations) / static_cast<double>(options.steps)},
                               {"unconverged_steps", unconverged},
                               {"compliance_share", seconds > 0 ? compliance_seconds / seconds : 0.0}};
    }
    if (simulation.collisions) result["contacts"] = contacts.to_json(seconds);
    out << result.dump(2) << '\n';
    return;
  }
  out << "fastcorot bench: " << name << ", " << size.points << " points, " << size.tetrahedra << " tetrahedra, "
      << size.edges << " edges, " << threads << " thread(s)\n"
      << std::fixed << std::setprecision(1) << options.steps << " steps in " << std::setprecision(3) << seconds
      << " s: " << std::setprecision(1) << steps_per_second << " steps/s, " << std::setprecision(3)
      << seconds * per_step << " ms per step\n";
  auto line = [&](const char* phase, double s) {
    out << "  " << std::left << std::setw(20) << phase << std::right << std::setw(9) << std::setprecision(3)
        << s * per_step << " ms  " << std::setw(5) << std::setprecision(1) << (seconds > 0 ? 100 * s / seconds : 0.0)
        << " %\n";
  };
  line("add_force", forces_only);
  line("stiffness refresh", refresh);
  line("matrix-vector", total.matrix_vector);
  line("solver vectors", total.solver_vectors);
  line("mass/constraints", total.mass_constraints);
  line("output", total.output);
  if (simulation.constraints) {
    line("constraint W", compliance_seconds);
    line("constraint solve", constraint_solve_seconds);
  }
  if (simulation.collisions) line("collision detection", contacts.seconds);
  line("other", other);
  if (simulation.constraints) {
    out << std::setprecision(1) << "constraints: " << static_cast<double>(constraint_rows) / static_cast<double>(options.steps)
        << " rows and " << static_cast<double>(constraint_iterations) / static_cast<double>(options.steps) << " "
        << simulation.constraints->solver_name() << " iterations per step, " << unconverged << " step(s) unconverged\n";
  }
  if (simulation.collisions) contacts.summarise(out);
  out << std::setprecision(0) << "force field memory " << size.force_field_bytes / 1024 << " KiB ("
      << (size.tetrahedra > 0 ? size.force_field_bytes / static_cast<double>(size.tetrahedra) : 0.0)
      << " bytes per tetrahedron); peak process memory " << peak_memory_bytes() / (1024 * 1024) << " MiB\n";
  const std::string cpu = cpu_model();
  out << "machine: " << (cpu.empty() ? "CPU model unknown" : cpu) << ", vector instructions "
      << cpu_vector_instructions() << "; the build uses " << build_vector_instructions() << '\n';
  if (std::isfinite(round_trip_ns)) {
    out << "threads: a value written by one reaches another and comes back in " << round_trip_ns
        << " ns (measured before the steps; two-thread figures depend on it)\n";
  } else if (threads > 1) {
    out << "threads: no round trip between two of them within " << kRoundTripBudget.count()
        << " ms (a busy machine)\n";
  }
  if (size.renumbered_force_fields > 0) {
    out << size.renumbered_force_fields
        << " force field(s) keep the points in an order of their own (the mesh's numbering is scattered)\n";
  }
}

}  // namespace fastcorot::cli
