#include "scene_source.h"

#include "run_command.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <filesystem>

namespace fastcorot::cli {

namespace {

ScriptLoader& script_loader() {
  static ScriptLoader loader;
  return loader;
}

// A scene or mesh file, or the built-in beam.
class FileSource final : public SceneSource {
 public:
  FileSource(std::string scene, bool strict) : scene_(std::move(scene)), strict_(strict), loaded_(reload_scene()) {}

  LoadedScene& scene() override { return loaded_; }
  LoadedScene& reload() override {
    loaded_ = reload_scene();
    return loaded_;
  }

 private:
  LoadedScene reload_scene() const { return load_scene_argument(scene_, strict_); }

  std::string scene_;
  bool strict_;
  LoadedScene loaded_;
};

}  // namespace

bool is_script(const std::string& scene) {
  std::string extension = std::filesystem::path(scene).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension == ".py";
}

std::unique_ptr<SceneSource> open_scene(const std::string& scene, bool strict) {
  if (!is_script(scene)) return std::make_unique<FileSource>(scene, strict);
  if (!script_loader()) {
    throw make_error(scene, ": a Python script runs through the Python module: `python3 -m fastcorot run ", scene,
                     "` (the fastcorot program does so itself when it was built with the module)");
  }
  return script_loader()(scene, strict);
}

void set_script_loader(ScriptLoader loader) { script_loader() = std::move(loader); }

}  // namespace fastcorot::cli
