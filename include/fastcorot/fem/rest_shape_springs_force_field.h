// RestShapeSpringsForceField<Real>: SOFA's RestShapeSpringsForceField on 3D points. Each listed
// point i is pulled towards its anchor p0_i (its rest position, or a point of another state):
//   f_i -= k_i · mask ∘ (x_i - p0_i),
// where mask zeroes the axes that activeDirections turns off, and K is the diagonal -k_i · mask on
// point i (SOFA's addKToMatrix), constant. No damping of its own beyond rayleighStiffness. The
// energy is Σ k_i |mask ∘ (x_i - p0_i)|² / 2 (SOFA reports 0: it does not implement it).
// On rigid bodies (Parameters::rigids set: SOFA's RestShapeSpringsForceField<Rigid3>) the points
// are the rigids' linear blocks, pulled to their rest centres as above, and each rigid is also
// turned back towards its rest orientation q0: with dq = q ⊗ q0⁻¹ (normalised, w ≥ 0) as axis u
// and angle φ (SOFA's quatToAxis), τ -= k_a · mask_r ∘ (φ u) on the angular block; its K is the
// constant diagonal -k_a · mask_r there (SOFA's, no geometric term).
#pragma once

#include "fastcorot/fem/force_field.h"
#include "fastcorot/state/rigid_blocks.h"

#include <array>
#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
class RestShapeSpringsForceField final : public ForceField<Real> {
 public:
  struct Parameters {
    std::vector<Index> points;            // the points pulled (SOFA's default: every point)
    std::vector<Vec3<Real>> anchors;      // one per point: where it is pulled to
    std::vector<Real> stiffness{Real(100)};  // one per point, or one for all (SOFA's rule: k[i] when i < #k, else k[0])
    std::array<bool, 3> active_directions{true, true, true};
    Real rayleigh_stiffness = 0;
    // Rigid bodies only (null otherwise): the rigid of each point (points[i] is its linear block),
    // the angular stiffness (one per point, or SOFA's rule as for stiffness), the rest
    // orientations (one per point) and the rotations' active axes.
    std::shared_ptr<const RigidBlocks<Real>> rigids;
    std::vector<Index> rigid_of_point;
    std::vector<Real> angular_stiffness;
    std::vector<Eigen::Quaternion<Real>> rest_orientations;
    std::array<bool, 3> active_rotations{true, true, true};
    // The anchors are the state's own rest positions (not an external_rest_shape): SOFA reads them
    // at every step, so a script that moves them moves the anchors (follow_rest).
    bool anchors_follow_rest = false;
  };

  // Throws fastcorot::Error for a point outside the mesh's points, as many anchors as points
  // not given, an empty stiffness list, a negative or non-finite stiffness, anchor or rayleigh_stiffness.
  RestShapeSpringsForceField(std::shared_ptr<const TetMesh> mesh, Parameters parameters);

  std::string component() const override { return "RestShapeSpringsForceField"; }
  std::string method_name() const override { return "rest shape springs"; }
  const TetMesh& mesh() const override { return *mesh_; }
  const Parameters& parameters() const { return p_; }

  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override { add_force(x, f); }
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                  Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  std::vector<Mat3<Real>> rotations() const override;

  // The points and anchors are fixed at init: topological changes of the mesh are refused.
  void check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const override;
  void apply(const TopologyChange& change) override;

  // After a script wrote the state's rest positions (the whole state's, and the rigids' rest
  // orientations in Parameters::rigids): the anchors and rest orientations are read again from
  // them when anchors_follow_rest; nothing happens otherwise. Returns whether they were.
  bool follow_rest(std::span<const Vec3<Real>> rest_position) override;

  std::vector<double> model_values() const override;
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes* times) override { times_ = times; }
  std::size_t memory_bytes() const override;

 private:
  Real stiffness(std::size_t i) const { return p_.stiffness[i < p_.stiffness.size() ? i : 0]; }
  Real angular_stiffness(std::size_t i) const { return p_.angular_stiffness[i < p_.angular_stiffness.size() ? i : 0]; }
  // The rotation vector φ u of rigid spring i at positions x, masked.
  Vec3<Real> rotation_offset(std::span<const Vec3<Real>> x, std::size_t i) const;
  // k_a · mask_r as a diagonal matrix.
  Mat3<Real> angular_block(std::size_t i) const;
  // k_i · mask as a diagonal matrix.
  Mat3<Real> block(std::size_t i) const;
  Real factor(Real k_factor, Real b_factor) const { return k_factor + b_factor * p_.rayleigh_stiffness; }

  std::shared_ptr<const TetMesh> mesh_;
  Parameters p_;
  int threads_ = 1;
  PhaseTimes* times_ = nullptr;
};

}  // namespace fastcorot
