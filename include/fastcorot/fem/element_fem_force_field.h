// ElementFEMForceField<Real, N>: SOFA's new element force fields (master's
// CorotationalFEMForceField and LinearSmallStrainFEMForceField, templates Vec3,Tetrahedron (N = 4)
// and Vec3,Hexahedron (N = 8)). Each element keeps the 3N × 3N linear elastic stiffness K of its rest
// shape (finite_element.h: SOFA's quadrature, strain-displacement and isotropic C).
//   - LinearSmallStrainFEMForceField: f_e = K (x - x0), df_e = K dx.
//   - CorotationalFEMForceField: a rotation R per element (rest -> current) from the element's
//     corners; with the centroids t of x and t0 of x0, d_j = R^T (x_j - t) - (x0_j - t0),
//     f_e = R K d (R applied per corner) and the tangent R K R^T (no derivative of R), as SOFA.
//     R by rotationMethod: `triangle` (tetrahedra's default: the frame of corners 0, 1, 2,
//     x = e01/|e01|, z = x × e02 normalised, y = z × x, so R = F^T F0), `hexahedron` (hexahedra's
//     default: the same Gram-Schmidt on the mean x and y edges), `polar` (the polar factor of
//     sum_j (x_j - t)(x0_j - t0)^T, SOFA's Decompose::polarDecomposition), `stable_polar`
//     (Decompose::polarDecomposition_stable of the same matrix) or `identity`.
// Node forces are f_i -= sum of the elements' corner forces, df_i -= k (K_e dx)_i, with
// k = k_factor + b_factor · rayleighStiffness. Element terms are computed on the threads (whatever
// SOFA's computeForceStrategy says), then added to the nodes in element order, so that results are
// bitwise the same for any thread count, as SOFA's sequenced and parallel strategies are. Potential
// energy is 1/2 d^T K d summed over the elements (SOFA reports 0).
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/fem/force_field.h"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

enum class ElementRotationMethod { none, identity, triangle, hexahedron, polar, stable_polar };

// SOFA's rotationMethod names: stable_polar, polar, identity, and triangle (N = 4) or hexahedron
// (N = 8). Throws fastcorot::Error naming the value and the accepted names.
ElementRotationMethod parse_element_rotation_method(std::string_view name, int nodes_per_element);
std::string to_string(ElementRotationMethod method);

template <class Real, int N>
class ElementFEMForceField final : public ForceField<Real> {
 public:
  static_assert(N == 4 || N == 8);
  using Element = std::array<Index, N>;
  using ElementStiffness = Eigen::Matrix<Real, 3 * N, 3 * N>;
  using ElementVector = Eigen::Matrix<Real, 3 * N, 1>;

  struct Parameters {
    std::vector<Real> young_modulus{Real(5000)};  // one value, or one per element
    std::vector<Real> poisson_ratio{Real(0.45)};  // one value, or one per element; in [0, 0.5)
    // none: LinearSmallStrainFEMForceField; any other: CorotationalFEMForceField.
    ElementRotationMethod method = N == 4 ? ElementRotationMethod::triangle : ElementRotationMethod::hexahedron;
    Real rayleigh_stiffness = 0;
  };

  // `drawn` is the tetrahedral mesh the field reports (the tetrahedra themselves for N = 4; six per
  // hexahedron for N = 8). Throws fastcorot::Error for an index outside [0, num_points), material
  // lists of the wrong length or values out of range, or a flat element (naming it).
  ElementFEMForceField(std::shared_ptr<TetMesh> drawn, std::vector<Element> elements, std::span<const Vec3<Real>> rest,
                       Parameters parameters);

  std::string component() const override;
  std::string method_name() const override { return to_string(parameters_.method); }
  const TetMesh& mesh() const override { return *drawn_; }
  std::span<const Element> elements() const { return elements_; }
  const ElementStiffness& element_stiffness(Index e) const { return stiffness_[static_cast<std::size_t>(e)]; }
  // R of element e at the last add_force (rest frame -> world; identity before).
  const Mat3<Real>& rotation(Index e) const { return rotation_[static_cast<std::size_t>(e)]; }

  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                  Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  std::vector<Mat3<Real>> rotations() const override;

  void check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const override;
  void apply(const TopologyChange& change) override;

  std::vector<double> model_values() const override;
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes* times) override { times_ = times; }
  std::size_t memory_bytes() const override;

 private:
  // R of element e at x (identity for none and identity).
  Mat3<Real> element_rotation(std::span<const Vec3<Real>> x, std::size_t e) const;
  // The element's corner forces (before the minus sign of the scatter) and its d.
  ElementVector element_force(std::span<const Vec3<Real>> x, std::size_t e, const Mat3<Real>& R) const;
  void forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record);
  Real factor(Real k_factor, Real b_factor) const { return k_factor + b_factor * parameters_.rayleigh_stiffness; }

  std::shared_ptr<TetMesh> drawn_;
  std::vector<Element> elements_;
  std::vector<Vec3<Real>> rest_;
  Parameters parameters_;
  std::vector<ElementStiffness> stiffness_;
  std::vector<Mat3<Real>> rest_frame_;  // F0 (frame rows at rest) for triangle and hexahedron
  std::vector<Mat3<Real>> rotation_;
  mutable std::vector<ElementVector> element_terms_;  // per-element forces or dforces before the scatter
  int threads_ = 1;
  PhaseTimes* times_ = nullptr;
};

// The frame SOFA's TriangleRotation (N = 4: corners 0, 1, 2) or HexahedronRotation (N = 8: mean x
// and y edges) builds: rows x, y, z.
template <class Real, int N>
Mat3<Real> element_frame(const std::array<Vec3<Real>, N>& corners);

}  // namespace fastcorot
