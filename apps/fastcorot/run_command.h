// `fastcorot run [SCENE] [--steps N] [--dt DT] [--out DIR] [--vtu] [--obj] [--every K]
//                [--dump-state FILE --dump-steps 0,1,10,100] [--threads N] [--quiet] [--json]
//                [--png DIR [--size WxH] [--drawing scene|on|off] [--camera-...]]
//                [--checkpoint-every K [--checkpoint FILE]] [--resume FILE] [--divergence-factor
//                F]`:
// runs a SOFA scene (.scn), a tetrahedral mesh (.msh/.vtk/.vtu, with documented defaults) or the
// built-in cantilever beam, headless. See docs/cli.md and docs/rendering.md.
#pragma once

#include "picture_options.h"

#include "fastcorot/scene/scene_builder.h"

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
  bool obj = false;  // write each visual surface (or each object's boundary) as OBJ per frame
  long every = 1;  // write VTU frames every K steps (and the last)
  std::string dump_state;
  std::set<long> dump_steps = {0, 1, 10, 100};
  int threads = 0;  // 0: every core (thread_count.h)
  bool quiet = false;
  bool json = false;    // the summary as JSON on standard output (also with quiet)
  bool strict = false;  // warnings (unknown attributes) are errors
  std::string png_dir;     // empty: no pictures; else one PNG per written frame
  PictureOptions picture;  // what the pictures (and the drawn tetrahedra in --vtu) look like
  long checkpoint_every = 0;    // 0: no checkpoints; else save the state every K steps
  std::string checkpoint_file;  // empty: OUT/checkpoint.ckpt
  std::string resume;           // a checkpoint to continue from; `steps` stays the last step number
  double divergence_factor = 1e6;  // Simulation::divergence_factor; 0 turns the bound off
};

// Parses "0,1,10,100"; throws fastcorot::Error on anything else.
std::set<long> parse_step_list(const std::string& text);

// The scene text `fastcorot run MESH` simulates: the mesh fixed at its lowest z, under gravity.
std::string mesh_scene_text(const std::string& mesh_path);

// The scene `fastcorot run SCENE` and `fastcorot view SCENE` simulate: a .scn file, a mesh file
// (.msh/.vtk/.vtu, through mesh_scene_text) or, for an empty argument, the built-in beam.
// With strict, unknown attributes are errors rather than warnings.
LoadedScene load_scene_argument(const std::string& scene, bool strict = false);

// Makes `dir` and its parents; throws fastcorot::Error naming `option`, the folder and the reason
// when it cannot, or when `dir` is not a writable folder.
void make_output_folder(const std::string& dir, const std::string& option);

// Runs; throws fastcorot::Error on bad input or divergence (after writing what it had).
void run(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace fastcorot::cli
