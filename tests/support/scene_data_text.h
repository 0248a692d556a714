// A scene written inline, read through the scene's data (SceneData) without building it: what
// engines and links compute, as a component that links to them reads it.
#pragma once

#include "fastcorot/core/error.h"
#include "scene/scene_data.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::testing {

class SceneDataText {
 public:
  // `body`: the root node's contents; `file`: the name errors give the scene.
  explicit SceneDataText(const std::string& body, const std::string& file = "test.scn")
      : scene_(parse_scene_text("<Node name=\"root\">" + body + "</Node>", file)) {
    data_ = std::make_unique<scene_detail::SceneData>(scene_, info_, &warnings_);
  }
  SceneDataText(const SceneDataText&) = delete;
  SceneDataText& operator=(const SceneDataText&) = delete;

  // Data `name` of the root's component named `component`.
  scene_detail::Numbers operator()(const std::string& component, const std::string& name) {
    for (auto& c : data_->root().components) {
      if (c->name() == component) return data_->data(*c, name);
    }
    throw make_error("no ", component);
  }
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  SceneNode scene_;
  std::vector<std::string> info_, warnings_;
  std::unique_ptr<scene_detail::SceneData> data_;
};

}  // namespace fastcorot::testing
