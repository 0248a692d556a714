// `fastcorot view [SCENE] [--size WxH] [--drawing scene|on|off] [--camera-...] [--paused]
//                 [--frames N] [--screenshot FILE] [--dt DT] [--threads N]`:
// an interactive window (GLFW, OpenGL, a Dear ImGui panel) that simulates the scene and shows it as
// `run --png` draws it. Mouse: left drag orbits, right (or shift + left) drag pans, the wheel
// zooms, ctrl + left drag (or left drag in cut mode) cuts: the tetrahedra under the cursor, within
// the brush radius, are removed as it moves. Keys: space play/pause, N or → one step, D cycles the
// tetrahedra drawing, E mesh edges, L the Lagrangian constraints, C cut mode, F reframes, R
// reloads the scene, Q or Esc quits; a key with Ctrl goes to a Python scene's controllers
// (SofaPython3's onKeypressedEvent).
// The panel shows time, steps and steps/s, switches cut mode, sets the brush radius, counts the
// tetrahedra removed, and changes each object's method, Young's modulus and Poisson's ratio live.
// `--frames N` closes after N frames and `--screenshot FILE` saves the last frame as PNG (tests run
// it in Xvfb). In a build without the viewer (FASTCOROT_BUILD_VIEWER=OFF) it is an error.
#pragma once

#include "picture_options.h"

#include <iosfwd>
#include <optional>
#include <string>

namespace fastcorot::cli {

struct ViewOptions {
  std::string scene;       // empty: the built-in beam
  PictureOptions picture;  // size is the window's
  bool paused = false;
  bool strict = false;  // warnings (unknown attributes) are errors
  long frames = 0;  // > 0: close after this many frames
  std::string screenshot;
  std::optional<double> dt;
  int threads = 0;  // 0: every core (thread_count.h)
};

// Opens the window and runs until it is closed (or `frames` are shown). Throws fastcorot::Error on
// bad input or when no window can be opened (no display: use xvfb-run, or `run --png`).
void view(const ViewOptions& options, std::ostream& out, std::ostream& err);

}  // namespace fastcorot::cli
