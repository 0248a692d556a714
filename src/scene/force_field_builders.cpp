#include "force_field_builders.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/penalty_force_fields.h"
#include "fastcorot/fem/spring_force_field.h"

namespace fastcorot::scene_detail {

namespace {

// A per-kind stiffness or damping of MeshSpringForceField: `name`, else its older alias (tetrasStiffness),
// else `stiffness` / `damping`, which SOFA declares as an alias of every kind's (so that it sets them all).
double per_kind(SceneData& data, Component& c, const std::string& name, const char* alias, const char* common) {
  if (c.has(name)) return data.real(c, name, 0);
  if (alias && c.has(alias)) return data.real(c, alias, 0);
  return data.real(c, common, 0);
}

MeshSpringParameters<double> mesh_spring_parameters(SceneData& data, Component& c) {
  MeshSpringParameters<double> p;
  p.lines_stiffness = per_kind(data, c, "linesStiffness", nullptr, "stiffness");
  p.lines_damping = per_kind(data, c, "linesDamping", nullptr, "damping");
  p.triangles_stiffness = per_kind(data, c, "trianglesStiffness", nullptr, "stiffness");
  p.triangles_damping = per_kind(data, c, "trianglesDamping", nullptr, "damping");
  p.quads_stiffness = per_kind(data, c, "quadsStiffness", nullptr, "stiffness");
  p.quads_damping = per_kind(data, c, "quadsDamping", nullptr, "damping");
  p.tetrahedra_stiffness = per_kind(data, c, "tetrahedraStiffness", "tetrasStiffness", "stiffness");
  p.tetrahedra_damping = per_kind(data, c, "tetrahedraDamping", "tetrasDamping", "damping");
  p.cubes_stiffness = per_kind(data, c, "cubesStiffness", nullptr, "stiffness");
  p.cubes_damping = per_kind(data, c, "cubesDamping", nullptr, "damping");
  p.no_compression = data.boolean(c, "noCompression", false);
  return p;
}

}  // namespace

bool makes_mesh_springs(SceneData& data, Component& c) {
  const auto p = mesh_spring_parameters(data, c);
  for (double value : {p.lines_stiffness, p.lines_damping, p.triangles_stiffness, p.triangles_damping, p.quads_stiffness,
                       p.quads_damping, p.tetrahedra_stiffness, p.tetrahedra_damping, p.cubes_stiffness, p.cubes_damping}) {
    if (value != 0) return true;
  }
  return false;
}

std::shared_ptr<ForceField<double>> build_mesh_springs(SceneData& data, Component& c, std::shared_ptr<const TetMesh> mesh,
                                                       std::span<const Vec3<double>> rest) {
  try {
    if (c.has("localRange")) throw make_error("localRange is not supported (every spring is kept)");
    auto springs = mesh_springs<double>(*mesh, rest, mesh_spring_parameters(data, c));
    return std::make_shared<SpringForceField<double>>(std::move(mesh), std::move(springs),
                                                      data.real(c, "rayleighStiffness", 0), "MeshSpringForceField");
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

std::shared_ptr<ForceField<double>> build_mesh_springs(SceneData& data, Component& c, SpringTopology topology,
                                                       std::span<const Vec3<double>> rest) {
  try {
    if (c.has("localRange")) throw make_error("localRange is not supported (every spring is kept)");
    auto springs = mesh_springs<double>(topology, rest, mesh_spring_parameters(data, c));
    auto points = std::make_shared<TetMesh>(static_cast<Index>(rest.size()), std::vector<Tetrahedron>{});
    return std::make_shared<SpringForceField<double>>(std::move(points), std::move(springs),
                                                      data.real(c, "rayleighStiffness", 0), "MeshSpringForceField");
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

bool is_penalty_force_field(std::string_view type) { return type == "PlaneForceField" || type == "ConicalForceField"; }

std::shared_ptr<ForceField<double>> build_penalty_force_field(SceneData& data, Component& c, std::shared_ptr<const TetMesh> mesh) {
  try {
    if (c.type() == "PlaneForceField") {
      PlaneForceField<double>::Parameters p;
      p.normal = data.vec3(c, "normal", {0, 1, 0});
      p.d = data.real(c, "d", 0);
      p.stiffness = data.real(c, "stiffness", 500);
      p.damping = data.real(c, "damping", 5);
      p.max_force = data.real(c, "maxForce", 0);
      p.bilateral = data.boolean(c, "bilateral", false);
      p.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0);
      if (c.has("localRange")) throw make_error("localRange is not supported (every point is tested)");
      return std::make_shared<PlaneForceField<double>>(std::move(mesh), p);
    }
    ConicalForceField<double>::Parameters p;
    p.center = data.vec3(c, "coneCenter", {0, 0, 0});
    p.height = data.vec3(c, "coneHeight", {0, 0, 0});
    p.angle = data.real(c, "coneAngle", 10);
    p.stiffness = data.real(c, "stiffness", 500);
    p.damping = data.real(c, "damping", 5);
    p.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0);
    return std::make_shared<ConicalForceField<double>>(std::move(mesh), p);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

ConstantForce<double> build_triangle_pressure(SceneData& data, Component& c, std::span<const Vec3<double>> rest) {
  try {
    if (!data.boolean(c, "useConstantForce", true)) {
      throw make_error("useConstantForce=\"false\" (the Cauchy stress form) is not supported");
    }
    Component* topology = c.has("topology") ? &data.resolve_object(*c.node, c.object->attributes.at("topology"), c)
                                            : data.triangle_container_of(*c.node);
    if (!topology) topology = data.topology_of(*c.node);
    if (!topology) throw make_error("no topology with triangles in its node or above");
    const std::vector<Index> triangles = data.indices(*topology, "triangles");
    const Vec3<double> pressure = data.vec3(c, "pressure", {0, 0, 0});
    ConstantForce<double> load;
    const auto count = static_cast<Index>(triangles.size() / 3);
    for (Index t : data.indices(c, "triangleList")) {
      if (t < 0 || t >= count) throw make_error("triangleList: triangle ", t, " out of range [0, ", count, ") of ", topology->where());
      const auto at = static_cast<std::size_t>(3 * t);
      for (std::size_t k = 0; k < 3; ++k) {
        if (triangles[at + k] < 0 || static_cast<std::size_t>(triangles[at + k]) >= rest.size()) {
          throw make_error("triangle ", t, " has point ", triangles[at + k], " outside the object's ", rest.size(), " points");
        }
      }
      const Vec3<double>& a = rest[static_cast<std::size_t>(triangles[at])];
      const Vec3<double>& b = rest[static_cast<std::size_t>(triangles[at + 1])];
      const Vec3<double>& d = rest[static_cast<std::size_t>(triangles[at + 2])];
      const double area = (b - a).cross(d - a).norm() / 2;
      const Vec3<double> force = pressure * area / 3;
      for (std::size_t k = 0; k < 3; ++k) {
        load.indices.push_back(triangles[at + k]);
        load.forces.push_back(force);
      }
    }
    return load;
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

ConstantForce<double> build_quad_pressure(SceneData& data, Component& c, std::span<const Vec3<double>> rest) {
  try {
    if (data.real(c, "dmin", 0) != data.real(c, "dmax", 0)) {
      throw make_error("dmin != dmax: the selection of quads along a plane is not supported (use quadList)");
    }
    const std::vector<Index> list = data.indices(c, "quadList");
    ConstantForce<double> load;
    if (list.empty()) return load;
    Component* topology = data.topology_of(c);
    if (!topology) throw make_error("no topology with quads in its node or above");
    const std::vector<Index> quads = data.indices(*topology, "quads");
    const Vec3<double> pressure = data.vec3(c, "pressure", {0, 0, 0});
    const auto count = static_cast<Index>(quads.size() / 4);
    for (Index q : list) {
      if (q < 0 || q >= count) throw make_error("quadList: quad ", q, " out of range [0, ", count, ") of ", topology->where());
      const auto at = static_cast<std::size_t>(4 * q);
      for (std::size_t k = 0; k < 4; ++k) {
        if (static_cast<std::size_t>(quads[at + k]) >= rest.size()) {
          throw make_error("quad ", q, " has point ", quads[at + k], " outside the object's ", rest.size(), " points");
        }
      }
      const auto p = [&](std::size_t k) -> const Vec3<double>& { return rest[static_cast<std::size_t>(quads[at + k])]; };
      const double area = (p(1) - p(0)).cross(p(2) - p(0)).norm() / 2 + (p(2) - p(0)).cross(p(3) - p(0)).norm() / 2;
      const Vec3<double> force = pressure * area / 4;
      for (std::size_t k = 0; k < 4; ++k) {
        load.indices.push_back(quads[at + k]);
        load.forces.push_back(force);
      }
    }
    return load;
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

std::vector<Index> constant_force_indices(SceneData& data, Component& c, Index size) {
  std::vector<Index> indices = data.indices(c, "indices");
  if (indices.empty()) {
    for (Index i = 0; i < size; ++i) indices.push_back(i);
  }
  if (data.boolean(c, "indexFromEnd", false)) {
    for (Index& i : indices) i = size - 1 - i;
  }
  for (Index i : indices) {
    if (i < 0 || i >= size) throw make_error(c.where(), ": index ", i, " out of range [0, ", size, ")");
  }
  return indices;
}

ConstantForce<double> build_constant_force(SceneData& data, std::vector<std::string>& info, Component& c, Index size) {
  ConstantForce<double> constant;
  constant.indices = constant_force_indices(data, c, size);
  const auto count = constant.indices.size();
  if (c.has("forces")) {
    constant.forces = data.points(c, "forces");
    // One force for several points: every point gets it (SOFA's computeForceFromSingleForce).
    if (constant.forces.size() == 1) constant.forces.assign(count, constant.forces.front());
    if (constant.forces.size() != count) {
      throw make_error(c.where(), ": forces has ", constant.forces.size(), " entries for ", count, " indices");
    }
  } else if (c.has("force")) {
    constant.forces.assign(count, data.vec3(c, "force", {0, 0, 0}));
  } else if (c.has("totalForce")) {
    constant.forces.assign(count, data.vec3(c, "totalForce", {0, 0, 0}) / static_cast<double>(count));
  } else {
    info.push_back(c.where() + ": no forces, force or totalForce given: no load");
    constant.forces.assign(count, Vec3<double>::Zero());
  }
  return constant;
}

}  // namespace fastcorot::scene_detail
