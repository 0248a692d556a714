// `fastcorot bench [SCENE] [--beam NXxNYxNZ] [--steps N] [--warmup N] [--threads N] [--vtu DIR] [--json]`:
// times whole time steps of a scene (default: the built-in 40×10×10 cantilever beam) and splits
// the time per phase (docs/performance.md). Nothing is written unless --vtu asks for a frame
// per step (timed as the output phase).
#pragma once

#include <iosfwd>
#include <string>

namespace fastcorot::cli {

struct BenchOptions {
  std::string scene;  // empty: the built-in beam
  std::string beam;   // "NXxNYxNZ": the built-in beam with this many grid points (no SCENE then)
  long steps = 200;
  long warmup = 10;
  bool strict = false;  // warnings (unknown attributes) are errors
  int threads = 0;  // 0: every core (thread_count.h)
  std::string vtu_dir;  // empty: no output
  bool json = false;
};

// The built-in beam scene with an NX×NY×NZ grid of points ("40x10x10"); throws fastcorot::Error
// on anything but three integers >= 2.
std::string beam_scene_text(const std::string& grid);

// Prints the figures (text, or JSON with --json) to `out`; throws fastcorot::Error on bad input.
// With several objects integrated concurrently, phase times are summed over objects.
void bench(const BenchOptions& options, std::ostream& out);

}  // namespace fastcorot::cli
