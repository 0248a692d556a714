// What components compute when a scene reads their data (SceneData::compute): the loaders'
// meshes, grids and generated meshes, topological mappings, ROIs and engines, as SOFA's
// components fill their outputs.
#include "scene_data.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/sphere_reader.h"
#include "fastcorot/topology/cylinder_grid.h"
#include "fastcorot/topology/cylinder_mesh.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tetrahedron_faces.h"
#include "fastcorot/topology/tetrahedron_subdivision.h"

#include <algorithm>
#include <cmath>

namespace fastcorot::scene_detail {

namespace {

Numbers flatten(const std::vector<Vec3<double>>& points) {
  Numbers out;
  out.reserve(3 * points.size());
  for (const auto& p : points) out.insert(out.end(), {p.x(), p.y(), p.z()});
  return out;
}

template <std::size_t N>
Numbers flatten_indices(const std::vector<std::array<Index, N>>& tuples) {
  Numbers out;
  out.reserve(N * tuples.size());
  for (const auto& t : tuples) {
    for (Index i : t) out.push_back(static_cast<double>(i));
  }
  return out;
}

}  // namespace

Numbers SceneData::compute(Component& c, const std::string& name) {
  const std::string_view type = c.type();
  if (type == "TriangleSetTopologyContainer" && name == "triangles") {
    // Filled by a Tetra2TriangleTopologicalMapping that outputs to it: the boundary of its input.
    if (Component* m = mapping_into(c, "Tetra2TriangleTopologicalMapping")) {
      if (!m->has("input")) throw make_error(m->where(), ": no input given");
      if (boolean(*m, "noInitialTriangles", false)) return {};
      Component& input = resolve_object(*m->node, m->object->attributes.at("input"), *m);
      return flatten_indices(boundary_triangles(tetrahedra_of(input), boolean(*m, "flipNormals", false)));
    }
  }
  // src="@loader": same-named data come from the source unless written here.
  if (const auto src = c.object->attributes.find("src"); src != c.object->attributes.end() &&
                                                         (name == "position" || name == "tetrahedra" || name == "triangles")) {
    Component& source = resolve_object(*c.node, src->second, c);
    if (type == "MechanicalObject" && name != "position") return {};
    if (type == "TetrahedronSetTopologyContainer" && name == "triangles" && data(source, name).empty()) {
      return flatten_indices(tetrahedron_set_triangles(tetrahedra_of(c)));
    }
    if (type != "MechanicalObject") return data(source, name);
  }
  if (type == "RegularGridTopology" && name == "position") return flatten(grid_points<double>(grid(c)));
  if (type == "RegularGridTopology" && name == "n") return {2, 2, 2};
  if (type == "CylinderGridTopology" && name == "position") return flatten(cylinder_grid_points(cylinder_grid(c)));
  if (type == "CylinderGridTopology" && name == "n") return {2, 2, 2};
  if (type == "MeshGmshLoader" || type == "MeshVTKLoader" || type == "GIDMeshLoader") {
    const MeshData& mesh = mesh_file(c);
    if (name == "position") return flatten(mesh.points);
    if (name == "tetrahedra") return flatten_indices(mesh.tetrahedra);
    if (name == "triangles") return flatten_indices(mesh.triangles);
    return {};
  }
  if (type == "TetrahedronSetTopologyContainer") {
    // Filled by a Hexa2TetraTopologicalMapping that names this container as its output.
    if (Component* m = mapping_into(c, "Hexa2TetraTopologicalMapping")) {
      if (!m->has("input")) throw make_error(m->where(), ": no input given");
      Component& grid = resolve_object(*m->node, m->object->attributes.at("input"), *m);
      if (grid.type() != "RegularGridTopology") {
        throw make_error(m->where(), ": input must be a RegularGridTopology, not ", grid.type());
      }
      if (name == "position") return data(grid, "position");
      if (name == "tetrahedra") return flatten_indices(grid_tetrahedra(this->grid(grid), boolean(*m, "swapping", false)));
    }
    // Filled by a SimpleTesselatedTetraTopologicalMapping: its input cut into 8 per tetrahedron.
    if (Component* m = mapping_into(c, "SimpleTesselatedTetraTopologicalMapping")) {
      if (!m->has("input")) throw make_error(m->where(), ": no input given");
      Component& input = resolve_object(*m->node, m->object->attributes.at("input"), *m);
      const auto input_points = points(input, "position");
      try {
        const TetMesh mesh(static_cast<Index>(input_points.size()), tetrahedra_of(input));
        const Subdivision cut = subdivide_tetrahedra(mesh, input_points);
        if (name == "position") return flatten(cut.points);
        if (name == "tetrahedra") return flatten_indices(cut.tetrahedra);
      } catch (const Error& error) {
        throw make_error(m->where(), ": ", error.what());
      }
    }
    // SOFA creates the triangle array from the tetrahedra when it is asked for and has none.
    if (name == "triangles") return flatten_indices(tetrahedron_set_triangles(tetrahedra_of(c)));
    return {};
  }
  if (type == "MechanicalObject") {
    if (name == "position") {
      std::vector<Vec3<double>> base;
      if (auto given = written(c, "position")) {
        base = points_from(*given, c, "position");
      } else if (const auto src = c.object->attributes.find("src"); src != c.object->attributes.end()) {
        base = points_from(data(resolve_object(*c.node, src->second, c), "position"), c, "position");
      } else {
        Component* topology = nullptr;
        if (c.has("topology")) {
          topology = &resolve_object(*c.node, c.object->attributes.at("topology"), c);
        } else {
          const auto local = c.node->of_category("topology");
          if (!local.empty()) topology = local.front();
        }
        if (!topology) {
          // SOFA's MechanicalObject is one point at the origin until something sizes it.
          warn(c.where() + ": no position given and no topology in node " + c.node->path +
               " to take points from: one point at the origin, SOFA's default");
          return {0.0, 0.0, 0.0};
        }
        // A grid whose position links back to this state (SOFA scenes write that) gives its own points.
        base = topology->type() == "RegularGridTopology"    ? grid_points<double>(grid(*topology))
               : topology->type() == "CylinderGridTopology" ? cylinder_grid_points(cylinder_grid(*topology))
                                                            : points_from(data(*topology, "position"), *topology, "position");
      }
      return flatten(transformed(std::move(base), placement(c, "scale3d"), placement(c, "rotation"),
                                 placement(c, "translation")));
    }
    if (name == "rest_position") return data(c, "position");
    if (name == "velocity") return {};
    return {};
  }
  if (type == "SphereLoader" && (name == "position" || name == "sphere_centers" || name == "listRadius")) {
    const std::string file = text(c, "filename", "");
    if (file.empty()) throw make_error(c.where(), ": no filename given");
    SphereData spheres;
    try {
      spheres = read_sphere_file(find_data_file(c.object->location.file, file));
    } catch (const Error& error) {
      throw make_error(c.where(), ": ", error.what());
    }
    if (name == "listRadius") return Numbers(spheres.radii.begin(), spheres.radii.end());
    for (const auto& line : spheres.warnings) warn(c.where() + ": " + line);
    // SOFA's `scale` is the same Data as scale3d (an alias), three numbers or one.
    Vec3<double> scale = vec3(c, "scale3d", {1, 1, 1});
    if (c.has("scale")) {
      const Numbers& given = data(c, "scale");
      if (given.size() != 1 && given.size() != 3) throw make_error(c.where(), ": scale needs 1 or 3 numbers");
      scale = given.size() == 1 ? Vec3<double>::Constant(given[0]) : Vec3<double>(given[0], given[1], given[2]);
    }
    return flatten(transformed(std::move(spheres.centers), scale, vec3(c, "rotation", {0, 0, 0}), vec3(c, "translation", {0, 0, 0})));
  }
  if (type == "GenerateCylinder") {
    if (whole_number(c, "BezierTetrahedronDegree", 0) > 1 || whole_number(c, "BezierTriangleDegree", 0) > 1) {
      throw make_error(c.where(), ": Bezier tetrahedra and triangles are not generated (linear tetrahedra only)");
    }
    const CylinderMesh mesh = generate_cylinder(real(c, "radius", 0.2), real(c, "height", 1), vec3(c, "origin", {0, 0, 0}),
                                                whole_number(c, "resCircumferential", 6), whole_number(c, "resRadial", 3),
                                                whole_number(c, "resHeight", 5));
    if (name == "output_TetrahedraPosition" || name == "output_position" || name == "position") return flatten(mesh.points);
    if (name == "tetrahedra") return flatten_indices(mesh.tetrahedra);
    return {};
  }
  if (type == "BoxROI" || type == "PlaneROI" || type == "PairBoxROI") return region_of_interest(c, name);
  return {};
}

}  // namespace fastcorot::scene_detail
