// The parsed form of a SOFA scene file (.scn, XML): a tree of nodes, each with its attributes, its
// components (objects) in document order and its child nodes, every item remembering the file and
// line it came from so that later errors can point at it. `<include href="..."/>` is expanded here as
// SOFA does: an included <Node> becomes a child node; an included <Group> has its contents inserted
// where the include stands. Paths are relative to the including file. No meaning is given to
// components at this stage: see scene_builder.h.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace fastcorot {

struct SourceLocation {
  std::filesystem::path file;
  int line = 0;
  std::string to_string() const;  // "file:line"
};

struct SceneObject {
  std::string type;                               // element name, e.g. "MechanicalObject"
  std::map<std::string, std::string> attributes;  // as written
  SourceLocation location;

  // The `name` attribute, or "" when absent.
  std::string name() const;
};

struct SceneNode {
  std::string name;
  std::map<std::string, std::string> attributes;  // including name
  std::vector<SceneObject> objects;
  std::vector<SceneNode> children;
  SourceLocation location;
};

// Parses a scene file. Throws fastcorot::Error naming the file and line for malformed XML, a root
// that is not a Node, an include that cannot be read, or an include cycle.
SceneNode parse_scene_file(const std::filesystem::path& path);

// Parses scene text; `file` names it in messages and anchors relative include paths.
SceneNode parse_scene_text(const std::string& text, const std::filesystem::path& file);

}  // namespace fastcorot
