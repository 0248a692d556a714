// ConstantForceField<Real>: SOFA's ConstantForceField as a force field: f_i += F_i at the listed
// points, no stiffness, energy -Σ F_i · x_i. A system applies its own constant loads directly
// (MechanicalSystem::constant_forces); this form is for loads written on a state that a nonlinear
// mapping carries (points under a RigidMapping), where MappedForceField brings them up through Jᵀ
// at each step's linearisation (a force on the centre and the torque r × F), as SOFA's visitors do.
#pragma once

#include "fastcorot/fem/force_field.h"

#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
class ConstantForceField final : public ForceField<Real> {
 public:
  // Throws fastcorot::Error for a point outside the mesh's points, a non-finite force, or not one
  // force per point.
  ConstantForceField(std::shared_ptr<const TetMesh> mesh, std::vector<Index> points, std::vector<Vec3<Real>> forces);

  std::string component() const override { return "ConstantForceField"; }
  std::string method_name() const override { return "constant forces"; }
  const TetMesh& mesh() const override { return *mesh_; }

  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override { add_force(x, f); }
  void add_dforce(std::span<const Vec3<Real>>, std::span<Vec3<Real>>, Real, Real = 0) const override {}
  void add_stiffness(MatrixSink<Real>&, Real, Index = 0, Real = 0) const override {}
  void add_diagonal_blocks(std::span<Mat3<Real>>, Real, Real = 0) const override {}
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  std::vector<Mat3<Real>> rotations() const override { return {}; }
  // Points, not elements: topological changes leave the loads as they are.
  void check_new_tetrahedra(std::span<const Tetrahedron>) const override {}
  void apply(const TopologyChange&) override {}
  std::vector<double> model_values() const override;
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes*) override {}
  std::size_t memory_bytes() const override { return points_.size() * (sizeof(Index) + sizeof(Vec3<Real>)); }

 private:
  std::shared_ptr<const TetMesh> mesh_;
  std::vector<Index> points_;
  std::vector<Vec3<Real>> forces_;
  int threads_ = 1;
};

}  // namespace fastcorot
