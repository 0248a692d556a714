// scene_data_value (fastcorot/scene/scene_builder.h): one datum of one object, read through a
// SceneData over the whole scene, as the builder would read it.
#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"
#include "scene_data.h"

#include <algorithm>

namespace fastcorot {

namespace {

// The object of rank `remaining` in document order (the children, active and deactivated, in the
// order the scene gives them).
scene_detail::Component* nth_component(scene_detail::GraphNode& node, std::size_t& remaining) {
  for (auto& component : node.components) {
    if (remaining == 0) return component.get();
    --remaining;
  }
  std::vector<scene_detail::GraphNode*> children;
  for (auto* list : {&node.children, &node.deactivated}) {
    for (auto& child : *list) children.push_back(child.get());
  }
  std::sort(children.begin(), children.end(), [](const auto* a, const auto* b) { return a->scene < b->scene; });
  for (auto* child : children) {
    if (auto* found = nth_component(*child, remaining)) return found;
  }
  return nullptr;
}

}  // namespace

std::vector<double> scene_data_value(const SceneNode& root, std::size_t object_index, const std::string& name) {
  std::vector<std::string> info, warnings;
  scene_detail::SceneData data(root, info, &warnings);
  std::size_t remaining = object_index;
  scene_detail::Component* component = nth_component(data.root(), remaining);
  if (!component) throw make_error("scene_data_value: the scene has no object ", object_index);
  const scene_detail::Numbers& values = data.data(*component, name);
  return {values.begin(), values.end()};
}

}  // namespace fastcorot
