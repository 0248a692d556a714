// The Dear ImGui panel of `fastcorot view`: time, step and speed; play, pause, step, reload and
// reframe; the tetrahedra drawing, mesh edges and constraints; cut mode, the cutting brush's radius
// and how many tetrahedra cuts removed; and per object its rotation method (applied at once) and
// Young's modulus and Poisson's ratio (applied with a button, as they rebuild the force field). Messages
// from ViewerSession (a diverging step, a refused value or cut) show in red.
#pragma once

#include "viewer_session.h"

#include <vector>

namespace fastcorot::cli {

// Values being typed in the panel, kept between frames until applied.
struct PanelState {
  std::vector<ObjectMaterial> pending;
};

struct PanelRequests {
  bool reframe = false;
};

// Must be called between ImGui::NewFrame and ImGui::Render.
PanelRequests draw_viewer_panel(ViewerSession& session, PanelState& state,
                                double frames_per_second);

}  // namespace fastcorot::cli
