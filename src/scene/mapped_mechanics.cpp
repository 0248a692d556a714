#include "mapped_mechanics.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/constant_force_field.h"
#include "fastcorot/mapping/mapped_force_field.h"
#include "fastcorot/sim/rigid_mapped_mass.h"

#include <algorithm>
#include <functional>
#include <memory>

namespace fastcorot::scene_detail {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

SparseMatrix mass_matrix(const Mass<double>& mass) {
  if (!mass.is_lumped()) return SparseMatrix(mass.matrix());
  const auto masses = mass.vertex_masses();
  SparseMatrix m(mass.size(), mass.size());
  std::vector<Eigen::Triplet<double>> diagonal;
  for (Index i = 0; i < mass.size(); ++i) diagonal.emplace_back(i, i, masses[static_cast<std::size_t>(i)]);
  m.setFromTriplets(diagonal.begin(), diagonal.end());
  return m;
}

bool is_diagonal(const SparseMatrix& m) {
  for (Index k = 0; k < m.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(m, k); it; ++it) {
      if (it.row() != it.col() && it.value() != 0) return false;
    }
  }
  return true;
}

// The parent's mass plus Jᵀ M_child J: lumped while both are diagonal (identity and subset
// mappings of lumped masses), else consistent. Gravity weighs the parent's own gravity masses
// plus Jᵀ m_child (the mapped weights m_i g carried up).
Mass<double> add_mapped_mass(const Mass<double>& parent, const Mass<double>& child, const PointMapping<double>& map, Index n) {
  const SparseMatrix j = SparseMatrix(map.matrix(n));
  const SparseMatrix added = SparseMatrix(j.transpose() * mass_matrix(child) * j);
  SparseMatrix total = parent.size() == 0 ? added : SparseMatrix(mass_matrix(parent) + added);
  std::vector<double> weights(static_cast<std::size_t>(n), 0.0);
  if (parent.size() != 0) {
    const auto own = parent.gravity_masses();
    weights.assign(own.begin(), own.end());
  }
  const auto child_weights = child.gravity_masses();
  for (std::size_t i = 0; i < map.size(); ++i) {
    for (std::size_t k = 0; k < static_cast<std::size_t>(PointMapping<double>::kSlots); ++k) {
      weights[static_cast<std::size_t>(map.vertices[i][k])] += map.weights[i][k] * child_weights[i];
    }
  }
  Mass<double> mass;
  if (is_diagonal(total) && (parent.size() == 0 || parent.is_lumped())) {
    std::vector<double> diagonal(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) diagonal[static_cast<std::size_t>(i)] = total.coeff(i, i);
    mass = Mass<double>::lumped(std::move(diagonal));
  } else {
    mass = Mass<double>::consistent(std::move(total));
  }
  mass.set_gravity_masses(std::move(weights));
  return mass;
}

// What no mapped node can hold here, whatever its mapping, and a mapping of the wrong size.
void check_foldable(const SimulatedObject<double>& child, std::size_t mapped_points, const char* mapping, const std::string& where) {
  const auto& from = child.system;
  if (static_cast<Index>(mapped_points) != from.size()) {
    throw make_error(where, ": the ", mapping, " gives ", mapped_points, " points, the mapped MechanicalObject has ", from.size());
  }
  if (!from.fixed.empty() || !from.projections.empty() || !from.couplings.empty() || !from.placements.empty() ||
      !from.motions.empty() || !from.linear_movements.empty()) {
    throw make_error(where, ": projective constraints on a mapped state are not supported (put them on the simulated object)");
  }
  if (!child.topology_scripts.empty()) throw make_error(where, ": scripted topological changes in a mapped node are not supported");
  for (const MappedState& state : child.mapped_states) {
    if (state.coordinates == 1) {
      throw make_error(where, ": the DistanceMapping of ", state.node, " reads the points of a mapped state: only a DistanceMapping ",
                       "on a simulated object's own points is supported");
    }
  }
}

// The child's force fields and constant loads acting on `parent` through mappings `make` gives
// (one per field: a nonlinear mapping records where its field last evaluated it). A constant load
// comes up as Jᵀ F with J evaluated where the points are (under a RigidMapping: the force on the
// centre and the torque r × F, r turning with the body), so it is a force field here too.
void add_fields_through(SimulatedObject<double>& child, const std::function<std::unique_ptr<MechanicalMapping<double>>()>& make,
                        SimulatedObject<double>& parent) {
  auto& from = child.system;
  auto fields = from.force_fields;
  const auto points = std::make_shared<const TetMesh>(from.size(), std::vector<Tetrahedron>{});
  for (const auto& load : from.constant_forces) {
    fields.push_back(std::make_shared<ConstantForceField<double>>(points, load.indices, load.forces));
  }
  for (const auto& field : fields) {
    parent.system.force_fields.push_back(std::make_shared<MappedForceField<double>>(field, make(), parent.system.size()));
    parent.force_field_drawing.push_back({});
  }
}

}  // namespace

void check_mapped_points_inside(const MappedState& mapped, const std::string& where) {
  if (mapped.rigid || !mapped.mapping.starts_with("BarycentricMapping (tetrahedra")) return;
  for (std::size_t i = 0; i < mapped.map.size(); ++i) {
    const auto& w = mapped.map.weights[i];
    if (std::min({w[0], w[1], w[2], w[3]}) >= -1) continue;
    throw make_error(where, ": point ", i, " of its MechanicalObject lies outside every tetrahedron, farther than the ",
                     "nearest one's size (barycentric coordinates ", w[0], " ", w[1], " ", w[2], " ", w[3],
                     "): forces on it would act through weights beyond the mesh; move it inside the mesh");
  }
}

void fold_mapped_object(SimulatedObject<double>& child, const PointMapping<double>& map, SimulatedObject<double>& parent,
                        const std::string& where) {
  auto& from = child.system;
  auto& to = parent.system;
  const Index n = to.size();
  check_foldable(child, map.size(), "mapping", where);
  for (std::size_t k = 0; k < from.force_fields.size(); ++k) {
    to.force_fields.push_back(std::make_shared<MappedForceField<double>>(from.force_fields[k], map, n));
    parent.force_field_drawing.push_back({});
  }
  if (from.mass.size() != 0) to.mass = add_mapped_mass(to.mass, from.mass, map, n);
  for (const auto& load : from.constant_forces) {
    ConstantForce<double> mapped;
    for (std::size_t i = 0; i < load.indices.size(); ++i) {
      const auto point = static_cast<std::size_t>(load.indices[i]);
      for (std::size_t k = 0; k < static_cast<std::size_t>(PointMapping<double>::kSlots); ++k) {
        if (map.weights[point][k] == 0) continue;
        mapped.indices.push_back(map.vertices[point][k]);
        mapped.forces.push_back(map.weights[point][k] * load.forces[i]);
      }
    }
    to.constant_forces.push_back(std::move(mapped));
  }
  for (auto& surface : child.visual_surfaces) {
    surface.map = surface.map.after(map);
    parent.visual_surfaces.push_back(std::move(surface));
  }
  for (auto& state : child.mapped_states) {
    state.map = state.map.after(map);
    parent.mapped_states.push_back(std::move(state));
  }
  parent.boxes.insert(parent.boxes.end(), child.boxes.begin(), child.boxes.end());
}

void fold_rigid_mapped_object(SimulatedObject<double>& child, const RigidPoints<double>& points, SimulatedObject<double>& parent,
                              const std::string& where) {
  auto& from = child.system;
  auto& to = parent.system;
  check_foldable(child, points.size(), "RigidMapping", where);
  if (from.mass.size() != 0) {
    if (!from.mass.is_lumped()) {
      throw make_error(where, ": a mass matrix (MeshMatrixMass without lumping) on points carried by rigid bodies is not supported: lump it or use UniformMass or DiagonalMass");
    }
    auto mapped = std::make_shared<RigidMappedMass<double>>();
    if (to.rigid_mapped_mass) {
      *mapped = *to.rigid_mapped_mass;
    } else {
      mapped->own = to.mass;
    }
    const auto masses = from.mass.vertex_masses();
    const auto weights = from.mass.gravity_masses();
    mapped->carried.push_back({points, {masses.begin(), masses.end()}, {weights.begin(), weights.end()}});
    to.rigid_mapped_mass = std::move(mapped);
    to.update_mass();
  }
  add_fields_through(child, [&] { return std::make_unique<RigidPointMapping<double>>(points); }, parent);
  // A point below that mixes rigids, or whose weights do not sum to 1, reads the carried points
  // themselves (`through`).
  std::shared_ptr<const MechanicalMapping<double>> carried;
  const auto follow = [&](auto& shown) {
    if (shown.rigid || shown.through) return false;
    shown.rigid = points.after(shown.map);
    if (!shown.rigid) {
      if (!carried) carried = std::make_shared<RigidPointMapping<double>>(points);
      shown.through = carried;
    }
    return true;
  };
  for (auto& surface : child.visual_surfaces) {
    if (follow(surface)) parent.visual_surfaces.push_back(std::move(surface));
  }
  for (auto& state : child.mapped_states) {
    if (follow(state)) parent.mapped_states.push_back(std::move(state));
  }
  parent.boxes.insert(parent.boxes.end(), child.boxes.begin(), child.boxes.end());
}

void fold_multi_mapped_mass(const SimulatedObject<double>& child, const SubsetMultiMappingInputs& inputs,
                            SimulatedObject<double>& parent, const std::string& where) {
  const auto& mass = child.system.mass;
  if (mass.size() == 0) return;
  if (!mass.is_lumped()) {
    throw make_error(where, ": a mass matrix (MeshMatrixMass without lumping) on a SubsetMultiMapping that joins points "
                     "carried by rigid bodies and other points is not supported: lump it or use UniformMass or DiagonalMass");
  }
  // Jᵀ M J of a lumped mass splits by point: each output point is one input's point, on the
  // parent's points (a linear input) or carried by a rigid (RigidMappedMass, as under a RigidMapping).
  auto& to = parent.system;
  const auto masses = mass.vertex_masses();
  const auto weights = mass.gravity_masses();
  PointMapping<double> linear;
  std::vector<double> linear_masses, linear_weights;
  std::vector<RigidMappedMass<double>::Carried> carried(inputs.inputs.size());
  for (std::size_t i = 0; i < inputs.pairs.size(); ++i) {
    const auto& [k, j] = inputs.pairs[i];
    const auto& input = inputs.inputs[k];
    const auto at = static_cast<std::size_t>(j);
    if (input.rigid) {
      auto& c = carried[k];
      if (!c.points.frames) c.points.frames = input.rigid->frames;
      c.points.local.push_back(input.rigid->local[at]);
      c.points.rigid.push_back(input.rigid->rigid[at]);
      c.masses.push_back(masses[i]);
      c.weights.push_back(weights[i]);
    } else {
      linear.vertices.push_back(input.map.vertices[at]);
      linear.weights.push_back(input.map.weights[at]);
      linear_masses.push_back(masses[i]);
      linear_weights.push_back(weights[i]);
    }
  }
  // The parent's own mass (what its rigids carry aside) as 3×3 blocks, with the linear inputs'
  // points added where they lie: a SubsetMultiMapping's linear inputs are the parent's points
  // themselves (one weight of 1); other weights would couple points, which a block mass cannot hold.
  const Mass<double> base = to.rigid_mapped_mass ? to.rigid_mapped_mass->own : to.mass;
  const auto n = static_cast<std::size_t>(to.size());
  std::vector<Mat3<double>> blocks(n, Mat3<double>::Zero());
  std::vector<double> gravity(n, 0.0);
  if (base.size() != 0) {
    if ((!base.is_lumped() && !base.is_block_diagonal()) || !base.couplings().empty() || base.size() != to.size()) {
      throw make_error(where, ": a mass on a SubsetMultiMapping over objects with a mass matrix (not lumped) is not supported");
    }
    const auto masses_of = base.vertex_masses();
    const auto blocks_of = base.blocks();
    const auto weights_of = base.gravity_masses();
    for (std::size_t i = 0; i < n; ++i) {
      blocks[i] = base.is_block_diagonal() ? blocks_of[i] : Mat3<double>(masses_of[i] * Mat3<double>::Identity());
      gravity[i] = weights_of[i];
    }
  }
  for (std::size_t i = 0; i < linear.size(); ++i) {
    const auto& w = linear.weights[i];
    std::size_t slot = 0, used = 0;
    for (std::size_t k = 0; k < w.size(); ++k) {
      if (w[k] != 0) {
        slot = k;
        ++used;
      }
    }
    if (used != 1 || w[slot] != 1) {
      throw make_error(where, ": a mass on a SubsetMultiMapping whose input is itself mapped (a point spread over several) is "
                       "not supported: put the mass on that input's state");
    }
    const auto v = static_cast<std::size_t>(linear.vertices[i][slot]);
    blocks[v].diagonal().array() += linear_masses[i];
    gravity[v] += linear_weights[i];
  }
  Mass<double> own = Mass<double>::block_diagonal(std::move(blocks));
  own.set_gravity_masses(std::move(gravity));
  auto mapped = std::make_shared<RigidMappedMass<double>>();
  if (to.rigid_mapped_mass) *mapped = *to.rigid_mapped_mass;
  mapped->own = std::move(own);
  for (auto& c : carried) {
    if (!c.points.local.empty()) mapped->carried.push_back(std::move(c));
  }
  to.rigid_mapped_mass = std::move(mapped);
  to.update_mass();
}

void fold_multi_mapped_object(SimulatedObject<double>& child, const std::function<std::unique_ptr<MechanicalMapping<double>>()>& make,
                              SimulatedObject<double>& parent, const std::string& where) {
  std::shared_ptr<const MechanicalMapping<double>> through = make();
  check_foldable(child, through->size(), "SubsetMultiMapping", where);
  add_fields_through(child, make, parent);
  for (auto& surface : child.visual_surfaces) {
    if (surface.rigid || surface.through) continue;
    surface.through = through;
    parent.visual_surfaces.push_back(std::move(surface));
  }
  for (auto& state : child.mapped_states) {
    if (state.rigid || state.through) continue;
    state.through = through;
    parent.mapped_states.push_back(std::move(state));
  }
  parent.boxes.insert(parent.boxes.end(), child.boxes.begin(), child.boxes.end());
}

}  // namespace fastcorot::scene_detail
