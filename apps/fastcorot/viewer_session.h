// The state behind `fastcorot view`, apart from any window so that it can be tested headless: the
// simulation and where it came from, play/pause and single steps, the measured steps per second,
// the drawing switches, live changes of each object's rotation method and material, and cutting:
// tetrahedra picked under the mouse are removed from the mesh, and the force fields and mass follow
// (MechanicalSystem::remove_tetrahedra). A failure (a diverging step, a bad modulus, a refused cut)
// never ends the session: it pauses or changes nothing, and leaves a message.
#pragma once

#include "view_command.h"

#include "fastcorot/fem/rotation_method.h"
#include "fastcorot/render/camera.h"
#include "fastcorot/render/draw_geometry.h"
#include "scene_source.h"

#include "fastcorot/scene/scene_builder.h"

#include <chrono>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace fastcorot::cli {

// What the panel edits for one object; applied with set_method / set_material.
struct ObjectMaterial {
  RotationMethod method = RotationMethod::qr;
  bool method_editable = true;  // false for TetrahedronFEMForceField (its methods are its own)
  double young_modulus = 0;
  double poisson_ratio = 0;
};

class ViewerSession {
 public:
  // Loads the scene (throws fastcorot::Error on a bad scene or option, like `run`).
  explicit ViewerSession(const ViewOptions& options);

  Simulation<double>& simulation() { return scene_->simulation; }
  const Simulation<double>& simulation() const { return scene_->simulation; }
  const std::string& title() const { return title_; }

  bool playing = true;
  int steps_per_frame = 1;
  DrawOptions draw;
  std::string message;                    // the last failure, shown until the next success
  std::vector<ObjectMaterial> materials;  // one per object, as last applied
  std::vector<std::string> warnings;      // of the scene as last loaded (unknown attributes)
  // Cutting: in cut mode the view's left drag cuts instead of orbiting. The brush removes, besides
  // the tetrahedron hit, those of the same object whose centroid lies within cut_radius (world
  // units) of the point hit; 0 cuts one tetrahedron at a time.
  bool cut_mode = false;
  double cut_radius = 0;

  // Called once per frame: steps_per_frame steps while playing.
  void advance();
  // One step (pauses nothing); on failure pauses and sets `message`.
  void step();
  // Reloads the scene from its source (same options); on failure keeps the current one.
  void reload();
  // A key for the scene's controllers (a script's onKeypressedEvent); a failure goes to `message`.
  void key_pressed(char key);
  // Applies `method` to every force field of object `o`.
  void set_method(std::size_t o, RotationMethod method);
  // Rebuilds every force field of object `o` with a uniform E and nu (same mesh, rest positions,
  // method and Rayleigh stiffness); on failure (E <= 0, nu outside [0, 0.5)) keeps the old ones
  // and sets `message`.
  void set_material(std::size_t o, double young_modulus, double poisson_ratio);

  // Removes tetrahedra `tetrahedra` (current numbering, any order) of object `o`; the others are
  // renumbered by swap-with-last. An object keeps at least one tetrahedron, since its force field
  // and mass are built on a non-empty mesh: a cut that would take the last ones leaves one of them
  // and says so in `message`. On failure (a bad index, an object without a mesh) nothing changes
  // and `message` says why. Returns how many were removed.
  std::size_t cut(std::size_t o, std::span<const Index> tetrahedra);
  // Cuts where `pixel` of a width × height view through `camera` shows an object: the nearest
  // boundary triangle under it over every object names the tetrahedron, and the brush adds its
  // neighbours. Returns how many were removed (0 where the pixel shows no object).
  std::size_t cut_at(const Camera& camera, int width, int height, const Eigen::Vector2d& pixel);
  // Tetrahedra removed by cuts since the scene was (re)loaded, over every object.
  std::size_t removed_tetrahedra() const { return removed_; }

  // Steps per second over the last half second or so of stepping (0 before any).
  double steps_per_second() const { return rate_; }

 private:
  void load(bool again);
  // One material entry per object of `simulation`, as its first force field has it.
  void derive_materials(const Simulation<double>& simulation);
  // After a script rebuilt the scene in place (its tree changed while running): the materials again.
  void follow_rebuilt_scene();

  ViewOptions options_;
  std::unique_ptr<SceneSource> source_;
  LoadedScene* scene_ = nullptr;  // the source's
  std::string title_;
  double rate_ = 0;
  std::size_t removed_ = 0;
  long window_steps_ = 0;
  double window_seconds_ = 0;
};

}  // namespace fastcorot::cli
