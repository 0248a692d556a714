#include "rigid_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/rest_shape_springs_force_field.h"
#include "fastcorot/mapping/mapped_force_field.h"
#include "fastcorot/mapping/rigid_points.h"
#include "fastcorot/state/rigid_mass.h"
#include "force_field_builders.h"
#include "projective_constraints.h"
#include "spring_builders.h"

#include <array>
#include <memory>

namespace fastcorot::scene_detail {

namespace {

// UniformMass on rigids (SOFA's UniformMass<Rigid3>): every rigid gets the same RigidMass.
RigidMass<double> uniform_mass(SceneData& data, Component& c, Index rigids) {
  UniformRigidMassInput<double> input;
  if (c.has("vertexMass")) input.vertex_mass = parse_rigid_mass<double>(data.data(c, "vertexMass"), c.where() + ": vertexMass");
  if (c.has("totalMass")) input.total_mass = data.real(c, "totalMass", 0);
  if (c.has("filename")) {
    const std::string name = data.text(c, "filename", "");
    try {
      input.file = read_rigid_file(find_data_file(c.object->location.file, name).string());
    } catch (const Error& error) {
      throw make_error(c.where(), ": filename: ", error.what());
    }
  }
  return uniform_rigid_mass(input, rigids, c.where());
}

// The rigids a FixedProjectiveConstraint holds (SOFA's default: rigid 0).
std::vector<Index> fixed_rigids(SceneData& data, Component& c, Index rigids) {
  std::vector<Index> indices;
  if (data.boolean(c, "fixAll", false)) {
    for (Index k = 0; k < rigids; ++k) indices.push_back(k);
  } else {
    indices = c.has("indices") ? data.indices(c, "indices") : std::vector<Index>{0};
  }
  for (Index k : indices) {
    if (k < 0 || k >= rigids) throw make_error(c.where(), ": index ", k, " out of range [0, ", rigids, ") (rigids)");
  }
  return indices;
}

// SOFA's RestShapeSpringsForceField<Rigid3>: the rigids' centres pulled to their rest centres, their
// orientations turned back to their rest orientations (angularStiffness: SOFA's init gives 100 to
// each stiffness entry without one and drops the extra ones).
std::shared_ptr<ForceField<double>> rigid_rest_shape_springs(SceneData& data, Component& c, const MechanicalSystem<double>& system,
                                                             const std::shared_ptr<const RigidBlocks<double>>& rigids) {
  try {
    const auto count = static_cast<Index>(rigids->size());
    for (const char* unsupported : {"external_rest_shape", "pivot_points", "pivotPoints"}) {
      if (c.has(unsupported)) throw make_error(unsupported, " is not supported on rigid bodies");
    }
    RestShapeSpringsForceField<double>::Parameters p;
    p.anchors_follow_rest = true;
    std::vector<Index> picked = data.indices(c, "points");
    if (picked.empty()) {
      for (Index k = 0; k < count; ++k) picked.push_back(k);
    }
    for (Index k : picked) {
      if (k < 0 || k >= count) throw make_error("points: index ", k, " out of range [0, ", count, ") (rigids)");
      const auto at = static_cast<std::size_t>(k);
      p.points.push_back(rigids->block[at]);
      p.rigid_of_point.push_back(k);
      const RigidCoord<double> rest = rigids->rest_coord(system.state.rest_position, at);
      p.anchors.push_back(rest.center);
      p.rest_orientations.push_back(rest.orientation);
    }
    if (c.has("stiffness")) p.stiffness = data.data(c, "stiffness");
    if (p.stiffness.empty()) p.stiffness = {100};
    if (c.has("angularStiffness")) p.angular_stiffness = data.data(c, "angularStiffness");
    p.angular_stiffness.resize(p.stiffness.size(), 100.0);
    if (c.has("activeDirections")) {
      const Numbers& active = data.data(c, "activeDirections");
      if (active.size() != 6) throw make_error("activeDirections has ", active.size(), " values: 6 (x y z rx ry rz) for Rigid3");
      for (std::size_t axis = 0; axis < 3; ++axis) {
        p.active_directions[axis] = active[axis] != 0;
        p.active_rotations[axis] = active[axis + 3] != 0;
      }
    }
    p.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0);
    p.rigids = rigids;
    auto mesh = std::make_shared<const TetMesh>(system.size(), std::vector<Tetrahedron>{});
    return std::make_shared<RestShapeSpringsForceField<double>>(std::move(mesh), std::move(p));
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

// A field on points (PlaneForceField) acting on the rigids' centres: the field on one point per
// rigid, mapped onto the linear blocks (SOFA's PlaneForceField<Rigid3> reads and pushes the centres).
std::shared_ptr<ForceField<double>> on_rigid_centres(std::shared_ptr<ForceField<double>> field, const RigidBlocks<double>& rigids, Index points) {
  return std::make_shared<MappedForceField<double>>(std::move(field), PointMapping<double>::subset(rigids.block), points);
}

// SOFA's PartialFixedProjectiveConstraint<Rigid3>: fixedDirections has 6 flags (x y z rx ry rz; all
// held when not given); the held components of each listed rigid's increments (and, with
// projectVelocity, of its velocity after each step) are zeroed on its linear and angular blocks.
void add_partial_fixed_rigids(SceneData& data, Component& c, const RigidBlocks<double>& rigids, MechanicalSystem<double>& system) {
  const std::vector<Index> indices = fixed_rigids(data, c, static_cast<Index>(rigids.size()));
  std::vector<double> axes(6, 1.0);
  if (c.has("fixedDirections")) {
    const Numbers& given = data.data(c, "fixedDirections");
    if (given.size() != 6) throw make_error(c.where(), ": fixedDirections on a Rigid3 state needs 6 values (x y z rx ry rz), got ", given.size());
    axes.assign(given.begin(), given.end());
  }
  std::array<Mat3<double>, 2> free = {Mat3<double>::Identity(), Mat3<double>::Identity()};
  for (std::size_t a = 0; a < 6; ++a) {
    if (axes[a] != 0) free[a / 3](static_cast<Eigen::Index>(a % 3), static_cast<Eigen::Index>(a % 3)) = 0;
  }
  const bool velocity = data.boolean(c, "projectVelocity", false);
  for (Index k : indices) {
    for (Index j = 0; j < 2; ++j) {
      const Index block = rigids.block[static_cast<std::size_t>(k)] + j;
      system.projections.push_back({block, free[static_cast<std::size_t>(j)]});
      if (velocity) system.placements.push_back({block, Mat3<double>::Identity(), Vec3<double>::Zero(), free[static_cast<std::size_t>(j)]});
    }
  }
}

// ConstantForceField on rigids: 6 numbers per force (fx fy fz τx τy τz) on the two blocks.
ConstantForce<double> rigid_constant_force(SceneData& data, std::vector<std::string>& info, Component& c, Index rigids) {
  const std::vector<Index> indices = constant_force_indices(data, c, rigids);
  const auto count = indices.size();
  std::vector<double> values;
  const auto six = [&](const char* name) {
    const Numbers& v = data.data(c, name);
    if (v.size() != 6) throw make_error(c.where(), ": ", name, " on a Rigid3 state needs 6 numbers (fx fy fz tx ty tz), got ", v.size());
    return v;
  };
  if (c.has("forces")) {
    values = data.data(c, "forces");
    if (values.size() != 6 * count) {
      throw make_error(c.where(), ": forces has ", values.size(), " numbers for ", count, " rigids (6 per rigid)");
    }
  } else if (c.has("force")) {
    const Numbers one = six("force");
    for (std::size_t k = 0; k < count; ++k) values.insert(values.end(), one.begin(), one.end());
  } else if (c.has("totalForce")) {
    Numbers one = six("totalForce");
    for (double& v : one) v /= static_cast<double>(count);
    for (std::size_t k = 0; k < count; ++k) values.insert(values.end(), one.begin(), one.end());
  } else {
    info.push_back(c.where() + ": no forces, force or totalForce given: no load");
    values.assign(6 * count, 0.0);
  }
  ConstantForce<double> constant;
  for (std::size_t k = 0; k < count; ++k) {
    for (Index j = 0; j < 2; ++j) {
      constant.indices.push_back(2 * indices[k] + j);
      constant.forces.emplace_back(values[6 * k + 3 * j], values[6 * k + 3 * j + 1], values[6 * k + 3 * j + 2]);
    }
  }
  return constant;
}

}  // namespace

RigidMapping<double> build_rigid_mapping(SceneData& data, Component& mapping, const SimulatedObject<double>& object,
                                         const std::vector<Vec3<double>>& child_positions,
                                         const std::vector<Vec3<double>>& child_rest_positions) {
  if (!object.system.rigids) {
    throw make_error(mapping.where(), ": RigidMapping needs a Rigid3 parent state; ", object.path, " is not one");
  }
  RigidMappingOptions<double> options;
  if (mapping.has("initialPoints")) options.initial_points = points_from(data.data(mapping, "initialPoints"), mapping, "initialPoints");
  options.index = data.whole_number(mapping, "index", 0);
  options.index_from_end = data.boolean(mapping, "indexFromEnd", false);
  options.rigid_index_per_point = data.indices(mapping, "rigidIndexPerPoint");
  options.global_to_local_coords = data.boolean(mapping, "globalToLocalCoords", false);
  options.use_x0 = data.boolean(mapping, "useX0", false);
  const auto rigids = object.system.rigids->coords(object.system.state.position);
  return RigidMapping<double>(mapping.where(), rigids, child_positions, child_rest_positions, options);
}

SimulatedObject<double> build_rigid_object(SceneData& data, std::vector<std::string>& info, Component& state,
                                           const std::vector<GraphNode*>& nodes, const Vec3<double>& gravity) {
  SimulatedObject<double> object;
  object.path = state.node->path;
  auto& system = object.system;
  system.gravity = gravity;
  std::vector<RigidCoord<double>> coords, rest;
  try {
    coords = parse_rigid_coords<double>(data.data(state, "position"), "position");
    // rest_position: as written, else the positions before translation2 / rotation2 (SOFA's order).
    rest = parse_rigid_coords<double>(data.data(state, "rest_position"), "rest_position");
  } catch (const Error& error) {
    throw error_at(state.where(), error);
  }
  const auto count = static_cast<Index>(coords.size());
  if (count == 0) throw make_error(state.where(), ": the state has no rigids");
  if (rest.size() != coords.size()) {
    throw make_error(state.where(), ": rest_position has ", rest.size(), " rigids, position has ", count);
  }
  std::vector<Vec3<double>> velocity(2 * coords.size(), Vec3<double>::Zero());
  if (state.has("velocity")) {
    try {
      velocity = parse_rigid_derivs<double>(data.data(state, "velocity"), "velocity");
    } catch (const Error& error) {
      throw error_at(state.where(), error);
    }
    if (velocity.size() == 2) {
      const std::vector<Vec3<double>> one = velocity;
      for (Index k = 1; k < count; ++k) velocity.insert(velocity.end(), one.begin(), one.end());
    }
    if (velocity.size() != 2 * coords.size()) {
      throw make_error(state.where(), ": velocity has ", velocity.size() / 2, " rigids, position has ", count);
    }
  }
  auto blocks = std::make_shared<RigidBlocks<double>>();
  for (std::size_t k = 0; k < coords.size(); ++k) {
    system.state.position.push_back(coords[k].center);
    system.state.position.push_back(Vec3<double>::Zero());
    system.state.rest_position.push_back(rest[k].center);
    system.state.rest_position.push_back(Vec3<double>::Zero());
    blocks->block.push_back(static_cast<Index>(2 * k));
    blocks->orientation.push_back(coords[k].orientation);
    blocks->rest_orientation.push_back(rest[k].orientation);
  }
  system.state.velocity = velocity;
  system.rigids = blocks;
  object.states.push_back({state.node->path, state.sofa_name(), 0, system.size(), true});

  for (GraphNode* node : nodes) {
    for (const auto& c : node->components) {
      if (!c->spec) continue;
      const std::string_view type = c->type();
      const std::string_view category = c->spec->category;
      if (is_interaction_spring(type)) continue;  // joins objects: added with them (add_interaction_springs)
      if (type == "UniformMass") {
        if (system.mass.size() != 0) throw make_error(c->where(), ": a second mass for ", object.path);
        const RigidMass<double> mass = uniform_mass(data, *c, count);
        const RigidMassBlocks<double> b = mass_blocks(mass);
        std::vector<Mat3<double>> per_block;
        std::vector<double> weights;
        for (Index k = 0; k < count; ++k) {
          per_block.push_back(b.linear);
          per_block.push_back(b.angular);
          weights.push_back(mass.mass);
          weights.push_back(0);
        }
        system.mass = Mass<double>::block_diagonal(std::move(per_block));
        system.mass.set_gravity_masses(std::move(weights));
      } else if (type == "FixedProjectiveConstraint") {
        for (Index k : fixed_rigids(data, *c, count)) {
          for (Index j = 0; j < 2; ++j) {
            system.fixed.push_back(2 * k + j);
            if (data.boolean(*c, "activate_projectVelocity", false)) system.zero_velocity.push_back(2 * k + j);
          }
        }
      } else if (type == "PartialFixedProjectiveConstraint") {
        add_partial_fixed_rigids(data, *c, *blocks, system);
      } else if (type == "LinearMovementProjectiveConstraint") {
        system.linear_movements.push_back(build_linear_movement(data, *c, count, true));
      } else if (type == "ConstantForceField") {
        system.constant_forces.push_back(rigid_constant_force(data, info, *c, count));
      } else if (type == "RestShapeSpringsForceField") {
        system.force_fields.push_back(rigid_rest_shape_springs(data, *c, system, blocks));
        object.force_field_drawing.push_back({});
      } else if (type == "PlaneForceField") {
        auto centres = std::make_shared<const TetMesh>(count, std::vector<Tetrahedron>{});
        system.force_fields.push_back(on_rigid_centres(build_penalty_force_field(data, *c, std::move(centres)), *blocks, system.size()));
        object.force_field_drawing.push_back({});
      } else if (category == "forcefield" || category == "mass" || category == "constraint") {
        throw make_error(c->where(), ": ", type, " on the Rigid3 state ", state.where(),
                         ": not supported on rigid bodies yet (there: UniformMass, FixedProjectiveConstraint, ConstantForceField, "
                         "PartialFixedProjectiveConstraint, LinearMovementProjectiveConstraint, RestShapeSpringsForceField, PlaneForceField)");
      }
    }
  }
  return object;
}

}  // namespace fastcorot::scene_detail
