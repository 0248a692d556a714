#include "fastcorot/sim/merged_objects.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

namespace {

TetMesh shifted_mesh(const TetMesh& mesh, Index offset, Index total) {
  std::vector<Tetrahedron> tetrahedra(mesh.tetrahedra().begin(), mesh.tetrahedra().end());
  for (auto& t : tetrahedra) {
    for (Index& v : t) v += offset;
  }
  return TetMesh(total, std::move(tetrahedra));
}

// The parts' masses as one block mass, when some part has rigid bodies: a lumped mass m gives
// blocks m I₃; a rigid part gives its own blocks (without what its carried points add: the merged
// object recomputes that from its RigidMappedMass). Weights: each part's gravity masses.
Mass<double> merged_block_mass(const std::vector<SimulatedObject<double>>& parts) {
  std::vector<Mat3<double>> blocks;
  std::vector<double> weights;
  for (const auto& part : parts) {
    const auto& s = part.system;
    const Mass<double>& own = s.rigid_mapped_mass ? s.rigid_mapped_mass->own : s.mass;
    if (own.size() == 0) {
      blocks.insert(blocks.end(), static_cast<std::size_t>(s.size()), Mat3<double>::Zero());
      weights.insert(weights.end(), static_cast<std::size_t>(s.size()), 0.0);
      continue;
    }
    if (own.is_block_diagonal()) {
      blocks.insert(blocks.end(), own.blocks().begin(), own.blocks().end());
    } else if (own.is_lumped()) {
      for (double m : own.vertex_masses()) blocks.push_back(m * Mat3<double>::Identity());
    } else {
      throw make_error(part.path, ": a mass matrix (MeshMatrixMass without lumping) solved together with rigid bodies is not supported ",
                       "(lump it, or give the rigid bodies their own ODE solver)");
    }
    const auto w = own.gravity_masses();
    weights.insert(weights.end(), w.begin(), w.end());
  }
  Mass<double> mass = Mass<double>::block_diagonal(std::move(blocks));
  mass.set_gravity_masses(std::move(weights));
  return mass;
}

}  // namespace

template <class Real>
OffsetForceField<Real>::OffsetForceField(std::shared_ptr<ForceField<Real>> inner, Index offset, Index total)
    : inner_(std::move(inner)), offset_(offset), count_(inner_->mesh().num_points()),
      shifted_(shifted_mesh(inner_->mesh(), offset, total)) {
  if (offset_ < 0 || offset_ + count_ > total) {
    throw make_error(inner_->component(), ": points [", offset_, ", ", offset_ + count_, ") outside a state of ", total);
  }
}

template <class Real>
void OffsetForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron>) const {
  throw make_error(inner_->component(), ": topological changes of objects solved together are not supported");
}

template <class Real>
void OffsetForceField<Real>::apply(const TopologyChange&) {
  throw make_error(inner_->component(), ": topological changes of objects solved together are not supported");
}

template <class Real>
std::vector<double> OffsetForceField<Real>::model_values() const {
  std::vector<double> values = inner_->model_values();
  values.push_back(static_cast<double>(offset_));
  return values;
}

template class OffsetForceField<double>;
template class OffsetForceField<float>;

SimulatedObject<double> merge_objects(std::vector<SimulatedObject<double>> parts, const std::string& path) {
  SimulatedObject<double> merged;
  merged.path = path;
  if (parts.empty()) throw make_error(path, ": no objects to merge");
  auto& system = merged.system;
  system.gravity = parts.front().system.gravity;
  Index total = 0;
  for (const auto& part : parts) total += part.system.size();
  // A part without mass whose every point is fixed (an anchor that SOFA's springs pull on, or a
  // still surface the scene builder holds) weighs nothing beside parts with masses: zero masses,
  // which its fixed points never use.
  bool any_mass = false;
  for (const auto& part : parts) any_mass = any_mass || part.system.mass.size() != 0;
  for (auto& part : parts) {
    auto& s = part.system;
    if (any_mass && s.mass.size() == 0 && static_cast<Index>(s.fixed.size()) == s.size()) {
      s.mass = Mass<double>::lumped(std::vector<double>(static_cast<std::size_t>(s.size()), 0.0));
    }
  }
  const bool massive = parts.front().system.mass.size() != 0;
  bool lumped = true;
  bool blocks = false;  // some part has a block mass (rigid bodies)
  std::shared_ptr<RigidBlocks<double>> rigids;
  std::vector<RigidMappedMass<double>::Carried> carried_masses;
  std::vector<Tetrahedron> all_tetrahedra;
  Index offset = 0;
  for (auto& part : parts) {
    auto& s = part.system;
    const auto shift = [offset](Index i) { return i + offset; };
    if (s.gravity != system.gravity) throw make_error(part.path, ": another gravity than ", parts.front().path, " under the same solver");
    if ((s.mass.size() != 0) != massive) throw make_error(part.path, ": a mass on some of the objects under one solver only");
    if (!part.topology_scripts.empty()) {
      throw make_error(part.path, ": scripted topological changes of objects solved together are not supported");
    }
    const std::size_t rigid_offset = rigids ? rigids->size() : 0;
    if (s.rigids) {
      // The part's rigids become the merged object's, their blocks shifted; the part keeps its
      // own RigidBlocks for what was built on its range (force fields), as a follower.
      if (!rigids) rigids = std::make_shared<RigidBlocks<double>>();
      for (std::size_t k = 0; k < s.rigids->size(); ++k) {
        rigids->block.push_back(shift(s.rigids->block[k]));
        rigids->orientation.push_back(s.rigids->orientation[k]);
        rigids->rest_orientation.push_back(s.rigids->rest_orientation[k]);
      }
      rigids->followers.emplace_back(s.rigids, rigid_offset);
    }
    const auto repoint = [&](RigidPoints<double>& points) {
      points.frames = rigids;
      for (Index& k : points.rigid) k += static_cast<Index>(rigid_offset);
    };
    if (s.rigid_mapped_mass) {
      for (auto carried : s.rigid_mapped_mass->carried) {
        repoint(carried.points);
        carried_masses.push_back(std::move(carried));
      }
    }
    lumped = lumped && s.mass.is_lumped();
    blocks = blocks || s.mass.is_block_diagonal();
    system.state.position.insert(system.state.position.end(), s.state.position.begin(), s.state.position.end());
    system.state.velocity.insert(system.state.velocity.end(), s.state.velocity.begin(), s.state.velocity.end());
    system.state.rest_position.insert(system.state.rest_position.end(), s.state.rest_position.begin(), s.state.rest_position.end());
    for (auto& field : s.force_fields) system.force_fields.push_back(std::make_shared<OffsetForceField<double>>(field, offset, total));
    for (Index i : s.fixed) system.fixed.push_back(shift(i));
    for (Index i : s.zero_velocity) system.zero_velocity.push_back(shift(i));
    for (auto constant : s.constant_forces) {
      for (Index& i : constant.indices) i = shift(i);
      system.constant_forces.push_back(std::move(constant));
    }
    for (auto p : s.projections) system.projections.push_back({shift(p.point), p.projector});
    for (auto c : s.couplings) {
      c.first = shift(c.first);
      c.second = shift(c.second);
      system.couplings.push_back(c);
    }
    for (auto p : s.placements) system.placements.push_back({shift(p.point), p.projector, p.origin, p.velocity_projector});
    for (auto m : s.motions) system.motions.push_back({shift(m.point), m.start, m.end, m.begin_time, m.end_time});
    for (auto movement : s.linear_movements) {
      for (Index& p : movement.points) p = shift(p);
      for (Index& k : movement.rigids) k += static_cast<Index>(rigid_offset);
      system.linear_movements.push_back(std::move(movement));
    }
    merged.force_field_drawing.insert(merged.force_field_drawing.end(), part.force_field_drawing.begin(), part.force_field_drawing.end());
    merged.boxes.insert(merged.boxes.end(), part.boxes.begin(), part.boxes.end());
    for (auto range : part.states) {
      range.offset = shift(range.offset);
      merged.states.push_back(std::move(range));
    }
    // A map reads the object's points, or, with `through`, the points `through` gives from the
    // part's own blocks (its own RigidBlocks follow the merged ones): then the part's offset moves.
    const auto follow = [&](auto& shown) {
      if (shown.through) {
        shown.through_offset = shift(shown.through_offset);
        return;
      }
      for (auto& slots : shown.map.vertices) {
        for (Index& v : slots) v = shift(v);
      }
      if (shown.rigid) repoint(*shown.rigid);
    };
    for (auto mapped : part.mapped_states) {
      follow(mapped);
      merged.mapped_states.push_back(std::move(mapped));
    }
    for (auto surface : part.visual_surfaces) {
      follow(surface);
      merged.visual_surfaces.push_back(std::move(surface));
    }
    if (part.mesh) {
      for (Tetrahedron t : part.mesh->tetrahedra()) {
        for (Index& v : t) v = shift(v);
        all_tetrahedra.push_back(t);
      }
    }
    offset += s.size();
  }
  system.rigids = rigids;
  if (massive && blocks) {
    system.mass = merged_block_mass(parts);
    if (!carried_masses.empty()) {
      auto mapped = std::make_shared<RigidMappedMass<double>>();
      mapped->own = system.mass;
      mapped->carried = std::move(carried_masses);
      system.rigid_mapped_mass = std::move(mapped);
    }
  } else if (massive) {
    // Masses one after the other: lumped stays lumped, else a block-diagonal matrix.
    if (lumped) {
      std::vector<double> masses;
      for (const auto& part : parts) masses.insert(masses.end(), part.system.mass.vertex_masses().begin(), part.system.mass.vertex_masses().end());
      system.mass = Mass<double>::lumped(std::move(masses));
    } else {
      std::vector<Eigen::Triplet<double>> entries;
      Index at = 0;
      for (const auto& part : parts) {
        const auto& mass = part.system.mass;
        if (mass.is_lumped()) {
          for (Index i = 0; i < mass.size(); ++i) entries.emplace_back(at + i, at + i, mass.vertex_masses()[static_cast<std::size_t>(i)]);
        } else {
          const auto& m = mass.matrix();
          for (int r = 0; r < m.outerSize(); ++r) {
            for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(m, r); it; ++it) {
              entries.emplace_back(at + static_cast<Index>(it.row()), at + static_cast<Index>(it.col()), it.value());
            }
          }
        }
        at += part.system.size();
      }
      Eigen::SparseMatrix<double> matrix(total, total);
      matrix.setFromTriplets(entries.begin(), entries.end());
      system.mass = Mass<double>::consistent(matrix);
    }
    bool own_gravity_masses = false;
    std::vector<double> gravity_masses;
    for (const auto& part : parts) {
      own_gravity_masses = own_gravity_masses || part.system.mass.has_own_gravity_masses();
      const auto masses = part.system.mass.gravity_masses();
      gravity_masses.insert(gravity_masses.end(), masses.begin(), masses.end());
    }
    if (own_gravity_masses) system.mass.set_gravity_masses(std::move(gravity_masses));
  }
  if (!all_tetrahedra.empty()) merged.mesh = std::make_shared<TetMesh>(total, std::move(all_tetrahedra));
  system.update_mass();
  system.finalize();
  return merged;
}

}  // namespace fastcorot
