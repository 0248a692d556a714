// The fastcorot program. A Python scene script (`fastcorot run scene.py`, SofaPython3's
// createScene) runs in the Python module: the program hands its arguments to `python3 -m fastcorot`,
// which runs the same command line with the script's scene and controllers (docs/python.md).
#include "cli_main.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

// Whether the command (run or view) names a Python script as its scene: an argument ending in .py
// that is not the value of an option naming a file.
bool runs_script(int argc, char** argv) {
  if (argc < 3 || (std::strcmp(argv[1], "run") != 0 && std::strcmp(argv[1], "view") != 0)) return false;
  for (int i = 2; i < argc; ++i) {
    const std::string argument = argv[i];
    const std::string before = argv[i - 1];
    const bool file_value = before == "--dump-state" || before == "--checkpoint" || before == "--resume" ||
                            before == "--screenshot" || before == "--out" || before == "--png";
    if (argument.size() > 3 && argument.compare(argument.size() - 3, 3, ".py") == 0 && !file_value) return true;
  }
  return false;
}

// Replaces this process by `python3 -m fastcorot ARGS...` with the module on PYTHONPATH; returns
// only on failure, with the exit status.
int exec_python(int argc, char** argv) {
#ifdef FASTCOROT_PYTHON_EXECUTABLE
  const char* python = std::getenv("FASTCOROT_PYTHON");
  if (!python || !*python) python = FASTCOROT_PYTHON_EXECUTABLE;
  const char* package = std::getenv("FASTCOROT_PYTHONPATH");
  std::string path = package && *package ? package : FASTCOROT_PYTHON_PACKAGE_DIR;
  if (std::error_code error; !std::filesystem::exists(std::filesystem::path(path) / "fastcorot" / "__main__.py", error)) {
    std::cerr << "fastcorot: error: Python scene scripts run in the Python module, which is not in " << path
              << " (build it with scripts/build, or set FASTCOROT_PYTHONPATH to the folder that holds fastcorot/)\n";
    return 2;
  }
  if (const char* existing = std::getenv("PYTHONPATH"); existing && *existing) path += std::string(":") + existing;
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<char*> arguments{const_cast<char*>(python), const_cast<char*>("-m"), const_cast<char*>("fastcorot")};
  for (int i = 1; i < argc; ++i) arguments.push_back(argv[i]);
  arguments.push_back(nullptr);
  execv(python, arguments.data());
  std::cerr << "fastcorot: error: cannot start " << python << " for the Python script: " << std::strerror(errno) << '\n';
#else
  (void)argc;
  (void)argv;
  std::cerr << "fastcorot: error: Python scene scripts need the Python module: this fastcorot was built without it "
               "(FASTCOROT_BUILD_PYTHON=OFF)\n";
#endif
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (runs_script(argc, argv)) return exec_python(argc, argv);
  return fastcorot::cli::run_cli(argc, argv);
}
