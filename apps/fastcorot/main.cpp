// The fastcorot command-line program: one subcommand per task (`probe` evaluates the force field on
// a case file). Errors in the input print one line naming the problem and exit with status 2.
#include "probe_command.h"

#include "fastcorot/core/error.h"

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
  probe->add_option("CASE", case_path, "case file (JSON: points, tetrahedra, method, x, dx, ...)")
      ->required();
  probe->add_option("-o,--output", output_path, "write the result here instead of standard output");

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
  } catch (const fastcorot::Error& error) {
    std::cerr << "fastcorot: error: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "fastcorot: internal error: " << error.what() << '\n';
    return 3;
  }
  return 0;
}
