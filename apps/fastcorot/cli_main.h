// The fastcorot command line as a function (cli_main.cpp), so that the program and the Python
// module (`python3 -m fastcorot`, which runs Python scene scripts) share it.
#pragma once

namespace fastcorot::cli {

// Parses the arguments (argv[0] is the program's name) and runs the subcommand; returns the exit
// status (0; 2 for bad input, with one line on standard error; 3 for an internal error).
int run_cli(int argc, char** argv);

}  // namespace fastcorot::cli
