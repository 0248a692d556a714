// MappedForceField<Real>: a force field written on a mapped state (a MechanicalObject in a child
// node under an IdentityMapping, SubsetMapping, BarycentricMapping or RigidMapping) acting on the
// simulated state above it, as SOFA's mechanical visitors make it act: positions go down the
// mapping (y = map(x)), velocities and increments through J, the field's forces come back up
// through Jᵀ, its stiffness enters products as Jᵀ K J dx and assembled matrices as the blocks of
// Jᵀ K J (no geometric stiffness: none for a linear mapping, SOFA's default for RigidMapping).
// A nonlinear mapping is linearised where add_force last evaluated it. Chains (tetrahedra → surface → points) are fields of fields: the inner field may be
// a MappedForceField itself. The inner field keeps its own rest positions and mesh, in the mapped
// state's numbering; mesh() is the parent's points with no elements. Topological changes are
// refused. Design: docs/mechanical-graph.md.
#pragma once

#include "fastcorot/fem/force_field.h"
#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/mapping/point_mapping.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
class MappedForceField final : public ForceField<Real> {
 public:
  // `inner` acts on the map.size() points of the mapped state; the parent has `parent_points`.
  // Throws fastcorot::Error when the inner field's points are not the mapping's, or the mapping
  // reaches beyond the parent.
  MappedForceField(std::shared_ptr<ForceField<Real>> inner, std::unique_ptr<MechanicalMapping<Real>> map, Index parent_points);
  MappedForceField(std::shared_ptr<ForceField<Real>> inner, PointMapping<Real> map, Index parent_points)
      : MappedForceField(std::move(inner), std::make_unique<LinearMapping<Real>>(std::move(map)), parent_points) {}

  std::string component() const override { return inner_->component(); }
  std::string method_name() const override { return inner_->method_name(); }
  const TetMesh& mesh() const override { return parent_mesh_; }
  const ForceField<Real>& inner() const { return *inner_; }

  void set_velocity(std::span<const Vec3<Real>> v) override;
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  void end_step(std::span<const Vec3<Real>> x) override;
  std::vector<Mat3<Real>> rotations() const override { return inner_->rotations(); }
  void check_new_tetrahedra(std::span<const Tetrahedron>) const override;
  void apply(const TopologyChange&) override;
  std::vector<double> model_values() const override;
  std::string unsaved_state() const override { return inner_->unsaved_state(); }
  void set_threads(int threads) override { inner_->set_threads(threads); }
  int threads() const override { return inner_->threads(); }
  void set_phase_times(PhaseTimes* times) override { inner_->set_phase_times(times); }
  std::size_t memory_bytes() const override;

 private:
  // The mapped field's blocks (i, j) of k_factor K (+ b_factor Rayleigh), in the mapped numbering.
  std::vector<Eigen::Triplet<Real>> inner_blocks(Real k_factor, Real b_factor) const;

  std::shared_ptr<ForceField<Real>> inner_;
  std::unique_ptr<MechanicalMapping<Real>> map_;
  TetMesh parent_mesh_;
  std::span<const Vec3<Real>> parent_velocity_;  // from set_velocity, read by add_force
  // Work vectors in the mapped numbering (the mapped positions, velocities, increments, forces).
  std::vector<Vec3<Real>> x_, v_;
  mutable std::vector<Vec3<Real>> dx_, f_;
};

}  // namespace fastcorot
