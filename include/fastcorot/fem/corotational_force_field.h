// CorotationalForceField<Real>: SOFA's FastTetrahedralCorotationalForceField over a whole
// tetrahedral mesh (SPEC.md). It owns the rest data of every tetrahedron and the linearisation of
// the last `add_force` call: one 3×3 stiffness block per mesh edge, which `add_dforce` and the
// matrix assembly reuse until the next `add_force`. Vertex arrays are spans of #V points (Vec3);
// forces accumulate into the output (they are added, never overwritten).
//
// How it is fast (docs/performance.md): each tetrahedron keeps only its shape vectors expressed in
// the rest frame of its rotation method and its scaled Lamé values (structure of arrays); one pass
// per add_force computes the rotation, the forces and the rotated edge blocks together, so no
// rotation is stored; edge blocks are kept oriented from the lower to the higher vertex index and
// applied in vertex order. Loops that scatter into shared arrays follow a ScatterSchedule, so any
// thread count gives bitwise the same results. The straightforward element-by-element form of the
// same computation (tetrahedron_element.h) is what the tests compare against.
//
// One object is not to be called from several threads at once (even its const members keep scratch
// and linearisation state); its own threads are set_threads'.
#pragma once

#include "fastcorot/core/phase_times.h"
#include "fastcorot/core/types.h"
#include "fastcorot/fem/force_field.h"
#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/fem/rotation_method.h"
#include "fastcorot/fem/tetrahedron_element.h"
#include "fastcorot/topology/scatter_schedule.h"
#include "fastcorot/topology/tet_mesh.h"
#include "fastcorot/topology/topology_change.h"

#include <Eigen/SparseCore>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
class CorotationalForceField final : public ForceField<Real> {
 public:
  // Scene attributes of the same names. youngModulus and poissonRatio hold one value for every
  // tetrahedron or one value per tetrahedron.
  struct Parameters {
    std::vector<Real> young_modulus{Real(5000)};
    std::vector<Real> poisson_ratio{Real(0.45)};
    RotationMethod method = RotationMethod::qr;
    Real rayleigh_stiffness = 0;
  };

  // Computes the rest data from `rest_positions` (#V points). Throws fastcorot::Error for an empty
  // mesh, a parameter list whose length is neither 1 nor the tetrahedron count, E <= 0, nu outside
  // [0, 0.5), a negative or non-finite rayleighStiffness, or a degenerate tetrahedron (by index).
  CorotationalForceField(std::shared_ptr<TetMesh> mesh, std::span<const Vec3<Real>> rest_positions,
                         Parameters parameters);

  std::string component() const override { return "FastTetrahedralCorotationalForceField"; }
  std::string method_name() const override { return to_string(parameters_.method); }
  const TetMesh& mesh() const override { return *mesh_; }
  const Parameters& parameters() const { return parameters_; }
  RotationMethod method() const { return parameters_.method; }

  // f += forces at positions x (#V points each); rebuilds the edge stiffness blocks used by
  // add_dforce and the assembly (the linearisation at x).
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;

  // f += forces at x without touching the linearisation (for explicit schemes and for measuring
  // what the stiffness refresh costs inside add_force).
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;

  // df += K(x_last) dx · (k_factor + b_factor · rayleighStiffness), K = df/dx as SPEC assembles it
  // from the edge blocks of the last add_force (rest state before the first one).
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                  Real b_factor = 0) const override;

  // Adds (k_factor + b_factor · rayleighStiffness) · df/dx into `sink`, block (i, j) at scalar row
  // offset + 3i and column offset + 3j.
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;

  // diagonal[v] += the (v, v) block of (k_factor + b_factor · rayleighStiffness) · df/dx, for every
  // point v (one block per point of the mesh): the diagonal blocks add_stiffness assembles, with the
  // same bits, for block-Jacobi preconditioning. Throws fastcorot::Error for a wrong size.
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;

  // Sum over tetrahedra of U_t = -1/2 sum_j u_j . g_j at positions x (rotations taken at x).
  // SOFA returns 0 here; this is the energy whose gradient is -f for `none`.
  Real potential_energy(std::span<const Vec3<Real>> x) const override;

  // Switches the rotation method; recomputes the rest rotations and resets the linearisation to
  // the rest state.
  void set_method(RotationMethod method);

  // Topological changes (cutting), at a cost proportional to the change (docs/cutting.md): new
  // tetrahedra get their rest data from the rest positions and entry 0 of per-tetrahedron E and nu
  // lists, removed ones take their data with them (swap-with-last, as the mesh), and the edge
  // blocks are rebuilt at the last linearisation positions when next needed.
  //
  // Throws fastcorot::Error (nothing changed) when a tetrahedron to add has a vertex out of range or
  // a (near) zero rest volume.
  void check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const override;
  // Follows a change just made to the shared mesh (every change, in order, before any other call).
  void apply(const TopologyChange& change) override;
  // Changes the shared mesh and follows (for a mesh no one else holds data on).
  TopologyChange add_tetrahedra(std::span<const Tetrahedron> tetrahedra);
  TopologyChange remove_tetrahedra(std::span<const Index> indices);

  // Recomputes the edges of each tetrahedron and their orientations from the mesh, then the edge
  // blocks (SOFA's updateTopologyInformation).
  void update_topology_information();

  // Rotation of each tetrahedron (rest frame to world) at the positions of the last add_force
  // (identity before the first); computed on demand.
  std::vector<Mat3<Real>> rotations() const override;
  // Signed rest volume V of each tetrahedron (SOFA's sign convention).
  std::vector<Real> rest_volumes() const;
  // Stiffness block K_E of each mesh edge, oriented as the mesh edge (SPEC.md, "Stiffness").
  std::vector<Mat3<Real>> edge_stiffness() const;

  // Threads for add_force, add_dforce and add_stiffness; results do not depend on it.
  void set_threads(int threads) override { threads_ = threads < 1 ? 1 : threads; }
  int threads() const override { return threads_; }
  // Where add_force adds its time (null: not timed).
  void set_phase_times(PhaseTimes* times) override { times_ = times; }

  // Bytes held by the force field (rest data, edge blocks, schedules, last positions, add_dforce's
  // padded points once it has run), not counting the shared mesh.
  std::size_t memory_bytes() const override;

  // E list, nu list, the method and rayleighStiffness, in that order.
  std::vector<double> model_values() const override;

  // Whether the force field keeps the points in an order of its own, because the mesh's numbering
  // is scattered (docs/performance.md); results are the same up to rounding either way.
  bool renumbers_points() const override { return !internal_point_.empty(); }

 private:
  void rebuild();
  template <bool kRefresh>
  void accumulate_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) const;
  // Recomputes the edge blocks at the last add_force's positions (rest before any) after a
  // topological change or a rebuild; called by everything that reads them.
  void ensure_linearisation() const;
  void set_rest_data(Index t);
  void place_tetrahedron(Index t);
  Index place_edge(const Edge& edge);
  bool schedules_degraded() const;
  void check_size(std::span<const Vec3<Real>> v, const char* what) const;
  void pad(const Real* from, Real scale, Real* to, Real* zeroed) const;
  void unpad(const Real* padded, Real* to) const;
  TetrahedronRest<Real> element_rest(Index t) const;

  std::shared_ptr<TetMesh> mesh_;
  std::vector<Vec3<Real>> rest_positions_;
  Parameters parameters_;
  // Whether youngModulus / poissonRatio hold one value per tetrahedron (they then follow the
  // tetrahedra, down to no value at all), and the values tetrahedra added later take (entry 0 at
  // construction).
  bool young_per_tetrahedron_ = false, poisson_per_tetrahedron_ = false;
  Real added_young_ = 0, added_poisson_ = 0;
  int threads_ = 1;
  PhaseTimes* times_ = nullptr;

  // Per tetrahedron, kept by its position in tetrahedron_schedule_.order (whose groups start at
  // multiples of the kernels' batch width W, so that a batch's data is one block): shape vectors
  // s~_1..s~_3 in the method's rest frame (R0 s_j; s~_0 = -(s~_1 + s~_2 + s~_3)), nine values, then
  // mu |V| and lambda |V|: kRestValues rows of W values per block of W positions (rest_index).
  // Positions that hold no tetrahedron hold finite leftovers (a batch's spare lanes read them).
  static constexpr std::size_t kRestValues = 11;
  std::vector<Real> rest_;
  std::size_t rest_index(std::size_t position, std::size_t value) const;
  void move_rest_data(std::size_t from, std::size_t to);
  ScatterSchedule tetrahedron_schedule_;
  std::vector<Index> position_;  // position of each tetrahedron in tetrahedron_schedule_.order
  // Edges are stored in the order of their schedule (grouped like the tetrahedra, sorted by lower
  // then higher vertex within a group), so add_dforce streams through memory: edge_slot_ gives the
  // slot of each mesh edge, edge_vertices_ the (lower, higher) vertices of each slot, and blocks_
  // the K_E of each slot oriented from the lower to the higher vertex (column-major 3×3, nine
  // values per slot, then kernels::kBlockTail spare zeros). Slots of removed edges stay where they
  // are (zero blocks) and go to their group's free list, for edges added later.
  ScatterSchedule edge_schedule_;  // in slots
  std::vector<Index> edge_slot_;
  std::vector<Edge> edge_vertices_;
  std::vector<std::vector<Index>> free_slots_;  // per edge group
  Index num_free_slots_ = 0;
  mutable std::vector<Real> blocks_;
  mutable bool stale_ = true;  // blocks_ do not hold the linearisation yet
  // add_dforce's points padded to four values, aligned for SIMD loads (k dx, and the edge terms
  // before they join df).
  struct alignas(4 * sizeof(Real)) PaddedPoint {
    Real value[4];
  };
  mutable std::vector<PaddedPoint> packed_in_, packed_out_;
  Mat3<Real> block(Index slot) const;
  std::vector<Vec3<Real>> last_positions_;  // x of the last add_force (empty before the first)

  // The force field's own point numbering: when the mesh's numbering is scattered (its edges'
  // points 8 times as far apart on average as in a reverse Cuthill–McKee order), the padded points,
  // the edge slots and the schedules follow that order instead, so that an element's points sit
  // close together in memory; empty when the mesh's own numbering serves. Chosen at construction.
  std::vector<Index> internal_point_;  // internal index of each mesh point
  std::vector<Index> mesh_point_;      // mesh point of each internal index
  void choose_point_order();
  Index internal(Index point) const {
    return internal_point_.empty() ? point : internal_point_[static_cast<std::size_t>(point)];
  }
  Index mesh_point(Index point) const {
    return mesh_point_.empty() ? point : mesh_point_[static_cast<std::size_t>(point)];
  }
  Tetrahedron internal(const Tetrahedron& tet) const {
    return {internal(tet[0]), internal(tet[1]), internal(tet[2]), internal(tet[3])};
  }
  // A mesh edge as its slot holds it: internal numbers, the lower first.
  Edge slot_edge(const Edge& edge) const {
    const Index a = internal(edge[0]), b = internal(edge[1]);
    return {std::min(a, b), std::max(a, b)};
  }
};

}  // namespace fastcorot
