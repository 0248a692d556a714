// What components compute when a scene reads their data (SceneData::compute): the loaders'
// meshes, grids and generated meshes, topological mappings, ROIs and engines, as SOFA's
// components fill their outputs.
#include "scene_data.h"
#include "engine_data.h"

#include "hexahedron_builders.h"
#include "index_tuples.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/mesh_readers.h"
#include "fastcorot/io/sphere_reader.h"
#include "fastcorot/io/surface_readers.h"
#include "fastcorot/topology/cylinder_grid.h"
#include "fastcorot/topology/cylinder_mesh.h"
#include "fastcorot/topology/generate_grid.h"
#include "fastcorot/topology/hexahedron_faces.h"
#include "fastcorot/topology/mesh2point_mapping.h"
#include "fastcorot/topology/sphere_grid.h"
#include "fastcorot/topology/string_mesh_creator.h"
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

bool is_set_container(std::string_view type) {
  return type == "PointSetTopologyContainer" || type == "QuadSetTopologyContainer" ||
         type == "HexahedronSetTopologyContainer" || type == "TetrahedronSetTopologyContainer" ||
         type == "TriangleSetTopologyContainer";
}

SphereGrid sphere_grid(SceneData& data, Component& c) {
  SphereGrid sphere;
  sphere.n = data.grid(c).n;
  sphere.center = data.vec3(c, "center", {0, 0, 0});
  sphere.axis = data.vec3(c, "axis", {0, 0, 1});
  sphere.radius = data.real(c, "radius", 1);
  return sphere;
}

std::vector<Vec3<double>> sphere_grid_points_of(SceneData& data, Component& c) {
  try {
    return sphere_grid_points(sphere_grid(data, c));
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

template <class T>
T checked(Component& c, const std::function<T()>& make) {
  try {
    return make();
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

// Mesh2PointTopologicalMapping m's data `name` for its output container: the points placed on
// its input's elements, or the input's elements copied onto the points made from their ends.
Numbers mesh2point(SceneData& data, Component& m, const std::string& name) {
  if (!m.has("input")) throw make_error(m.where(), ": no input given");
  Component& input = data.resolve_object(*m.node, m.object->attributes.at("input"), m);
  const auto coords = [&](const char* attribute) { return data.points(m, attribute); };
  Mesh2PointCoords at{coords("pointBaryCoords"), coords("edgeBaryCoords"), coords("triangleBaryCoords"),
                      coords("quadBaryCoords"),  coords("tetraBaryCoords"), coords("hexaBaryCoords")};
  const std::size_t per_point = at.point.size();
  for (const char* copy : {"copyEdges", "copyTriangles", "copyTetrahedra"}) {
    if (data.boolean(m, copy, false) && per_point == 0) {
      throw make_error(m.where(), ": ", copy, " needs at least one offset in pointBaryCoords");
    }
  }
  const auto input_points = data.points(input, "position");
  const std::vector<Tetrahedron> tetrahedra = data.tetrahedra_of(input);
  std::vector<Hexahedron> hexahedra = topology_hexahedra(data, input);
  // The input's edges: given, else those its container creates from its elements.
  const auto edges = [&] {
    const std::vector<Index> flat = data.indices(input, "edges");
    if (flat.size() % 2 != 0) throw make_error(input.where(), ": edges needs 2 indices per edge");
    std::vector<Edge> out(flat.size() / 2);
    for (std::size_t e = 0; e < out.size(); ++e) out[e] = {flat[2 * e], flat[2 * e + 1]};
    if (!out.empty()) return out;
    if (!tetrahedra.empty()) {
      const TetMesh mesh = checked<TetMesh>(input, [&] { return TetMesh(static_cast<Index>(input_points.size()), tetrahedra); });
      return std::vector<Edge>(mesh.edges().begin(), mesh.edges().end());
    }
    if (!hexahedra.empty()) return hexahedron_set_edges(hexahedra);
    if (!data.indices(input, "triangles").empty() || !data.indices(input, "quads").empty()) {
      throw make_error(m.where(), ": edgeBaryCoords or copyEdges on ", input.where(),
                       ", which has no edges given: the edges SOFA creates from triangles or quads are not made");
    }
    return out;
  };
  const bool need_edges = !at.edge.empty() || data.boolean(m, "copyEdges", false);
  const std::vector<Edge> edge_list = need_edges ? edges() : std::vector<Edge>{};
  const std::vector<Triangle> triangles =
      !at.triangle.empty() || data.boolean(m, "copyTriangles", false) ? index_tuples<3>(data, input, "triangles") : std::vector<Triangle>{};
  const std::vector<std::array<Index, 4>> quads =
      at.quad.empty() ? std::vector<std::array<Index, 4>>{} : index_tuples<4>(data, input, "quads");
  if (name == "position") {
    return flatten(checked<std::vector<Vec3<double>>>(m, [&] {
      return mesh2point_points({input_points, edge_list, triangles, quads, tetrahedra, hexahedra}, at);
    }));
  }
  // copyEdges, copyTriangles, copyTetrahedra: vertex v becomes the first point made from it.
  const auto copied = [&]<class Tuples>(const char* flag, const Tuples& elements) {
    Numbers out;
    if (!data.boolean(m, flag, false)) return out;
    for (const auto& element : elements) {
      for (Index v : element) {
        if (v < 0 || static_cast<std::size_t>(v) >= input_points.size()) {
          throw make_error(m.where(), ": ", flag, ": the input names point ", v, ", outside its ", input_points.size(), " points");
        }
        out.push_back(static_cast<double>(static_cast<std::size_t>(v) * per_point));
      }
    }
    return out;
  };
  if (name == "edges") return copied("copyEdges", edge_list);
  if (name == "triangles") return copied("copyTriangles", triangles);
  if (name == "tetrahedra") return copied("copyTetrahedra", tetrahedra);
  return {};
}

}  // namespace

// SOFA's NearestPointROI::computeNearestPointMaps.
Numbers SceneData::nearest_point_roi(Component& c, const std::string& name) {
  const double radius = real(c, "radius", 1);
  if (!(radius > 0)) throw make_error(c.where(), ": radius = ", radius, ": must be > 0");
  const std::string which = boolean(c, "useRestPosition", true) ? "rest_position" : "position";
  const auto points_of = [&](const char* link) {
    if (!c.has(link)) throw make_error(c.where(), ": ", link, " is not given");
    Component& state = resolve_state(*c.node, c.object->attributes.at(link), c);
    std::vector<Vec3<double>> x = points(state, which);
    if (x.empty()) x = points(state, "position");
    return x;
  };
  const auto x1 = points_of("object1");
  const auto x2 = points_of("object2");
  const auto filter = [&](const char* attribute, std::size_t size) {
    std::vector<Index> list = c.has(attribute) ? indices(c, attribute) : std::vector<Index>{};
    if (list.empty()) {
      for (std::size_t i = 0; i < size; ++i) list.push_back(static_cast<Index>(i));
    }
    for (Index i : list) {
      if (i < 0 || static_cast<std::size_t>(i) >= size) throw make_error(c.where(), ": ", attribute, ": index ", i, " out of range [0, ", size, ")");
    }
    return list;
  };
  const auto candidates = filter("inputIndices1", x1.size());
  const auto wanted = filter("inputIndices2", x2.size());
  Numbers indices1, indices2, edges, pairs, distances;
  if (!x1.empty() && !x2.empty()) {
    for (Index i2 : wanted) {
      const Vec3<double>& p2 = x2[static_cast<std::size_t>(i2)];
      Index best = candidates.front();
      double best_distance = (x1[static_cast<std::size_t>(best)] - p2).squaredNorm();
      for (Index i1 : candidates) {
        const double d = (x1[static_cast<std::size_t>(i1)] - p2).squaredNorm();
        if (d < best_distance) best = i1, best_distance = d;
      }
      if (!(best_distance < radius * radius)) continue;
      indices1.push_back(best);
      indices2.push_back(i2);
      edges.insert(edges.end(), {2.0 * i2, 2.0 * i2 + 1});
      pairs.insert(pairs.end(), {0.0, static_cast<double>(best), 1.0, static_cast<double>(i2)});
      distances.push_back(std::sqrt(best_distance));
    }
  }
  if (name == "indices1") return indices1;
  if (name == "indices2") return indices2;
  if (name == "edges") return edges;
  if (name == "indexPairs") return pairs;
  if (name == "distances") return distances;
  return {};
}

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
  if (type == "QuadSetTopologyContainer" && name == "quads") {
    // Filled by a Hexa2QuadTopologicalMapping: the quads of its input bounding one hexahedron.
    if (Component* m = mapping_into(c, "Hexa2QuadTopologicalMapping")) {
      if (!m->has("input")) throw make_error(m->where(), ": no input given");
      Component& input = resolve_object(*m->node, m->object->attributes.at("input"), *m);
      const auto hexahedra = topology_hexahedra(*this, input);
      const auto quads = is_grid_topology(input.type()) ? grid_quads(grid(input)) : hexahedron_set_quads(hexahedra);
      return flatten_indices(boundary_quads(quads, hexahedra, boolean(*m, "flipNormals", false)));
    }
  }
  // SOFA's other names of the containers' data.
  if (type == "TetrahedronSetTopologyContainer") {
    if (name == "points") return data(c, "position");
    if (name == "tetras") return data(c, "tetrahedra");
    if (name == "tetrahedra" && c.has("tetras")) return data(c, "tetras");
  }
  // A mesh file read by the container itself (SOFA's fileTopology, alias filename: MeshTopology's
  // filename="mesh/liver-smooth.obj"): a surface (.obj, .stl) gives points, triangles and quads, a
  // volume mesh points, tetrahedra and triangles.
  if (type == "TetrahedronSetTopologyContainer" && (c.has("filename") || c.has("fileTopology")) &&
      (name == "position" || name == "tetrahedra" || name == "triangles" || name == "quads")) {
    const std::string file = text(c, c.has("filename") ? "filename" : "fileTopology", "");
    if (!file.empty()) {
      try {
        const auto path = find_data_file(c.object->location.file, file);
        const std::string extension = path.extension().string();
        if (extension == ".obj" || extension == ".OBJ" || extension == ".stl" || extension == ".STL") {
          const SurfaceData surface = read_surface_file(path);
          if (name == "position") return flatten(surface.points);
          if (name == "triangles") return flatten_indices(surface.triangles);
          if (name == "quads") return flatten_indices(surface.quads);
          return {};
        }
        const MeshData mesh = read_mesh_file(path);
        if (name == "position") return flatten(mesh.points);
        if (name == "tetrahedra") return flatten_indices(mesh.tetrahedra);
        if (name == "triangles") return flatten_indices(mesh.triangles);
        return {};
      } catch (const Error& error) {
        throw error_at(c.where(), error);
      }
    }
  }
  if (is_set_container(type) && name == "position" && c.has("points")) return data(c, "points");
  if (type == "HexahedronSetTopologyContainer" && name == "hexahedra" && c.has("hexas")) return data(c, "hexas");
  // src="@loader": same-named data come from the source unless written here.
  const bool from_source = name == "position" || name == "tetrahedra" || name == "triangles" ||
                           (is_set_container(type) && (name == "edges" || name == "quads" || name == "hexahedra"));
  if (const auto src = c.object->attributes.find("src"); src != c.object->attributes.end() && from_source) {
    Component& source = resolve_object(*c.node, src->second, c);
    if (type == "HexahedronSetTopologyContainer" && name == "quads" && data(source, name).empty()) {
      return flatten_indices(hexahedron_set_quads(topology_hexahedra(*this, c)));
    }
    if (type == "MechanicalObject" && name != "position") return {};
    if (type == "TetrahedronSetTopologyContainer" && name == "triangles" && data(source, name).empty()) {
      return flatten_indices(tetrahedron_set_triangles(tetrahedra_of(c)));
    }
    if (type != "MechanicalObject") return data(source, name);
  }
  if (type == "RegularGridTopology" && name == "position") return flatten(grid_points<double>(grid(c)));
  if (type == "RegularGridTopology" && name == "n") return {2, 2, 2};
  if (type == "RegularGridTopology" && name == "hexahedra") {
    // SOFA's grid gives its cells as hexahedra (a HexahedronSetTopologyContainer with src="@grid").
    return flatten_indices(topology_hexahedra(*this, c));
  }
  if (type == "CylinderGridTopology" && name == "position") return flatten(cylinder_grid_points(cylinder_grid(c)));
  if (type == "CylinderGridTopology" && name == "n") return {2, 2, 2};
  if (type == "SphereGridTopology" && name == "position") return flatten(sphere_grid_points_of(*this, c));
  if (type == "SphereGridTopology" && name == "n") return {2, 2, 2};
  if (type == "HexahedronSetTopologyContainer") {
    // SOFA creates the quad array from the hexahedra when it is asked for and has none.
    if (name == "quads") return flatten_indices(hexahedron_set_quads(topology_hexahedra(*this, c)));
    return {};
  }
  if (type == "PointSetTopologyContainer") {
    if (Component* m = mapping_into(c, "Mesh2PointTopologicalMapping")) return mesh2point(*this, *m, name);
    return {};
  }
  if (type == "GenerateGrid") {
    const Numbers& resolution = data(c, "resolution");
    if (resolution.size() != 3) throw make_error(c.where(), ": resolution needs 3 integers, got ", resolution.size());
    std::array<long long, 3> cells{};
    for (std::size_t a = 0; a < 3; ++a) {
      if (resolution[a] != std::floor(resolution[a]) || std::abs(resolution[a]) > 1e9) {
        throw make_error(c.where(), ": resolution = ", resolution[a], ": expected whole numbers");
      }
      cells[a] = static_cast<long long>(resolution[a]);
    }
    const GeneratedGrid grid = checked<GeneratedGrid>(c, [&] {
      return generate_grid(vec3(c, "min", {0, 0, 0}), vec3(c, "max", {0, 0, 0}), cells);
    });
    if (name == "output_position" || name == "position") return flatten(grid.points);
    if (name == "hexahedra") return flatten_indices(grid.hexahedra);
    if (name == "tetrahedra") return flatten_indices(grid.tetrahedra);
    if (name == "quads") return flatten_indices(grid.quads);
    if (name == "triangles") return flatten_indices(grid.triangles);
    if (name == "resolution") return {3, 3, 3};
    return {};
  }
  if (type == "StringMeshCreator") {
    const StringMesh mesh = checked<StringMesh>(c, [&] { return string_mesh(whole_number(c, "resolution", 2)); });
    if (name == "position") {
      return flatten(transformed(mesh.points, vec3(c, "scale3d", {1, 1, 1}), vec3(c, "rotation", {0, 0, 0}),
                                 vec3(c, "translation", {0, 0, 0})));
    }
    if (name == "edges") return flatten_indices(mesh.edges);
    return {};
  }
  // A surface loader read by a state or a topology (src="@loader": a static obstacle's points, a
  // collision surface): the file's points placed as the loader places them, its triangles and quads.
  if ((type == "MeshOBJLoader" || type == "MeshSTLLoader") && (name == "position" || name == "triangles" || name == "quads")) {
    const std::string file = text(c, "filename", "");
    if (file.empty()) throw make_error(c.where(), ": no filename given");
    SurfaceData surface;
    try {
      surface = read_surface_file(find_data_file(c.object->location.file, file));
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
    // triangulate (MeshOBJLoader): each quad as (a, b, c) and (a, c, d), as SOFA splits it; SOFA keeps
    // the file's face order, here a mixed file's triangles come before its split quads.
    const bool triangulate = type == "MeshOBJLoader" && boolean(c, "triangulate", false);
    if (name == "triangles") return flatten_indices(triangulate ? surface.all_triangles() : surface.triangles);
    if (name == "quads") return triangulate ? Numbers{} : flatten_indices(surface.quads);
    Vec3<double> scale = vec3(c, "scale3d", {1, 1, 1});
    if (c.has("scale")) scale *= real(c, "scale", 1);
    return flatten(transformed(surface.points, scale, vec3(c, "rotation", {0, 0, 0}), vec3(c, "translation", {0, 0, 0})));
  }
  if (type == "MeshGmshLoader" || type == "MeshVTKLoader" || type == "GIDMeshLoader") {
    const MeshData& mesh = mesh_file(c);
    if (name == "position") return flatten(mesh.points);
    if (name == "tetrahedra" || name == "tetras") return flatten_indices(mesh.tetrahedra);  // tetras: SOFA's other name
    if (name == "triangles") return flatten_indices(mesh.triangles);
    return {};
  }
  if (type == "TetrahedronSetTopologyContainer") {
    // Filled by a Hexa2TetraTopologicalMapping that names this container as its output.
    if (Component* m = mapping_into(c, "Hexa2TetraTopologicalMapping")) {
      if (!m->has("input")) throw make_error(m->where(), ": no input given");
      Component& grid = resolve_object(*m->node, m->object->attributes.at("input"), *m);
      if (grid.type() == "HexahedronSetTopologyContainer") {
        // Not a grid: SOFA takes its hexahedra as cells of a 2 x 1 layer for the swapping parities.
        if (name == "position") return data(grid, "position");
        if (name == "tetrahedra") {
          return flatten_indices(split_hexahedra(topology_hexahedra(*this, grid), 2, 1, boolean(*m, "swapping", false), true));
        }
        return {};
      }
      if (grid.type() != "RegularGridTopology") {
        throw make_error(m->where(), ": input must be a RegularGridTopology or a HexahedronSetTopologyContainer, not ", grid.type());
      }
      if (name == "position") return data(grid, "position");
      if (name == "tetrahedra") {
        try {
          return flatten_indices(grid_tetrahedra(this->grid(grid), boolean(*m, "swapping", false)));
        } catch (const Error& error) {
          throw error_at(m->where(), error);
        }
      }
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
        throw error_at(m->where(), error);
      }
    }
    // SOFA creates the triangle array from the tetrahedra when it is asked for and has none.
    if (name == "triangles") return flatten_indices(tetrahedron_set_triangles(tetrahedra_of(c)));
    return {};
  }
  if (type == "MechanicalObject" && (name == "position" || name == "rest_position") &&
      (c.has("translation2") || c.has("rotation2") || c.has("dx2") || c.has("dy2") || c.has("dz2") || c.has("rx2") ||
       c.has("ry2") || c.has("rz2"))) {
    // SOFA's MechanicalObject::init: translation2 and rotation2 move the positions after the rest
    // positions were taken from them (rotation2 first; on Rigid3 states it turns the orientations too).
    const Numbers first = compute(c, "placed_position");
    if (name == "rest_position") return first;
    const Vec3<double> rotation = placement(c, "rotation2"), translation = placement(c, "translation2");
    Numbers values = first;
    const bool rigid = is_rigid_template(text(c, "template", "Vec3d"));
    const std::size_t width = rigid ? 7 : 3;
    const Eigen::Quaterniond turn(euler_rotation(rotation));
    for (std::size_t k = 0; k + width <= values.size(); k += width) {
      const Vec3<double> moved =
          transformed({Vec3<double>(values[k], values[k + 1], values[k + 2])}, Vec3<double>::Ones(), rotation, translation).front();
      for (int j = 0; j < 3; ++j) values[k + j] = moved[j];
      if (rigid && rotation != Vec3<double>::Zero()) {
        const Eigen::Quaterniond q = turn * Eigen::Quaterniond(values[k + 6], values[k + 3], values[k + 4], values[k + 5]);
        values[k + 3] = q.x(), values[k + 4] = q.y(), values[k + 5] = q.z(), values[k + 6] = q.w();
      }
    }
    return values;
  }
  if (type == "MechanicalObject") {
    // "placed_position": the positions before translation2 and rotation2 (above).
    const bool position = name == "position" || name == "placed_position";
    if (position && is_rigid_template(text(c, "template", "Vec3d"))) {
      // A Rigid3 state: 7 numbers per rigid (x y z qx qy qz qw), one rigid at the origin by default
      // (SOFA's size-one state); the placement moves the centres, and a rotation also turns the
      // orientations (SOFA's MechanicalObject<Rigid3>::applyRotation).
      Numbers values = {0, 0, 0, 0, 0, 0, 1};
      if (auto given = written(c, "position")) values = std::move(*given);
      else if (c.has("src")) values = data(resolve_object(*c.node, c.object->attributes.at("src"), c), "position");
      if (values.size() % 7 != 0) {
        throw make_error(c.where(), ": position of a ", text(c, "template", ""), " state has ", values.size(),
                         " numbers: expected 7 per rigid (x y z qx qy qz qw)");
      }
      const Vec3<double> rotation = placement(c, "rotation");
      const Eigen::Quaterniond turn(euler_rotation(rotation));
      for (std::size_t k = 0; k < values.size(); k += 7) {
        const Vec3<double> center = transformed({Vec3<double>(values[k], values[k + 1], values[k + 2])}, placement(c, "scale3d"),
                                                rotation, placement(c, "translation"))
                                        .front();
        for (int j = 0; j < 3; ++j) values[k + j] = center[j];
        if (rotation != Vec3<double>::Zero()) {
          const Eigen::Quaterniond q = turn * Eigen::Quaterniond(values[k + 6], values[k + 3], values[k + 4], values[k + 5]);
          values[k + 3] = q.x(), values[k + 4] = q.y(), values[k + 5] = q.z(), values[k + 6] = q.w();
        }
      }
      return values;
    }
    if (position) {
      const std::string tmpl = text(c, "template", "Vec3d");
      if (tmpl == "Vec1" || tmpl == "Vec1d" || tmpl == "Vec1f") {
        throw make_error(c.where(), ": the positions of a Vec1 state are asked for: Vec1 states are supported only as the output of a ",
                         "DistanceMapping (with Lagrangian constraints on them), not with their own mechanics or positions");
      }
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
          // A TriangleSetTopologyContainer with points gives them too (SOFA's MechanicalObject takes the
          // context topology's points).
          for (Component* triangles : c.node->of_category("trianglecontainer")) {
            if (!topology && (triangles->has("position") || triangles->has("src"))) topology = triangles;
          }
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
               : topology->type() == "SphereGridTopology"   ? sphere_grid_points_of(*this, *topology)
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
      throw error_at(c.where(), error);
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
  if (type == "BoxROI" || type == "SphereROI" || type == "PlaneROI" || type == "PairBoxROI") return region_of_interest(c, name);
  if (type == "SubsetTopology") return subset_topology(*this, c, name);
  if (type == "NearestPointROI") return nearest_point_roi(c, name);
  if (type == "IndexValueMapper" && name == "outputValues") {
    // SOFA's IndexValueMapper::doUpdate.
    Numbers out = c.has("inputValues") ? data(c, "inputValues") : Numbers{};
    const double value = real(c, "value", 0);
    const double fallback = real(c, "defaultValue", 1);
    for (Index i : c.has("indices") ? indices(c, "indices") : std::vector<Index>{}) {
      const auto at = static_cast<std::size_t>(i);
      if (at >= out.size()) out.resize(at + 1, fallback);
      out[at] = value;
    }
    return out;
  }
  if ((type == "VolumeFromVolumetricElements" || type == "VolumeFromTetrahedrons" || type == "VolumeFromTriangles") && name == "volume") {
    return {engine_volume(c)};
  }
  if (type == "MeshTetraStuffing") return mesh_tetra_stuffing(*this, c, name);
  if (type == "MeshSplittingEngine") return mesh_splitting_engine(*this, c, name);
  if (type == "TransformEngine") return transform_engine(*this, c, name);
  if (type == "PointsFromIndices") return points_from_indices(*this, c, name);
  return {};
}

}  // namespace fastcorot::scene_detail
