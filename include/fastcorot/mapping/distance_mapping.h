// DistanceMapping<Real>: SOFA's DistanceMapping<Vec3, Vec1>. Child point i is edge i's extension
// e_i = |x_b - x_a| - L_i (edge (a, b), rest length L_i), a one-coordinate (Vec1) state: its value
// is kept in the x coordinate of the child's Vec3, y and z stay zero, so the child is a
// MechanicalMapping like the others and the states, constraints and outputs that read it know it
// has one coordinate (MappedState::coordinates). J's row i is -uᵀ on a and +uᵀ on b, u the edge's
// unit direction where apply last evaluated it (SOFA's: u = (x_b - x_a) · (1 / |x_b - x_a|), or
// every component 1/√3 for an edge shorter than machine epsilon).
// The geometric stiffness (∂Jᵀ/∂x applied to the child's forces F) is DistanceGeometricStiffness
// below: per edge b_i = (I - u uᵀ) F_i / |x_b - x_a|, +b_i on (a, a) and (b, b), -b_i across.
// Design: docs/mechanical-graph.md ("Vec1 states").
#pragma once

#include "fastcorot/fem/force_field.h"
#include "fastcorot/mapping/mechanical_mapping.h"

#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

// SOFA's geometricStiffness option of nonlinear mappings: None, Exact, or Stabilized (DistanceMapping's
// default: only edges in tension, F < 0, whose stiffness is negative semi-definite).
enum class GeometricStiffnessMethod { none, exact, stabilized };

template <class Real>
class DistanceMapping final : public MechanicalMapping<Real> {
 public:
  // Throws fastcorot::Error for an edge on a negative point, or rest lengths that are not one per
  // edge (empty: measured at `rest`, SOFA's init when computeDistance is false).
  DistanceMapping(std::vector<Edge> edges, std::span<const Vec3<Real>> rest, std::vector<Real> rest_lengths = {});

  std::size_t size() const override { return edges_.size(); }
  Index parent_extent() const override;
  void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) override;
  void positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const override;
  void velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const override;
  void apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const override;
  void apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const override;
  void row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const override;
  std::vector<double> model_values() const override;

  const std::vector<Edge>& edges() const { return edges_; }
  const std::vector<Real>& rest_lengths() const { return rest_lengths_; }

  // An edge's unit direction and inverse length at x (SOFA's DistanceMapping::apply for one edge).
  struct Direction {
    Vec3<Real> u;
    Real inverse_length;
  };
  static Direction direction(const Vec3<Real>& a, const Vec3<Real>& b);

 private:
  std::vector<Edge> edges_;
  std::vector<Real> rest_lengths_;
  std::vector<Vec3<Real>> directions_;  // u of the last apply (J's rows)
};

// The geometric stiffness a DistanceMapping adds to its parent, as a force field on the parent's
// points: no force, the stiffness of the child's forces `child_force` (one per edge, in the x
// coordinate; shared with what sets them: FreeMotionAnimationLoop stores the constraint forces λ/h
// acting on the child, SOFA's λ vector counted in the child's total force). Directions and lengths
// are those at the x of the last add_force (the step's start, where SOFA's mapping last applied).
template <class Real>
class DistanceGeometricStiffness final : public ForceField<Real> {
 public:
  // Throws fastcorot::Error for an edge outside `mesh`'s points or method none.
  DistanceGeometricStiffness(std::shared_ptr<const TetMesh> mesh, std::vector<Edge> edges,
                             std::shared_ptr<const std::vector<Vec3<Real>>> child_force, GeometricStiffnessMethod method);

  std::string component() const override { return "DistanceMapping"; }
  std::string method_name() const override { return "geometric stiffness"; }
  const TetMesh& mesh() const override { return *mesh_; }

  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>>, std::span<Vec3<Real>>) override {}
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  Real potential_energy(std::span<const Vec3<Real>>) const override { return 0; }
  std::vector<Mat3<Real>> rotations() const override { return {}; }
  void check_new_tetrahedra(std::span<const Tetrahedron>) const override {}
  void apply(const TopologyChange&) override {}
  // The child's forces come from the last step's constraint solve, which checkpoints do not keep.
  std::string unsaved_state() const override { return "DistanceMapping's geometric stiffness (the last step's constraint forces)"; }
  std::vector<double> model_values() const override;
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes*) override {}
  std::size_t memory_bytes() const override { return edges_.size() * (sizeof(Edge) + sizeof(Mat3<Real>)); }

 private:
  std::shared_ptr<const TetMesh> mesh_;
  std::vector<Edge> edges_;
  std::shared_ptr<const std::vector<Vec3<Real>>> child_force_;
  GeometricStiffnessMethod method_;
  std::vector<Mat3<Real>> blocks_;  // b_i of the last add_force (zero where the method leaves the edge out)
  int threads_ = 1;
};

}  // namespace fastcorot
