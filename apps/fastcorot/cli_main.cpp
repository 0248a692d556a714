// The fastcorot command line: one subcommand per task. Errors in the input print one line naming
// the problem and return status 2. `main` (the fastcorot program) and `python3 -m fastcorot` (the
// Python module, which adds Python scene scripts) both run it.
#include "cli_main.h"

#include "bench_command.h"
#include "probe_command.h"
#include "run_command.h"
#include "view_command.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/component_table.h"
#include "fastcorot/sim/petsc_runtime.h"

#include <CLI/CLI.hpp>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace fastcorot::cli {

namespace {

// Whether this process was started by mpirun (Open MPI) on more than one rank.
bool started_by_mpirun() {
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  return size && std::atoi(size) > 1;
}

// The options that shape a picture, shared by `run --png` and `view`. Returned so that `run` can
// require --png with them.
std::vector<CLI::Option*> add_picture_options(CLI::App* command, fastcorot::cli::PictureOptions& picture) {
  return {
      command->add_option("--size", picture.size, "picture or window size WIDTHxHEIGHT")->capture_default_str(),
      command->add_option("--drawing", picture.drawing,
                          "force fields drawn as shrunk tetrahedra: scene (each one's `drawing`), on, off")
          ->capture_default_str(),
      command->add_flag("--edges", picture.surface_edges, "outline the mesh on the boundary surface"),
      command->add_option("--constraints", picture.constraints,
                          "Lagrangian constraints' points, bilateral pairs and forces: on, off")
          ->capture_default_str(),
      command->add_option("--constraint-force-scale", picture.constraint_force_scale,
                          "constraint force arrows' length per unit of force (0: the largest a tenth of the scene)")
          ->capture_default_str(),
      command->add_option("--contacts", picture.contacts,
                          "the last collision detection's contacts (points joined, normals): on, off")
          ->capture_default_str(),
      command->add_option("--camera-eye", picture.camera_eye, "camera position X,Y,Z (default: framed automatically)"),
      command->add_option("--camera-target", picture.camera_target, "point looked at X,Y,Z (default: the scene's centre)"),
      command->add_option("--camera-up", picture.camera_up, "up direction X,Y,Z (default: against gravity)"),
      command->add_option("--camera-fov", picture.camera_fov, "vertical field of view, degrees")->capture_default_str(),
      command->add_option("--camera-azimuth", picture.camera_azimuth,
                          "turn about up from the broadside view, degrees")->capture_default_str(),
      command->add_option("--camera-elevation", picture.camera_elevation, "eye above the horizontal, degrees")
          ->capture_default_str()};
}

}  // namespace

int run_cli(int argc, char** argv) {
  // PETSc's options (-ksp_type cg -pc_type gamg -ksp_monitor ...) go to PETSc; the rest to us.
  std::vector<std::string> arguments(argv, argv + argc);
  const std::vector<std::string> petsc_options = take_petsc_options(arguments);
  std::vector<char*> kept;
  for (auto& argument : arguments) kept.push_back(argument.data());
  argc = static_cast<int>(kept.size());
  argv = kept.data();
  try {
    if (!petsc_options.empty() || started_by_mpirun()) initialise_petsc(petsc_options);
  } catch (const fastcorot::ReportedElsewhere&) {
    return 2;  // the rank that failed first printed the error
  } catch (const fastcorot::Error& error) {
    std::cerr << "fastcorot: error: " << error.what() << '\n';
    return 2;
  }

  CLI::App app{"fastcorot: fast corotational tetrahedral finite elements (SOFA-compatible)"};
  app.require_subcommand(1);

  std::string case_path;
  std::string output_path;
  CLI::App* probe = app.add_subcommand(
      "probe", "Evaluate the force field on a mesh and configuration given as JSON; print JSON");
  probe->add_option("CASE", case_path, "case file (JSON: points, tetrahedra, method, x, dx, ...)")->required();
  probe->add_option("-o,--output", output_path, "write the result here instead of standard output");

  fastcorot::cli::RunOptions run_options;
  std::string dump_steps;
  double dt = 0;
  CLI::App* run = app.add_subcommand(
      "run", "Run a SOFA scene (.scn), a tetrahedral mesh (.msh, .vtk, .vtu) or, with no SCENE, the "
             "built-in cantilever beam");
  run->add_option("SCENE", run_options.scene, "scene or mesh file");
  run->add_option("--steps", run_options.steps, "number of time steps")->capture_default_str();
  auto* dt_option = run->add_option("--dt", dt, "time step (default: the scene's)");
  run->add_option("--out", run_options.out_dir, "folder for --vtu and --obj output")->capture_default_str();
  run->add_flag("--vtu", run_options.vtu, "write a ParaView time series (.vtu per frame and a .pvd)");
  run->add_flag("--obj", run_options.obj, "write the visual surfaces (or each object's boundary) as .obj per frame");
  run->add_option("--every", run_options.every, "write a frame every K steps (and the last)")->capture_default_str();
  run->add_option("--dump-state", run_options.dump_state, "write positions as JSON to FILE");
  run->add_option("--dump-steps", dump_steps, "steps to dump, e.g. 0,1,10,100 (default; the last step is always dumped)");
  run->add_option("--threads", run_options.threads,
                  "threads: independent objects concurrently, then each object's kernels (0: one per 2000 points, "
                  "at most every core; fewer while other processes keep cores busy; 1 per rank under mpirun)")
      ->capture_default_str();
  run->add_flag("--quiet", run_options.quiet, "no progress bar, info lines or summary");
  run->add_flag("--json", run_options.json, "print the summary as JSON (also with --quiet)");
  run->add_flag("--strict", run_options.strict, "treat warnings (unknown attributes) as errors");
  auto* checkpoint_every = run->add_option("--checkpoint-every", run_options.checkpoint_every,
                                           "save the whole state every K steps (to --checkpoint)");
  run->add_option("--checkpoint", run_options.checkpoint_file,
                  "checkpoint file (default: OUT/checkpoint.ckpt)")
      ->needs(checkpoint_every);
  run->add_option(
      "--resume", run_options.resume,
      "continue from a checkpoint of the same scene up to step --steps; bitwise the same run");
  run->add_option(
         "--divergence-factor", run_options.divergence_factor,
         "stop when a point moves more than F x the scene's size from rest (0: only NaN/Inf)")
      ->capture_default_str();
  auto* png_option = run->add_option("--png", run_options.png_dir,
                                     "render each written frame (see --every) to DIR/step_NNNNN.png, headless");
  for (CLI::Option* option : add_picture_options(run, run_options.picture)) {
    if (option->get_name() != "--drawing") option->needs(png_option);  // --drawing also shapes --vtu
  }

  fastcorot::cli::ViewOptions view_options;
  double view_dt = 0;
  CLI::App* view = app.add_subcommand(
      "view", "Simulate a scene in an interactive window (orbit, pan, zoom; play, step; change method, E, nu)");
  view->add_option("SCENE", view_options.scene, "scene or mesh file (default: the built-in beam)");
  view_options.picture.size = "1280x720";
  add_picture_options(view, view_options.picture);
  view->add_flag("--paused", view_options.paused, "start paused");
  view->add_flag("--strict", view_options.strict, "treat warnings (unknown attributes) as errors");
  view->add_option("--frames", view_options.frames, "close after N frames (0: when the window is closed)")
      ->capture_default_str();
  view->add_option("--screenshot", view_options.screenshot, "save the last frame shown as PNG");
  auto* view_dt_option = view->add_option("--dt", view_dt, "time step (default: the scene's)");
  view->add_option("--threads", view_options.threads, "threads: objects, then each object's kernels (0: one per 2000 points, at most every core)")->capture_default_str();

  fastcorot::cli::BenchOptions bench_options;
  CLI::App* bench = app.add_subcommand(
      "bench", "Time steps of a scene (default: the built-in 40x10x10 beam) and split the time per phase");
  bench->add_option("SCENE", bench_options.scene, "scene or mesh file");
  bench->add_option("--beam", bench_options.beam, "the built-in beam with NXxNYxNZ grid points, e.g. 76x16x16");
  bench->add_option("--steps", bench_options.steps, "timed steps")->capture_default_str();
  bench->add_option("--warmup", bench_options.warmup, "untimed steps first")->capture_default_str();
  bench->add_option("--threads", bench_options.threads, "threads: objects, then each object's kernels (0: one per 2000 points, at most every core)")
      ->capture_default_str();
  bench->add_option("--vtu", bench_options.vtu_dir, "write a VTU frame per step to DIR (timed as output)");
  bench->add_flag("--json", bench_options.json, "print the figures as JSON");
  bench->add_flag("--strict", bench_options.strict, "treat warnings (unknown attributes) as errors");

  app.add_subcommand("components", "Print the supported SOFA components and their attributes (Markdown)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    app.exit(error);
    return 2;
  }

  try {
    if (probe->parsed()) fastcorot::cli::probe_file(case_path, output_path);
    if (run->parsed()) {
      if (*dt_option) run_options.dt = dt;
      if (!dump_steps.empty()) run_options.dump_steps = fastcorot::cli::parse_step_list(dump_steps);
      fastcorot::cli::run(run_options, std::cout, std::cerr);
    }
    if (bench->parsed()) fastcorot::cli::bench(bench_options, std::cout);
    if (view->parsed()) {
      if (*view_dt_option) view_options.dt = view_dt;
      fastcorot::cli::view(view_options, std::cout, std::cerr);
    }
    if (app.got_subcommand("components")) std::cout << fastcorot::component_documentation();
  } catch (const fastcorot::ReportedElsewhere&) {
    return 2;  // the rank that failed first printed the error
  } catch (const fastcorot::Error& error) {
    std::cerr << "fastcorot: error: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "fastcorot: internal error: " << error.what() << '\n';
    return 3;
  }
  return 0;
}

}  // namespace fastcorot::cli
