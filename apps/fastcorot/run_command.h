// `fastcorot run [SCENE] [--steps N] [--dt DT] [--out DIR] [--vtu] [--every K]
//                [--dump-state FILE --dump-steps 0,1,10,100] [--threads N] [--quiet]`:
// runs a SOFA scene (.scn), a tetrahedral mesh (.msh/.vtk/.vtu, with documented defaults) or the
// built-in cantilever beam, headless. See README.md, "fastcorot run".
#pragma once

#include <iosfwd>
#include <optional>
#include <set>
#include <string>

namespace fastcorot::cli {

struct RunOptions {
  std::string scene;  // empty: the built-in default scene
  long steps = 100;
  std::optional<double> dt;
  std::string out_dir = "out";
  bool vtu = false;
  long every = 1;  // write VTU frames every K steps (and the last)
  std::string dump_state;
  std::set<long> dump_steps = {0, 1, 10, 100};
  int threads = 1;
  bool quiet = false;
};

// Parses "0,1,10,100"; throws fastcorot::Error on anything else.
std::set<long> parse_step_list(const std::string& text);

// The scene text `fastcorot run MESH` simulates: the mesh fixed at its lowest z, under gravity.
std::string mesh_scene_text(const std::string& mesh_path);

// Runs; throws fastcorot::Error on bad input or divergence (after writing what it had).
void run(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace fastcorot::cli
