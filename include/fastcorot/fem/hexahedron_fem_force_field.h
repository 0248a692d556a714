// HexahedronFEMForceField<Real>: SOFA's HexahedronFEMForceField, the trilinear hexahedron (eight
// points in SOFA's order: the bottom face counter-clockwise from point 0, then the top face) with
// three ways of following rotations: `small` (none), `large` (the frame of the mean x and y edges,
// Gram-Schmidt), `polar` (the polar factor of the mean edge matrix). Per hexahedron it keeps what
// SOFA keeps: the 24×24 stiffness K of the rest shape in the element's rest frame (8-point Gauss
// quadrature of B^T C B det J, SOFA's generic path, isotropic C of (E, nu)), the rest positions in
// that frame and the rotation. The force is R^T K (rest - R x) per element and the tangent SOFA's
// R^T K R (no derivative of R). Elements run in order (results are bitwise those of one thread).
// The hexahedra cannot change (cutting refuses them). docs/sofa-components.md has the formulas.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/fem/force_field.h"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace fastcorot {

using Hexahedron = std::array<Index, 8>;

enum class HexahedronFEMMethod { small, large, polar };

// "small", "large" or "polar"; throws fastcorot::Error naming the value.
HexahedronFEMMethod parse_hexahedron_fem_method(std::string_view name);

// SOFA's Hexahedron::volume: the sum of six tetrahedra's unsigned volumes (corners 0-5-1-6, 0-1-3-6,
// 1-3-6-2, 6-3-0-7, 6-7-0-5, 7-5-4-0). These six tetrahedra are also how the hexahedra are drawn.
template <class Real>
Real hexahedron_volume(std::span<const Vec3<Real>> points, const Hexahedron& h);
std::vector<Tetrahedron> hexahedra_tetrahedra(std::span<const Hexahedron> hexahedra);

template <class Real>
class HexahedronFEMForceField final : public ForceField<Real> {
 public:
  using ElementStiffness = Eigen::Matrix<Real, 24, 24>;

  struct Parameters {
    std::vector<Real> young_modulus{Real(5000)};  // one value, or one per hexahedron
    std::vector<Real> poisson_ratio{Real(0.45)};  // one value, or one per hexahedron
    HexahedronFEMMethod method = HexahedronFEMMethod::large;
    Real rayleigh_stiffness = 0;
  };

  // Throws fastcorot::Error for an index outside [0, num_points), a repeated point, a list of
  // material values of the wrong length or out of range, or a flat hexahedron (det J <= 0 at a
  // Gauss point, naming it).
  HexahedronFEMForceField(Index num_points, std::vector<Hexahedron> hexahedra, std::span<const Vec3<Real>> rest,
                          Parameters parameters);

  std::string component() const override { return "HexahedronFEMForceField"; }
  std::string method_name() const override;
  // The hexahedra as six tetrahedra each (hexahedra_tetrahedra), for drawing and output.
  const TetMesh& mesh() const override { return *drawn_; }
  std::shared_ptr<TetMesh> drawn_mesh() const { return drawn_; }
  std::span<const Hexahedron> hexahedra() const { return hexahedra_; }
  const ElementStiffness& element_stiffness(Index h) const { return stiffness_[static_cast<std::size_t>(h)]; }
  // Hexahedron h's rest corners in its rest frame (SOFA's _rotatedInitialElements).
  const std::array<Vec3<Real>, 8>& rest_in_frame(Index h) const { return rest_in_frame_[static_cast<std::size_t>(h)]; }
  // R of hexahedron h at the last add_force: element frame = R · world.
  const Mat3<Real>& rotation(Index h) const { return rotation_[static_cast<std::size_t>(h)]; }

  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                  Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  // SOFA's m_potentialEnergy at x: the sum over elements of D . K D / 2.
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  // R^T (element frame to world) of each drawn tetrahedron's hexahedron.
  std::vector<Mat3<Real>> rotations() const override;

  void check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const override;
  void apply(const TopologyChange& change) override;

  std::vector<double> model_values() const override;
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes* times) override { times_ = times; }
  std::size_t memory_bytes() const override;

 private:
  Mat3<Real> element_rotation(std::span<const Vec3<Real>> x, const Hexahedron& h) const;
  // R of element e at x (its rest rotation for small), and D = rest corners in the frame - R x.
  Mat3<Real> current_rotation(std::span<const Vec3<Real>> x, std::size_t e) const;
  Eigen::Matrix<Real, 24, 1> displacement(std::span<const Vec3<Real>> x, std::size_t e, const Mat3<Real>& R) const;
  // Forces at x; records the rotations when `record`.
  void forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record);
  Real factor(Real k_factor, Real b_factor) const { return k_factor + b_factor * parameters_.rayleigh_stiffness; }

  std::vector<Hexahedron> hexahedra_;
  Parameters parameters_;
  std::shared_ptr<TetMesh> drawn_;
  std::vector<ElementStiffness> stiffness_;
  std::vector<std::array<Vec3<Real>, 8>> rest_in_frame_;  // SOFA's _rotatedInitialElements
  std::vector<Mat3<Real>> rotation_;
  int threads_ = 1;
  PhaseTimes* times_ = nullptr;
};

// The element stiffness SOFA's computeElementStiffness computes (GENERIC_STIFFNESS_MATRIX,
// MAT_STIFFNESS_USE_W, DN_USE_J) for the hexahedron with corners `nodes` and material values
// (U, V, W) = C(0,0), C(0,1), C(3,3); throws fastcorot::Error when det J <= 0 at a Gauss point.
template <class Real>
Eigen::Matrix<Real, 24, 24> hexahedron_element_stiffness(const std::array<Vec3<Real>, 8>& nodes, Real u, Real v, Real w);

}  // namespace fastcorot
