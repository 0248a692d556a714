// Where `fastcorot run` and `fastcorot view` get their scene: a scene or mesh file or the built-in
// beam (load_scene_argument), or a Python script written for SofaPython3, whose createScene(root)
// builds the scene and whose controllers are called around each step. Scripts need the Python
// module: it registers the loader (set_script_loader) when `python3 -m fastcorot` runs the commands,
// which is what the `fastcorot` program does for a .py scene (docs/python.md).
#pragma once

#include "fastcorot/scene/scene_builder.h"

#include <functional>
#include <memory>
#include <string>

namespace fastcorot::cli {

class SceneSource {
 public:
  virtual ~SceneSource() = default;
  // The scene, built; it stays owned by the source (a script's controllers view its state).
  virtual LoadedScene& scene() = 0;
  // Builds the scene again from its source (the viewer's reload) and returns it.
  virtual LoadedScene& reload() = 0;
  // Around each step, as SOFA's animation loop sends AnimateBeginEvent and AnimateEndEvent. A
  // controller's failure is a fastcorot::Error naming it.
  virtual void begin_step() {}
  virtual void end_step() {}
  // A key pressed in the viewer (SOFA's KeypressedEvent), as its character.
  virtual void key_pressed(char /*key*/) {}
  // Whether state outside the simulation (a controller's own) takes part: a checkpoint then holds
  // only part of what the run depends on.
  virtual bool has_controllers() const { return false; }
  // True once after the scene was built again in place (a script's controller added or removed
  // nodes while it runs): what was derived from its objects is to be derived again.
  virtual bool take_rebuilt() { return false; }
};

// True for a scene argument that names a Python script (.py).
bool is_script(const std::string& scene);

// The source of `scene` (as load_scene_argument takes it, or a .py script through the registered
// loader; without one, a fastcorot::Error saying how to run scripts).
std::unique_ptr<SceneSource> open_scene(const std::string& scene, bool strict);

using ScriptLoader = std::function<std::unique_ptr<SceneSource>(const std::string& script, bool strict)>;
void set_script_loader(ScriptLoader loader);

}  // namespace fastcorot::cli
