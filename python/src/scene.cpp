// The scene graph between Python and C++: the component table (what the Python layer checks
// attributes against and documents them with), parsing .scn files into plain Python trees, and
// turning such trees back into SceneNode for the scene builder. Attribute values travel as text,
// exactly as a scene file writes them, so that a scene assembled in Python goes through the same
// parsing and building as the same scene read from a file.
#include "bindings.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/component_table.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"
#include "fastcorot/sim/simulation.h"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

namespace fastcorot::python {

namespace {

py::tuple tree_of(const SceneNode& node) {
  py::list objects;
  for (const auto& object : node.objects) {
    objects.append(py::make_tuple(object.type, object.attributes, object.location.file.string(), object.location.line));
  }
  py::list children;
  for (const auto& child : node.children) children.append(tree_of(child));
  return py::make_tuple(node.name, node.attributes, objects, children, node.location.file.string(),
                        node.location.line);
}

std::map<std::string, std::string> text_attributes(py::handle value, const std::string& where) {
  try {
    return value.cast<std::map<std::string, std::string>>();
  } catch (const py::cast_error&) {
    throw py::type_error(where + ": attributes must be a dict of str to str");
  }
}

py::object component_spec(const std::string& type) {
  const ComponentSpec* spec = find_component(type);
  if (!spec) return py::none();
  py::list attributes;
  for (const auto& a : spec->attributes) {
    attributes.append(py::make_tuple(std::string(a.name), std::string(a.type), std::string(a.default_value),
                                     std::string(a.doc)));
  }
  py::list aliases;
  for (auto alias : spec->aliases) aliases.append(std::string(alias));
  py::dict out;
  out["name"] = std::string(spec->name);
  out["category"] = std::string(spec->category);
  out["doc"] = std::string(spec->doc);
  out["attributes"] = attributes;
  out["aliases"] = aliases;
  return out;
}

}  // namespace

SceneNode scene_node_from_tree(py::handle tree) {
  if (!py::isinstance<py::tuple>(tree) || py::len(tree) != 6) {
    throw py::type_error("scene tree: expected (name, attributes, objects, children, file, line)");
  }
  const auto items = py::reinterpret_borrow<py::tuple>(tree);
  SceneNode node;
  node.name = items[0].cast<std::string>();
  node.attributes = text_attributes(items[1], "node " + node.name);
  node.location = {items[4].cast<std::string>(), items[5].cast<int>()};
  for (py::handle entry : items[2]) {
    const auto object = entry.cast<py::tuple>();
    if (py::len(object) != 4) throw py::type_error("scene tree: expected objects as (type, attributes, file, line)");
    node.objects.push_back({object[0].cast<std::string>(),
                            text_attributes(object[1], object[0].cast<std::string>()),
                            {object[2].cast<std::string>(), object[3].cast<int>()}});
  }
  for (py::handle child : items[3]) node.children.push_back(scene_node_from_tree(child));
  return node;
}

void bind_scene(py::module_& m) {
  m.def("component_spec", &component_spec, py::arg("type"),
        "The table entry of a supported component (or alias): {name, category, doc, attributes: [(name, "
        "type, default, doc)], aliases}; None otherwise.");
  m.def("is_ignored_component", [](const std::string& type) { return is_ignored_component(type); });
  m.def(
      "add_data_repository", [](const std::filesystem::path& folder) { add_data_repository(folder); }, py::arg("folder"),
      "SOFA's AddDataRepository: files are also looked for in `folder`, after FASTCOROT_DATA_PATH, for the rest of the process.");
  m.def(
      "find_data_file", [](const std::filesystem::path& from, const std::string& name) { return find_data_file(from, name); },
      py::arg("from_file"), py::arg("name"),
      "Where a scene file `from_file` finds `name` (its folder, FASTCOROT_DATA_PATH, the data repositories, share/ above); "
      "ValueError listing where it looked when nowhere.");
  m.def("is_common_attribute", [](const std::string& name) { return is_common_attribute(name); });
  m.def("component_documentation", &component_documentation,
        "The supported SOFA components and their attributes, as Markdown (`fastcorot components`).");
  m.def(
      "check_object",
      [](const std::string& type, const std::vector<std::string>& names, const std::string& file, int line,
         bool strict) {
        SceneObject object{type, {}, {file, line}};
        for (const auto& name : names) object.attributes[name] = "";
        std::vector<std::string> warnings;
        const ComponentSpec* spec = check_scene_object(object, strict ? nullptr : &warnings);
        return py::make_tuple(spec ? py::object(py::str(std::string(spec->name))) : py::object(py::none()), warnings);
      },
      py::arg("type"), py::arg("attributes"), py::arg("file"), py::arg("line"), py::arg("strict") = true,
      "Checks a component type and attribute names as a scene file's are checked: (the supported component's "
      "name or None for an ignored component, the warnings); ValueError with the scene loader's message for an "
      "unknown component, or an unknown attribute when strict.");
  m.def(
      "parse_scene_file",
      [](const std::filesystem::path& path) {
        try {
          return tree_of(parse_scene_file(path));
        } catch (const Error& error) {
          if (!std::filesystem::exists(path)) throw_file_not_found(error.what());
          throw;
        }
      },
      py::arg("path"), "Parses a .scn file (includes expanded) into a scene tree.");
  m.def(
      "scene_data_value",
      [](py::handle tree, std::size_t object_index, const std::string& name) {
        const SceneNode root = scene_node_from_tree(tree);
        try {
          return scene_data_value(root, object_index, name);
        } catch (const Error& error) {
          throw py::value_error(error.what());
        }
      },
      py::arg("tree"), py::arg("object_index"), py::arg("name"),
      "The numbers of data `name` of the tree's object `object_index` (document order), as the scene builder "
      "reads them (links followed, loaders read, engines computed); ValueError naming what fails.");
  const Simulation<double> defaults;
  m.attr("DEFAULT_DT") = defaults.dt;
  m.attr("DEFAULT_GRAVITY") = py::make_tuple(defaults.gravity.x(), defaults.gravity.y(), defaults.gravity.z());
}

}  // namespace fastcorot::python
