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

// Finds a file a scene names (a mesh, an included file) as SOFA's data repositories find it: `name`
// itself when absolute; else in the folder of `from` (the file that names it), then in the current
// folder, then in each folder of
// the environment variable FASTCOROT_DATA_PATH (colon-separated), then in the `share/`,
// `share/mesh/` and `examples/` folders of each folder above `from` that has a `share/` or an
// `examples/` folder, nearest first. Returns the first that exists; throws fastcorot::Error listing where it
// looked when none does.
std::filesystem::path find_data_file(const std::filesystem::path& from, const std::string& name);

// SOFA's AddDataRepository (and AddResourceRepository): find_data_file also looks in `folder`, after
// the folders of FASTCOROT_DATA_PATH, for the rest of the process (SOFA's DataRepository is
// process-wide too). Adding a folder twice keeps it once. Thread-safe.
void add_data_repository(const std::filesystem::path& folder);
std::vector<std::filesystem::path> data_repositories();

// Parses a scene file. Throws fastcorot::Error naming the file and line for malformed XML, a root
// that is not a Node, an include that cannot be read, or an include cycle. <include href="F" a="v">
// works as SOFA's: F is found with find_data_file; attribute a (not href or name) replaces the
// value of every object or node of F that has an attribute a (N__a only in those named N); a
// `name` renames the included node; an included node named Group or _Group_ adds its objects and
// children to the including node.
SceneNode parse_scene_file(const std::filesystem::path& path);

// Parses scene text; `file` names it in messages and anchors relative include paths.
SceneNode parse_scene_text(const std::string& text, const std::filesystem::path& file);

}  // namespace fastcorot
