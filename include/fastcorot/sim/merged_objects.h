// Several SOFA objects under one ODE solver, integrated as one system, as SOFA's solver does: the
// states one after the other, each object's force fields acting on its own range of points
// (OffsetForceField), its mass, constraints, loads and visual surfaces shifted to that range. The
// solver then sees one system: one linear solve for all, with CG's residual and iteration count
// taken over all of them, as in SOFA.
#pragma once

#include "fastcorot/sim/simulation.h"

#include <memory>
#include <vector>

namespace fastcorot {

// A force field on points [offset, offset + inner.mesh().num_points()) of a larger state of
// `total` points: every call passes the inner field that range. mesh() is the inner mesh with its
// indices shifted (for drawing and output); topological changes are refused.
template <class Real>
class OffsetForceField final : public ForceField<Real> {
 public:
  OffsetForceField(std::shared_ptr<ForceField<Real>> inner, Index offset, Index total);

  std::string component() const override { return inner_->component(); }
  std::string method_name() const override { return inner_->method_name(); }
  const TetMesh& mesh() const override { return shifted_; }
  const ForceField<Real>& inner() const { return *inner_; }

  void set_velocity(std::span<const Vec3<Real>> v) override { inner_->set_velocity(v.empty() ? v : range(v)); }
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override { inner_->add_force(range(x), range(f)); }
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override {
    inner_->add_force_only(range(x), range(f));
  }
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real b_factor = 0) const override {
    inner_->add_dforce(range(dx), range(df), k_factor, b_factor);
  }
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override {
    inner_->add_stiffness(sink, k_factor, offset + 3 * offset_, b_factor);
  }
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override {
    inner_->add_diagonal_blocks(range(diagonal), k_factor, b_factor);
  }
  Real potential_energy(std::span<const Vec3<Real>> x) const override { return inner_->potential_energy(range(x)); }
  void end_step(std::span<const Vec3<Real>> x) override { inner_->end_step(range(x)); }
  std::vector<Mat3<Real>> rotations() const override { return inner_->rotations(); }
  void check_new_tetrahedra(std::span<const Tetrahedron>) const override;
  void apply(const TopologyChange&) override;
  std::vector<double> model_values() const override;
  bool follow_rest(std::span<const Vec3<Real>> rest_position) override { return inner_->follow_rest(range(rest_position)); }
  std::string unsaved_state() const override { return inner_->unsaved_state(); }
  void set_threads(int threads) override { inner_->set_threads(threads); }
  int threads() const override { return inner_->threads(); }
  void set_phase_times(PhaseTimes* times) override { inner_->set_phase_times(times); }
  std::size_t memory_bytes() const override { return inner_->memory_bytes(); }

 private:
  template <class T>
  std::span<T> range(std::span<T> v) const {
    return v.subspan(static_cast<std::size_t>(offset_), static_cast<std::size_t>(count_));
  }

  std::shared_ptr<ForceField<Real>> inner_;
  Index offset_, count_;
  TetMesh shifted_;
};

// One object of the parts' states in order (path: `path`), each part finalized. Throws
// fastcorot::Error naming the part for what a merged object cannot hold: different gravities,
// masses on some parts only, scripted topological changes.
SimulatedObject<double> merge_objects(std::vector<SimulatedObject<double>> parts, const std::string& path);

}  // namespace fastcorot
