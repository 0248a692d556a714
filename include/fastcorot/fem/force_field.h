// ForceField<Real>: what a mechanical system asks of a tetrahedral force field, whichever SOFA
// component it reproduces (FastTetrahedralCorotationalForceField: CorotationalForceField;
// TetrahedronFEMForceField: TetrahedronFEMForceField). Each is defined over one TetMesh and the
// rest positions it was built from; `add_force` computes the forces at x and records the
// linearisation there (rotations and stiffness), which `add_dforce`, `add_stiffness` and
// `add_diagonal_blocks` use until the next `add_force`. Outputs accumulate (they are added to, never
// overwritten). K is df/dx of that linearisation as SOFA assembles it; with b_factor the force
// field's own Rayleigh damping enters as k_factor + b_factor · rayleighStiffness.
#pragma once

#include "fastcorot/core/phase_times.h"
#include "fastcorot/core/types.h"
#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/topology/tet_mesh.h"
#include "fastcorot/topology/topology_change.h"

#include <Eigen/SparseCore>

#include <span>
#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
class ForceField {
 public:
  virtual ~ForceField() = default;

  // The SOFA component this force field reproduces (its scene name).
  virtual std::string component() const = 0;
  // The method as the scene names it (qr, polar, ... for one; small, large, ... for the other).
  virtual std::string method_name() const = 0;
  virtual const TetMesh& mesh() const = 0;

  // Fields whose forces depend on velocities (spring damping) read `v` in the add_force calls that
  // follow (the span must stay valid until then); the others ignore it.
  virtual void set_velocity(std::span<const Vec3<Real>> /*v*/) {}
  virtual void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) = 0;
  // The forces alone: the linearisation stays that of the last add_force (explicit schemes, and
  // measuring what the linearisation costs).
  virtual void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) = 0;
  // df += (k_factor + b_factor · rayleighStiffness) · K · dx.
  virtual void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                          Real b_factor = 0) const = 0;
  // The same linearisation assembled as 3×3 blocks into `sink` at scalar offset `offset`: block
  // (i, j) is (k_factor + b_factor · rayleighStiffness) · df_i/dx_j (SOFA's addKToMatrix: minus
  // the stiffness, so negative semi-definite).
  virtual void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0,
                             Real b_factor = 0) const = 0;
  // diagonal[i] += the block (i, i) that add_stiffness adds.
  virtual void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const = 0;
  // k_factor · df/dx, assembled (3#V × 3#V).
  Eigen::SparseMatrix<Real> stiffness_matrix(Real k_factor = 1) const {
    TripletSink<Real> sink;
    add_stiffness(sink, k_factor);
    return sink.to_sparse(3 * mesh().num_points());
  }

  virtual Real potential_energy(std::span<const Vec3<Real>> x) const = 0;
  // What SOFA does when a time step ends (its AnimateEndEvent), at the step's final positions:
  // outputs that do not feed back into the mechanics (TetrahedronFEMForceField's von Mises stress).
  virtual void end_step(std::span<const Vec3<Real>> /*x*/) {}
  // Per-tetrahedron rotation from the rest frame to the world at the last add_force.
  virtual std::vector<Mat3<Real>> rotations() const = 0;

  // Topological changes of the mesh (which the caller changed): refuse new tetrahedra that the
  // field cannot take (before the mesh changes), then follow a change.
  virtual void check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const = 0;
  virtual void apply(const TopologyChange& change) = 0;

  // What the field carries from step to step that checkpoints do not save ("" when nothing): a run
  // with such a field is not checkpointed rather than resumed wrongly.
  virtual std::string unsaved_state() const { return {}; }
  // Values that define the model (material, method, damping), for checkpoints' fingerprints.
  virtual std::vector<double> model_values() const = 0;
  // A script wrote the state's rest positions (SOFA's rest_position, `rest_position` here the whole
  // state's): a field that reads them at every step in SOFA (RestShapeSpringsForceField) takes them
  // again and returns true; the others keep what they took at init, as SOFA's do.
  virtual bool follow_rest(std::span<const Vec3<Real>> rest_position) {
    static_cast<void>(rest_position);
    return false;
  }

  virtual void set_threads(int threads) = 0;
  virtual int threads() const = 0;
  virtual void set_phase_times(PhaseTimes* times) = 0;
  // Bytes of per-element and per-edge data the field keeps (not counting the mesh).
  virtual std::size_t memory_bytes() const = 0;
  // Whether the field keeps the points in an order of its own (docs/performance.md).
  virtual bool renumbers_points() const { return false; }
};

}  // namespace fastcorot
