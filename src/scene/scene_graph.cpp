#include "fastcorot/scene/scene_graph.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/component_table.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <map>
#include <optional>
#include <string_view>
#include <fstream>
#include <sstream>

namespace fastcorot {

std::string SourceLocation::to_string() const { return file.string() + ":" + std::to_string(line); }

std::string SceneObject::name() const {
  const auto it = attributes.find("name");
  return it == attributes.end() ? std::string() : it->second;
}

namespace {

bool is_node_element(const std::string& tag) { return tag == "Node" || tag == "node"; }

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw make_error(path.string(), ": cannot open scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

class Parser {
 public:
  SceneNode parse(const std::string& text, const std::filesystem::path& file) {
    tinyxml2::XMLDocument document;
    if (document.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
      throw make_error(file.string(), ":", document.ErrorLineNum(), ": malformed XML: ",
                       document.ErrorStr());
    }
    const tinyxml2::XMLElement* root = document.RootElement();
    if (!root) throw make_error(file.string(), ": no root element");
    if (!is_node_element(root->Name())) {
      throw make_error(file.string(), ":", root->GetLineNum(), ": the root element is <", root->Name(),
                       ">; a scene's root must be a <Node>");
    }
    files_.push_back(std::filesystem::weakly_canonical(file));
    SceneNode node = read_node(*root, file);
    files_.pop_back();
    return node;
  }

 private:
  SceneNode read_node(const tinyxml2::XMLElement& element, const std::filesystem::path& file) {
    SceneNode node;
    node.location = {file, element.GetLineNum()};
    node.attributes = read_attributes(element);
    node.name = node.attributes.count("name") ? node.attributes["name"] : std::string("unnamed");
    read_children(element, file, node);
    return node;
  }

  void read_children(const tinyxml2::XMLElement& element, const std::filesystem::path& file, SceneNode& node) {
    for (const auto* child = element.FirstChildElement(); child; child = child->NextSiblingElement()) {
      const std::string tag = child->Name();
      if (is_node_element(tag)) {
        node.children.push_back(read_node(*child, file));
      } else if (tag == "include" || tag == "Include") {
        expand_include(*child, file, node);
      } else {
        SceneObject object;
        object.type = tag;
        object.attributes = read_attributes(*child);
        object.location = {file, child->GetLineNum()};
        // SOFA's older syntax: <Object type="MechanicalObject" .../>
        if (tag == "Object" && object.attributes.count("type")) {
          object.type = object.attributes["type"];
          object.attributes.erase("type");
        }
        if (!is_known_component(object.type) && replace_by_object_file(*child, object.type, file, node)) continue;
        node.objects.push_back(std::move(object));
      }
    }
  }

  void expand_include(const tinyxml2::XMLElement& element, const std::filesystem::path& file, SceneNode& node) {
    const char* href = element.Attribute("href");
    if (!href) throw make_error(file.string(), ":", element.GetLineNum(), ": <include> needs an href attribute");
    std::filesystem::path path;
    try {
      path = find_data_file(file, href);
    } catch (const Error& error) {
      throw make_error(file.string(), ":", element.GetLineNum(), ": cannot read included file ", href, " (",
                       error.what(), ")");
    }
    std::string text;
    try {
      text = read_text_file(path);
    } catch (const Error&) {
      throw make_error(file.string(), ":", element.GetLineNum(), ": cannot read included file ", path.string());
    }
    include_text(element, file, text, path, node);
  }

  // SOFA's loader replaces an element whose type its object factory does not know by the node of
  // the file Objects/<type>.xml on its data path, as an <include> of that file with the element's
  // attributes (the scene's folder first, then the data path: find_data_file). SOFA ships two such
  // files, BoxConstraint.xml and PlaneConstraint.xml; their nodes are built in for scenes read
  // away from SOFA's folders. False when there is no such file.
  bool replace_by_object_file(const tinyxml2::XMLElement& element, const std::string& type,
                              const std::filesystem::path& file, SceneNode& node) {
    const std::string name = "Objects/" + type + ".xml";
    std::filesystem::path path;
    try {
      path = find_data_file(file, name);
    } catch (const Error&) {
      const auto builtin = builtin_object_files().find(type);
      if (builtin == builtin_object_files().end()) return false;
      include_text(element, file, std::string(builtin->second), "<built-in " + name + ">", node,
                   SourceLocation{file, element.GetLineNum()});
      return true;
    }
    include_text(element, file, read_text_file(path), path, node);
    return true;
  }

  static const std::map<std::string, std::string_view>& builtin_object_files() {
    // The same elements as SOFA's examples/Objects files: a region of interest and the
    // FixedProjectiveConstraint of the points it selects (`@[-1]`: the object just before).
    static const std::map<std::string, std::string_view> files = {
        {"BoxConstraint",
         R"(<Node name="Group"><BoxROI name="box_roi" box="0 0 0 1 1 1" drawBoxes="0"/>)"
         R"(<FixedProjectiveConstraint indices="@[-1].indices"/></Node>)"},
        {"PlaneConstraint",
         R"(<Node name="Group"><PlaneROI name="box_roi" plane="-4 3 0 1 2 1 0 0 1 2" drawSize="0"/>)"
         R"(<FixedProjectiveConstraint indices="@[-1].indices" drawSize="0"/></Node>)"}};
    return files;
  }

  // Includes the scene text `text` of file `path` (its root a <Node> or <Group>) where `element`
  // stands, with the element's attributes. What built-in text holds is placed at `built_in`: the
  // scene's element, which errors then name.
  void include_text(const tinyxml2::XMLElement& element, const std::filesystem::path& file, const std::string& text,
                    const std::filesystem::path& path, SceneNode& node,
                    const std::optional<SourceLocation>& built_in = std::nullopt) {
    const auto canonical = std::filesystem::weakly_canonical(path);
    for (const auto& open : files_) {
      if (open == canonical) {
        throw make_error(file.string(), ":", element.GetLineNum(), ": include cycle through ", path.string());
      }
    }
    tinyxml2::XMLDocument document;
    if (document.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
      throw make_error(path.string(), ":", document.ErrorLineNum(), ": malformed XML: ", document.ErrorStr());
    }
    const tinyxml2::XMLElement* root = document.RootElement();
    if (!root) throw make_error(path.string(), ": no root element");
    files_.push_back(canonical);
    const std::string tag = root->Name();
    SceneNode included;
    if (is_node_element(tag)) {
      included = read_node(*root, path);
    } else if (tag == "Group" || tag == "_Group_") {
      included.name = "Group";
      included.location = {path, root->GetLineNum()};
      read_children(*root, path, included);
    } else {
      throw make_error(path.string(), ":", root->GetLineNum(), ": an included file's root must be a <Node> or <Group>");
    }
    files_.pop_back();
    if (built_in) place_at(included, *built_in);
    add_included(element, std::move(included), node);
  }

  static void place_at(SceneNode& node, const SourceLocation& location) {
    node.location = location;
    for (auto& object : node.objects) object.location = location;
    for (auto& child : node.children) place_at(child, location);
  }

  // The include's attributes: a name renames the included node; any other replaces the values of
  // the attributes of that name in the included nodes and objects (NODE__attribute: in the node or
  // object NODE only). A node named Group (as the file names it: a name given by the include does
  // not change that, as in SOFA) joins the including node.
  static void add_included(const tinyxml2::XMLElement& element, SceneNode included, SceneNode& node) {
    const bool group = included.name == "Group" || included.name == "_Group_";
    for (const auto* a = element.FirstAttribute(); a; a = a->Next()) {
      const std::string attribute = a->Name();
      if (attribute == "href" || attribute == "type") continue;
      if (attribute == "name") {
        included.name = a->Value();
        included.attributes["name"] = a->Value();
        continue;
      }
      const auto separator = attribute.find("__");
      if (separator == std::string::npos) {
        replace_attribute(included, attribute, a->Value(), nullptr);
      } else {
        const std::string target = attribute.substr(0, separator);
        replace_attribute(included, attribute.substr(separator + 2), a->Value(), &target);
      }
    }
    if (group) {
      for (auto& object : included.objects) node.objects.push_back(std::move(object));
      for (auto& child : included.children) node.children.push_back(std::move(child));
    } else {
      node.children.push_back(std::move(included));
    }
  }

  // Sets `attribute` to `value` wherever it is already present (in nodes and objects named
  // `*only` when given).
  static void replace_attribute(SceneNode& node, const std::string& attribute, const std::string& value,
                                const std::string* only) {
    const auto set = [&](std::map<std::string, std::string>& attributes) {
      const auto it = attributes.find(attribute);
      if (it == attributes.end()) return;
      const auto name = attributes.find("name");
      if (only && (name == attributes.end() || name->second != *only)) return;
      it->second = value;
    };
    set(node.attributes);
    for (auto& object : node.objects) set(object.attributes);
    for (auto& child : node.children) replace_attribute(child, attribute, value, only);
  }

  static std::map<std::string, std::string> read_attributes(const tinyxml2::XMLElement& element) {
    std::map<std::string, std::string> attributes;
    for (const auto* a = element.FirstAttribute(); a; a = a->Next()) attributes[a->Name()] = a->Value();
    return attributes;
  }

  std::vector<std::filesystem::path> files_;
};

}  // namespace

namespace {

std::mutex& repositories_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::vector<std::filesystem::path>& repositories() {
  static std::vector<std::filesystem::path> folders;
  return folders;
}

}  // namespace

void add_data_repository(const std::filesystem::path& folder) {
  const std::lock_guard lock(repositories_mutex());
  auto& folders = repositories();
  if (std::find(folders.begin(), folders.end(), folder) == folders.end()) folders.push_back(folder);
}

std::vector<std::filesystem::path> data_repositories() {
  const std::lock_guard lock(repositories_mutex());
  return repositories();
}

std::filesystem::path find_data_file(const std::filesystem::path& from, const std::string& name) {
  const std::filesystem::path relative(name);
  if (relative.is_absolute()) {
    if (std::filesystem::exists(relative)) return relative;
    throw make_error(name, ": no such file");
  }
  std::vector<std::filesystem::path> tried;
  const auto found = [&](const std::filesystem::path& candidate) {
    tried.push_back(candidate);
    std::error_code ec;
    return std::filesystem::is_regular_file(candidate, ec);
  };
  const std::filesystem::path folder = from.parent_path();
  if (found(folder / relative)) return folder / relative;
  // The current folder, as SOFA looks first (it makes the scene's folder the current one as it
  // loads; a script run from its folder names files from there, also in the modules it imports).
  {
    std::error_code ec;
    const std::filesystem::path here = std::filesystem::current_path(ec);
    if (!ec && here != std::filesystem::absolute(folder, ec) && found(here / relative)) return here / relative;
  }
  if (const char* data_path = std::getenv("FASTCOROT_DATA_PATH")) {
    std::string list = data_path;
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      if (end > start) {
        const std::filesystem::path candidate = std::filesystem::path(list.substr(start, end - start)) / relative;
        if (found(candidate)) return candidate;
      }
      start = end + 1;
    }
  }
  for (const auto& folder : data_repositories()) {
    if (found(folder / relative)) return folder / relative;
  }
  std::error_code ec;
  for (std::filesystem::path above = std::filesystem::absolute(from, ec).parent_path(); !above.empty();
       above = above.parent_path()) {
    if (std::filesystem::is_directory(above / "share", ec) || std::filesystem::is_directory(above / "examples", ec)) {
      for (const char* sub : {"share", "share/mesh", "examples"}) {
        if (found(above / sub / relative)) return above / sub / relative;
      }
      // Not there: further up (SofaPython3's examples/ sit below the folder with SOFA's share/).
    }
    if (above == above.parent_path()) break;
  }
  std::string where;
  for (const auto& t : tried) where += (where.empty() ? "" : ", ") + t.string();
  throw make_error(name, ": no such file (looked for ", where, ")");
}

SceneNode parse_scene_text(const std::string& text, const std::filesystem::path& file) {
  return Parser().parse(text, file);
}

SceneNode parse_scene_file(const std::filesystem::path& path) {
  return parse_scene_text(read_text_file(path), path);
}

}  // namespace fastcorot
