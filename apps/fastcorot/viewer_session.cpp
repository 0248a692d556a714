#include "viewer_session.h"

#include "run_command.h"

#include "fastcorot/core/error.h"

#include <filesystem>

namespace fastcorot::cli {

ViewerSession::ViewerSession(const ViewOptions& options) : options_(options) {
  draw = draw_options(options.picture);
  playing = !options.paused;
  if (options.threads < 1) throw make_error("--threads ", options.threads, ": must be >= 1");
  if (options.dt && !(*options.dt > 0)) throw make_error("--dt ", *options.dt, ": must be > 0");
  load();
  title_ = options.scene.empty() ? "built-in cantilever beam"
                                 : std::filesystem::path(options.scene).filename().string();
}

void ViewerSession::load() {
  LoadedScene scene = load_scene_argument(options_.scene);
  if (options_.dt) scene.simulation.dt = *options_.dt;
  scene.simulation.threads = options_.threads;
  materials.clear();
  for (const auto& object : scene.simulation.objects) {
    ObjectMaterial material;
    if (!object.system.force_fields.empty()) {
      const auto& parameters = object.system.force_fields.front()->parameters();
      material.method = parameters.method;
      material.young_modulus = parameters.young_modulus.front();
      material.poisson_ratio = parameters.poisson_ratio.front();
    }
    materials.push_back(material);
  }
  scene_ = std::move(scene);
}

void ViewerSession::step() {
  const auto start = std::chrono::steady_clock::now();
  try {
    scene_.simulation.step();
    message.clear();
  } catch (const Error& error) {
    playing = false;
    message = error.what();
    return;
  }
  window_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++window_steps_;
  // Refresh about twice a second, and at once when there is no figure yet.
  if (window_seconds_ >= 0.5 || rate_ == 0) {
    rate_ = window_seconds_ > 0 ? static_cast<double>(window_steps_) / window_seconds_ : 0;
    window_steps_ = 0;
    window_seconds_ = 0;
  }
}

void ViewerSession::advance() {
  for (int s = 0; playing && s < steps_per_frame; ++s) step();
}

void ViewerSession::reload() {
  try {
    load();
    message.clear();
  } catch (const Error& error) {
    message = std::string("reload failed: ") + error.what();
  }
}

void ViewerSession::set_method(std::size_t o, RotationMethod method) {
  auto& object = scene_.simulation.objects.at(o);
  for (auto& field : object.system.force_fields) field->set_method(method);
  materials.at(o).method = method;
}

void ViewerSession::set_material(std::size_t o, double young_modulus, double poisson_ratio) {
  auto& object = scene_.simulation.objects.at(o);
  auto& fields = object.system.force_fields;
  try {
    // Build every new field before replacing any, so that a bad value changes nothing.
    std::vector<std::shared_ptr<CorotationalForceField<double>>> rebuilt;
    for (const auto& field : fields) {
      auto parameters = field->parameters();
      parameters.young_modulus = {young_modulus};
      parameters.poisson_ratio = {poisson_ratio};
      auto mesh = object.mesh && &field->mesh() == object.mesh.get()
                      ? object.mesh
                      : std::make_shared<TetMesh>(field->mesh());
      rebuilt.push_back(std::make_shared<CorotationalForceField<double>>(
          mesh, object.system.state.rest_position, parameters));
    }
    fields = std::move(rebuilt);
    materials.at(o).young_modulus = young_modulus;
    materials.at(o).poisson_ratio = poisson_ratio;
    message.clear();
  } catch (const Error& error) {
    message = object.path + ": " + error.what();
  }
}

}  // namespace fastcorot::cli
