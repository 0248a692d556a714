#include "viewer_session.h"

#include "run_command.h"
#include "thread_count.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"
#include "fastcorot/render/picking.h"

#include <algorithm>
#include <filesystem>
#include <optional>

namespace fastcorot::cli {

ViewerSession::ViewerSession(const ViewOptions& options) : options_(options) {
  draw = draw_options(options.picture);
  playing = !options.paused;
  check_threads_option(options.threads);
  if (options.dt && !(*options.dt > 0)) throw make_error("--dt ", *options.dt, ": must be > 0");
  load(false);
  // A brush of 1.5 % of the scene's diagonal takes a few tetrahedra of a typical mesh per cut, so
  // that one drag leaves a visible cut; the panel changes it.
  cut_radius = 0.015 * scene_->simulation.scene_size();
  title_ = options.scene.empty() ? "built-in cantilever beam"
                                 : std::filesystem::path(options.scene).filename().string();
}

void ViewerSession::load(bool again) {
  if (!source_) source_ = open_scene(options_.scene, options_.strict);
  LoadedScene& scene = again ? source_->reload() : source_->scene();
  warnings = scene.warnings;
  if (options_.dt) scene.simulation.dt = *options_.dt;
  scene.simulation.threads = threads_to_run(options_.threads, false, simulated_points(scene.simulation));
  derive_materials(scene.simulation);
  scene_ = &scene;
  removed_ = 0;
}

void ViewerSession::derive_materials(const Simulation<double>& simulation) {
  materials.clear();
  for (const auto& object : simulation.objects) {
    ObjectMaterial material;
    if (!object.system.force_fields.empty()) {
      const auto& field = object.system.force_fields.front();
      if (const auto* corotational = dynamic_cast<const CorotationalForceField<double>*>(field.get())) {
        material.method = corotational->method();
        material.young_modulus = corotational->parameters().young_modulus.front();
        material.poisson_ratio = corotational->parameters().poisson_ratio.front();
      } else if (const auto* fem = dynamic_cast<const TetrahedronFEMForceField<double>*>(field.get())) {
        material.method_editable = false;
        material.young_modulus = fem->parameters().young_modulus.front();
        material.poisson_ratio = fem->parameters().poisson_ratio.front();
      }
    }
    materials.push_back(material);
  }
}

void ViewerSession::follow_rebuilt_scene() {
  if (source_->take_rebuilt()) derive_materials(scene_->simulation);
}

void ViewerSession::step() {
  const auto start = std::chrono::steady_clock::now();
  try {
    source_->begin_step();
    follow_rebuilt_scene();
    scene_->simulation.step();
    source_->end_step();
    follow_rebuilt_scene();
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
    load(true);
    message.clear();
  } catch (const Error& error) {
    message = std::string("reload failed: ") + error.what();
  }
}

void ViewerSession::key_pressed(char key) {
  try {
    source_->key_pressed(key);
    follow_rebuilt_scene();
  } catch (const Error& error) {
    playing = false;
    message = error.what();
  }
}

void ViewerSession::set_method(std::size_t o, RotationMethod method) {
  auto& object = scene_->simulation.objects.at(o);
  // The methods of FastTetrahedralCorotationalForceField; a TetrahedronFEMForceField keeps its own.
  for (auto& field : object.system.force_fields) {
    if (auto* corotational = dynamic_cast<CorotationalForceField<double>*>(field.get())) corotational->set_method(method);
  }
  materials.at(o).method = method;
}

void ViewerSession::set_material(std::size_t o, double young_modulus, double poisson_ratio) {
  auto& object = scene_->simulation.objects.at(o);
  auto& fields = object.system.force_fields;
  try {
    // Build every new field before replacing any, so that a bad value changes nothing.
    std::vector<std::shared_ptr<ForceField<double>>> rebuilt;
    for (const auto& field : fields) {
      auto mesh = object.mesh && &field->mesh() == object.mesh.get()
                      ? object.mesh
                      : std::make_shared<TetMesh>(field->mesh());
      const auto rebuild = [&](auto parameters, auto* kind) {
        parameters.young_modulus = {young_modulus};
        parameters.poisson_ratio = {poisson_ratio};
        using Field = std::remove_pointer_t<decltype(kind)>;
        rebuilt.push_back(std::make_shared<Field>(mesh, object.system.state.rest_position, parameters));
      };
      if (const auto* corotational = dynamic_cast<const CorotationalForceField<double>*>(field.get())) {
        rebuild(corotational->parameters(), static_cast<CorotationalForceField<double>*>(nullptr));
      } else if (const auto* fem = dynamic_cast<const TetrahedronFEMForceField<double>*>(field.get())) {
        rebuild(fem->parameters(), static_cast<TetrahedronFEMForceField<double>*>(nullptr));
      }
    }
    fields = std::move(rebuilt);
    materials.at(o).young_modulus = young_modulus;
    materials.at(o).poisson_ratio = poisson_ratio;
    message.clear();
  } catch (const Error& error) {
    message = object.path + ": " + error.what();
  }
}

std::size_t ViewerSession::cut(std::size_t o, std::span<const Index> tetrahedra) {
  if (o >= scene_->simulation.objects.size()) {
    message = "cut: there is no object " + std::to_string(o);
    return 0;
  }
  auto& object = scene_->simulation.objects[o];
  if (!object.mesh) {
    message = "cut: " + object.path + " has no tetrahedra to cut";
    return 0;
  }
  if (tetrahedra.empty()) return 0;
  std::span<const Index> removing = tetrahedra;
  std::vector<Index> kept_back;
  if (tetrahedra.size() >= static_cast<std::size_t>(object.mesh->num_tetrahedra())) {
    // A force field and a mass are only ever built on a mesh with tetrahedra, so the last one
    // stays: an object cut away entirely would leave a force field in a state nothing else makes.
    // Which one stays does not matter to the user; the smallest index is as good as any.
    kept_back.assign(tetrahedra.begin(), tetrahedra.end());
    std::sort(kept_back.begin(), kept_back.end());
    kept_back.erase(kept_back.begin());
    removing = kept_back;
  }
  try {
    if (!removing.empty()) object.system.remove_tetrahedra(*object.mesh, removing);
  } catch (const Error& error) {
    message = "cut: " + object.path + ": " + error.what();
    return 0;
  }
  removed_ += removing.size();
  if (removing.size() < tetrahedra.size()) {
    message = "cut: " + object.path + " keeps its last tetrahedron";
  } else {
    message.clear();
  }
  return removing.size();
}

std::size_t ViewerSession::cut_at(const Camera& camera, int width, int height,
                                  const Eigen::Vector2d& pixel) {
  if (width < 1 || height < 1) return 0;  // a minimised window shows nothing to cut
  const Ray ray = pixel_ray(camera, width, height, pixel);
  auto& objects = scene_->simulation.objects;
  std::optional<TetrahedronHit> nearest;
  std::size_t hit_object = 0;
  for (std::size_t o = 0; o < objects.size(); ++o) {
    if (!objects[o].mesh) continue;
    const auto hit =
        pick_tetrahedron<double>(*objects[o].mesh, objects[o].system.state.position, ray);
    if (hit && (!nearest || hit->distance < nearest->distance)) {
      nearest = hit;
      hit_object = o;
    }
  }
  if (!nearest) return 0;
  const auto& object = objects[hit_object];
  std::vector<Index> brush = tetrahedra_within<double>(*object.mesh, object.system.state.position,
                                                       nearest->point, cut_radius);
  // The tetrahedron hit goes even when its centroid is outside the brush (a small radius, a long
  // thin element), so every cut under the mouse removes something.
  if (!std::binary_search(brush.begin(), brush.end(), nearest->tetrahedron)) {
    brush.insert(std::lower_bound(brush.begin(), brush.end(), nearest->tetrahedron),
                 nearest->tetrahedron);
  }
  return cut(hit_object, brush);
}

}  // namespace fastcorot::cli
