#include "fastcorot/scene/scene_graph.h"

#include "fastcorot/core/error.h"

#include <tinyxml2.h>

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
        node.objects.push_back(std::move(object));
      }
    }
  }

  void expand_include(const tinyxml2::XMLElement& element, const std::filesystem::path& file, SceneNode& node) {
    const char* href = element.Attribute("href");
    if (!href) throw make_error(file.string(), ":", element.GetLineNum(), ": <include> needs an href attribute");
    const std::filesystem::path path = file.parent_path() / href;
    const auto canonical = std::filesystem::weakly_canonical(path);
    for (const auto& open : files_) {
      if (open == canonical) {
        throw make_error(file.string(), ":", element.GetLineNum(), ": include cycle through ", path.string());
      }
    }
    std::string text;
    try {
      text = read_text_file(path);
    } catch (const Error&) {
      throw make_error(file.string(), ":", element.GetLineNum(), ": cannot read included file ", path.string());
    }
    tinyxml2::XMLDocument document;
    if (document.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
      throw make_error(path.string(), ":", document.ErrorLineNum(), ": malformed XML: ", document.ErrorStr());
    }
    const tinyxml2::XMLElement* root = document.RootElement();
    if (!root) throw make_error(path.string(), ": no root element");
    files_.push_back(canonical);
    const std::string tag = root->Name();
    if (is_node_element(tag)) {
      node.children.push_back(read_node(*root, path));  // the included node becomes a child
    } else if (tag == "Group" || tag == "_Group_") {
      read_children(*root, path, node);  // a group's contents join the including node
    } else {
      throw make_error(path.string(), ":", root->GetLineNum(), ": an included file's root must be a <Node> or <Group>");
    }
    files_.pop_back();
  }

  static std::map<std::string, std::string> read_attributes(const tinyxml2::XMLElement& element) {
    std::map<std::string, std::string> attributes;
    for (const auto* a = element.FirstAttribute(); a; a = a->Next()) attributes[a->Name()] = a->Value();
    return attributes;
  }

  std::vector<std::filesystem::path> files_;
};

}  // namespace

SceneNode parse_scene_text(const std::string& text, const std::filesystem::path& file) {
  return Parser().parse(text, file);
}

SceneNode parse_scene_file(const std::filesystem::path& path) {
  return parse_scene_text(read_text_file(path), path);
}

}  // namespace fastcorot
