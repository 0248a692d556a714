// SOFA's PrecomputedConstraintCorrection (Sofa/Component/Constraint/Lagrangian/Correction,
// PrecomputedConstraintCorrection.inl): the object's compliance C, a dense 3#V × 3#V matrix, is
// computed once at the start and used for every step's W and correction, whatever the object does
// later. SOFA's column for a point and an axis is the velocity after one implicit step from rest
// under a unit force there, times positionIntegrationFactor / dt: with EulerImplicitSolver,
// C = h P A₀⁻¹ P, A₀ = (1 + h r_m) M − h B − h (h + r_k) K at the start positions and P the
// projective constraints' projection. Here C comes from A₀ assembled and factorised (LDLᵀ), exact
// to round-off, where SOFA runs its CG at tolerance 1e-20.
//   W += factor H C Hᵀ, factor 1 (1 / dt in velocity order), from the blocks of C on the points H
//   reaches; SOFA's regularizationTerm is added to a row's diagonal once per point the row
//   touches, as SOFA's loop adds it.
//   correction dx = C Hᵀλ: x = x_free + dx, v = v_free + dx / dt (velocity order: v only).
//   rotations, R each point's rotation from the object's rotation finder (sim/rotation_finder.h):
//   SOFA master turns a copy of H (so W stays H C Hᵀ) and the state's dx vector (since sofa PR
//   #3894). Under its Gauss–Seidel family the correction does not read that vector, so the option
//   changes nothing (Rotations::none, what the scene builder picks, with a warning); under its
//   LCPConstraintSolver the correction is that vector, turned: dx = R C Hᵀλ (Rotations::response).
//   Rotations::both is the exact rotated compliance, W = H R C Rᵀ Hᵀ and dx = R C Rᵀ Hᵀλ, for
//   callers of this class. Design and the cache file: docs/constraints.md.
#pragma once

#include "fastcorot/constraint/constraint_corrections.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace fastcorot {

// Dense C is (3#V)² numbers: refused beyond this many bytes (as doubles).
inline constexpr std::uint64_t kMaxPrecomputedComplianceBytes = std::uint64_t(4) << 30;

// Throws fastcorot::Error, naming `where`, when C for `points` points would exceed the bound (it
// says how many GiB C would take).
void check_precomputed_compliance_size(const std::string& where, std::size_t points);

// C = (position / dt) Δv per unit force = position P A⁻¹ P for the object's system as it stands
// (its force fields linearised at its positions, velocities ignored: A does not depend on them),
// with the ODE solver's integration factors for dt. Throws fastcorot::Error when the ODE solver
// gives no integration factors, the object holds rigid bodies, A cannot be factorised, or C is too
// big.
template <class Real>
DenseMatrix<Real> precompute_compliance(SimulatedObject<Real>& object, Real dt);

// SOFA's cache file name: "<node name>-<3#V>-<dt>.comp", dt written as C++ streams write a double
// by default (0.01, 1e-05).
std::string compliance_file_name(const std::string& node_name, std::size_t rows, double dt);

// SOFA's cache file: the rows × rows numbers of C, row after row, as raw native doubles (SOFA's
// Vec3d Real), nothing else. Reading throws fastcorot::Error naming the file when it cannot be
// opened or does not hold exactly rows² doubles; writing when it cannot be written.
template <class Real>
DenseMatrix<Real> read_compliance_file(const std::filesystem::path& file, std::size_t rows);
template <class Real>
void write_compliance_file(const std::filesystem::path& file, const DenseMatrix<Real>& compliance);

template <class Real>
class PrecomputedConstraintCorrection final : public ConstraintCorrection<Real> {
 public:
  enum class Rotations { none, response, both };  // see above
  struct Parameters {
    Rotations rotations = Rotations::none;
    Real regularization = 0;  // SOFA's `regularizationTerm`
  };
  // `compliance` is C for the whole object (3#V square); throws fastcorot::Error when it is not
  // square or not finite. With rotations, the steps throw when the object has no rotation finder,
  // and both throw when the object no longer has C's size.
  PrecomputedConstraintCorrection(std::string where, std::size_t object, std::shared_ptr<const DenseMatrix<Real>> compliance,
                                  Parameters parameters);
  void add_compliance(SimulatedObject<Real>& object, const Eigen::SparseMatrix<Real>& ht, ConstraintOrder order, Real dt,
                      DenseMatrix<Real>& w) override;
  void correct(SimulatedObject<Real>& object, std::span<const Vec3<Real>> impulse, ConstraintOrder order, Real dt) override;

  const DenseMatrix<Real>& compliance() const { return *compliance_; }
  const Parameters& parameters() const { return parameters_; }

 private:
  // Each point's rotation (rotations), refreshed from the object's force field.
  const std::vector<Mat3<Real>>& rotations(const SimulatedObject<Real>& object);
  void check_size(const SimulatedObject<Real>& object) const;

  std::shared_ptr<const DenseMatrix<Real>> compliance_;
  Parameters parameters_;
  std::vector<Mat3<Real>> rotations_, initial_rotations_;
  std::vector<Index> support_;
  std::vector<Vec3<Real>> local_;
};

}  // namespace fastcorot
