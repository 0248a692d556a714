#include "viewer_panel.h"

#include <imgui.h>

#include <array>

namespace fastcorot::cli {

namespace {

constexpr std::array<RotationMethod, 4> kMethods = {RotationMethod::qr, RotationMethod::polar,
                                                    RotationMethod::polar2, RotationMethod::none};
constexpr std::array<const char*, 4> kMethodNames = {"qr (large)", "polar", "polar2",
                                                     "none (small)"};
constexpr std::array<const char*, 3> kDrawingNames = {"as the scene says", "all", "none"};

int index_of(RotationMethod method) {
  for (std::size_t i = 0; i < kMethods.size(); ++i) {
    if (kMethods[i] == method) return static_cast<int>(i);
  }
  return 0;
}

}  // namespace

PanelRequests draw_viewer_panel(ViewerSession& session, PanelState& state,
                                double frames_per_second) {
  PanelRequests requests;
  Simulation<double>& simulation = session.simulation();
  if (state.pending.size() != session.materials.size()) state.pending = session.materials;

  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(300, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);  // the scene stays visible behind the panel
  ImGui::Begin("fastcorot");
  ImGui::Text("%s", session.title().c_str());
  ImGui::Text("t = %.3f s   step %ld   dt = %g", simulation.time(), simulation.steps_done(),
              simulation.dt);
  ImGui::Text("%.1f steps/s (simulation)   %.0f frames/s", session.steps_per_second(),
              frames_per_second);
  if (ImGui::Button(session.playing ? "Pause" : "Play")) session.playing = !session.playing;
  ImGui::SameLine();
  if (ImGui::Button("Step")) session.step();
  ImGui::SameLine();
  if (ImGui::Button("Reload")) {
    session.reload();
    state.pending = session.materials;
  }
  ImGui::SameLine();
  if (ImGui::Button("Reframe")) requests.reframe = true;
  ImGui::SliderInt("steps per frame", &session.steps_per_frame, 1, 20);

  int drawing = static_cast<int>(session.draw.tetrahedra);
  if (ImGui::Combo("tetrahedra", &drawing, kDrawingNames.data(),
                   static_cast<int>(kDrawingNames.size()))) {
    session.draw.tetrahedra = static_cast<TetrahedronDrawing>(drawing);
  }
  ImGui::Checkbox("mesh edges", &session.draw.surface_edges);
  ImGui::SameLine();
  ImGui::Checkbox("fixed points", &session.draw.fixed_points);
  ImGui::SameLine();
  ImGui::Checkbox("boxes", &session.draw.boxes);
  ImGui::SameLine();
  ImGui::Checkbox("constraints (L)", &session.draw.constraints);
  ImGui::SameLine();
  ImGui::Checkbox("contacts (K)", &session.draw.contacts);

  ImGui::Checkbox("cut mode (C)", &session.cut_mode);
  ImGui::SameLine();
  ImGui::Text("removed %zu tetrahedra", session.removed_tetrahedra());
  // Up to a tenth of the scene's diagonal: beyond that one click takes most of an object.
  const double no_radius = 0, widest = 0.1 * simulation.scene_size();
  ImGui::SliderScalar("brush radius", ImGuiDataType_Double, &session.cut_radius, &no_radius,
                      &widest, "%.3g");

  for (std::size_t o = 0; o < simulation.objects.size(); ++o) {
    if (simulation.objects[o].system.force_fields.empty()) continue;
    ImGui::PushID(static_cast<int>(o));
    // Open by default only when there are few objects, so that the panel fits the window.
    const ImGuiTreeNodeFlags open =
        simulation.objects.size() <= 2 ? ImGuiTreeNodeFlags_DefaultOpen : 0;
    if (ImGui::CollapsingHeader(simulation.objects[o].path.c_str(), open)) {
      int method = index_of(session.materials[o].method);
      if (!session.materials[o].method_editable) {
        ImGui::TextUnformatted(("method " + simulation.objects[o].system.force_fields.front()->method_name()).c_str());
      } else if (ImGui::Combo("method", &method, kMethodNames.data(), static_cast<int>(kMethodNames.size()))) {
        session.set_method(o, kMethods[static_cast<std::size_t>(method)]);
        state.pending[o].method = session.materials[o].method;
      }
      ImGui::InputDouble("E", &state.pending[o].young_modulus, 0, 0, "%.6g");
      ImGui::InputDouble("nu", &state.pending[o].poisson_ratio, 0, 0, "%.4g");
      if (ImGui::Button("apply E, nu")) {
        session.set_material(o, state.pending[o].young_modulus, state.pending[o].poisson_ratio);
      }
    }
    ImGui::PopID();
  }
  if (!session.message.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.35f, 1.0f));
    ImGui::TextWrapped("%s", session.message.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::TextDisabled(
      "drag: orbit  right drag: pan  wheel: zoom\n"
      "ctrl drag (or drag in cut mode): cut\nspace: play/pause  N: step  D: drawing\n"
      "E: edges  L: constraints  K: contacts\nC: cut mode  F: reframe  R: reload  Q: quit");
  ImGui::End();
  return requests;
}

}  // namespace fastcorot::cli
