// Scenes written inline in tests: the body of a root node, through the real parser and builder.
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"

#include <string>

namespace fastcorot::testing {

inline LoadedScene build_scene_text(const std::string& body, const std::string& root_attributes = "") {
  return build_scene(parse_scene_text("<Node name=\"root\" " + root_attributes + ">\n" + body + "\n</Node>", "test.scn"));
}

// The error building the scene gives, or "" when it builds.
inline std::string scene_error(const std::string& body) {
  try {
    build_scene_text(body);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

}  // namespace fastcorot::testing
