// The fastcorot command-line program: one subcommand per task. Errors in the input print one line
// naming the problem and exit with status 2.
#include "probe_command.h"
#include "run_command.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/component_table.h"

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
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
  run->add_option("--out", run_options.out_dir, "folder for --vtu output")->capture_default_str();
  run->add_flag("--vtu", run_options.vtu, "write a ParaView time series (.vtu per frame and a .pvd)");
  run->add_option("--every", run_options.every, "write a frame every K steps (and the last)")->capture_default_str();
  run->add_option("--dump-state", run_options.dump_state, "write positions as JSON to FILE");
  run->add_option("--dump-steps", dump_steps, "steps to dump, e.g. 0,1,10,100 (default; the last step is always dumped)");
  run->add_option("--threads", run_options.threads, "threads: independent objects are integrated concurrently")
      ->capture_default_str();
  run->add_flag("--quiet", run_options.quiet, "no progress bar, info lines or summary");

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
    if (app.got_subcommand("components")) std::cout << fastcorot::component_documentation();
  } catch (const fastcorot::Error& error) {
    std::cerr << "fastcorot: error: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "fastcorot: internal error: " << error.what() << '\n';
    return 3;
  }
  return 0;
}
