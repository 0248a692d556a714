// TetrahedronFEMForceField<Real>: SOFA's TetrahedronFEMForceField, the linear tetrahedron with four
// ways of following rotations (`small`: none; `large`: the frame of the first two edges; `polar`:
// the polar factor of the edge matrix; `svd`: the polar factor, or for an inverted or flat element
// the rotation of a stable SVD). Per tetrahedron it keeps what SOFA keeps: the strain-displacement
// matrix J (12×6, three distinct values per vertex, six times the volume times the shape gradient,
// in the rest frame of the method), the material matrix K (6×6 isotropic, divided by 36 times the
// volume), the rest positions in that frame and the rest rotation. The force of an element is
// R J K J^T D, D being the rest positions minus the current ones in the element's frame; the
// stiffness is SOFA's tangent R J K J^T R^T (no derivative of R), which `add_force` assembles into
// one 3×3 block per point and per mesh edge, so that `add_dforce` is a block-sparse product.
//
// The mathematics differ from FastTetrahedralCorotationalForceField's (SPEC.md) where the two
// components differ in SOFA: here the linearisation point of `large` is the element's first vertex
// and its first edge (forces of the same strain, another rotation), and the stiffness blocks come
// from J K J^T rather than from shape-vector outer products; docs/tetrahedron-fem.md compares them.
// Loops that add into shared arrays follow a ScatterSchedule, so results are bitwise the same on
// any thread count.
#pragma once

#include "fastcorot/core/phase_times.h"
#include "fastcorot/core/types.h"
#include "fastcorot/fem/force_field.h"
#include "fastcorot/fem/tetrahedron_element.h"
#include "fastcorot/topology/scatter_schedule.h"
#include "fastcorot/topology/tet_mesh.h"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

enum class TetrahedronFEMMethod { small, large, polar, svd };

// "small", "large", "polar" or "svd" (SOFA's names); throws fastcorot::Error naming the value.
TetrahedronFEMMethod parse_tetrahedron_fem_method(std::string_view name);
std::string to_string(TetrahedronFEMMethod method);

template <class Real>
class TetrahedronFEMForceField final : public ForceField<Real> {
 public:
  using Mat6 = Eigen::Matrix<Real, 6, 6>;
  using StrainDisplacement = Eigen::Matrix<Real, 12, 6>;

  // Scene attributes of the same names (SOFA's defaults).
  struct Parameters {
    std::vector<Real> young_modulus{Real(5000)};  // one value, or one per tetrahedron
    std::vector<Real> poisson_ratio{Real(0.45)};  // one value, or one per tetrahedron
    TetrahedronFEMMethod method = TetrahedronFEMMethod::large;
    Real rayleigh_stiffness = 0;
    // localStiffnessFactor: M factors; tetrahedron t's E is multiplied by factor[t * M / #T].
    std::vector<Real> local_stiffness_factor;
    // computeVonMisesStress: 0 none, 1 from the corotational strain, 2 from the Green strain.
    int von_mises = 0;
    // The SOFA component reproduced: TetrahedronFEMForceField, or TetrahedralCorotationalFEMForceField,
    // SOFA's older corotational tetrahedron, whose small, large and polar methods compute the same
    // element (the same J, K, rotations and tangent) in the same order of operations.
    std::string component = "TetrahedronFEMForceField";
    // SOFA's plasticity (on when plastic_max_threshold > 0): at each force evaluation the elastic
    // strain e = J^T D - p grows p by creep e when |e| > yield, p is scaled back to norm max when
    // larger, and the force is that of J^T D - p. Defaults as SOFA's (float constants).
    Real plastic_max_threshold = 0;
    Real plastic_yield_threshold = static_cast<Real>(0.0001f);
    Real plastic_creep = static_cast<Real>(0.9f);
    // SOFA's updateStiffnessMatrix (polar and svd): at each force evaluation J is recomputed from
    // the element's current positions in its frame (the rest volume stays in K), and the force and
    // tangent use it. Refused for large, where SOFA updates only some of J's entries.
    bool update_stiffness_matrix = false;
  };

  // What SOFA keeps per tetrahedron, compactly: J holds three distinct values per vertex
  // (gradient[i] = (J(3i,0), J(3i,3), J(3i,5)), six times the volume times vertex i's shape
  // gradient in the element's rest frame) and K three (material = (K(0,0), K(0,1), K(3,3)));
  // strain_displacement() and material_matrix() give SOFA's full matrices. `rotation` maps the
  // element's frame to the world as SOFA's Transformation `rotations[i]` does; `initial_rotation` is
  // its value at rest.
  struct Element {
    std::array<Vec3<Real>, 4> gradient{};
    Vec3<Real> material = Vec3<Real>::Zero();
    std::array<Vec3<Real>, 4> rotated_rest{};     // rest positions in the element's rest frame
    Mat3<Real> initial_rotation = Mat3<Real>::Identity();
    Mat3<Real> rotation = Mat3<Real>::Identity();  // at the last add_force
    Mat3<Real> initial_transformation = Mat3<Real>::Identity();  // svd: the rest edge matrix's inverse
    // The plastic part of the strain J^T D (SOFA's _plasticStrains), updated by every force
    // evaluation when plasticity is on.
    std::array<Real, 6> plastic_strain{};
  };

  // Computes the rest data from `rest_positions`. Throws fastcorot::Error for an empty mesh, a list
  // whose length is neither 1 nor the tetrahedron count, E <= 0, nu outside [0, 0.5), a negative
  // rayleighStiffness or local stiffness factor, computeVonMisesStress outside 0..2, or a
  // degenerate tetrahedron (by index).
  TetrahedronFEMForceField(std::shared_ptr<TetMesh> mesh, std::span<const Vec3<Real>> rest_positions,
                           Parameters parameters);

  std::string component() const override { return parameters_.component; }
  std::string unsaved_state() const override {
    return parameters_.plastic_max_threshold > 0 ? "the plastic strains (plasticMaxThreshold > 0)" : "";
  }
  std::string method_name() const override { return to_string(parameters_.method); }
  const TetMesh& mesh() const override { return *mesh_; }
  const Parameters& parameters() const { return parameters_; }
  const Element& element(Index t) const { return elements_.at(static_cast<std::size_t>(t)); }
  StrainDisplacement strain_displacement(Index t) const;
  Mat6 material_matrix(Index t) const;

  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                  Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;

  // SOFA's getPotentialEnergy for `small` (1/2 D^T J K J^T D summed); for the other methods SOFA
  // returns 0, and this returns the same expression in each element's frame at x.
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  // Rest frame to world: rotation * initial_rotation^T per tetrahedron (identity for small).
  std::vector<Mat3<Real>> rotations() const override;

  // Von Mises stress (computeVonMisesStress 1 or 2) at positions x, as SOFA computes it after each
  // step (and at init): per tetrahedron, and per point the mean over its tetrahedra. Empty when not asked for, or
  // for method small with computeVonMisesStress 1, where SOFA computes none.
  void update_von_mises_stress(std::span<const Vec3<Real>> x);
  void end_step(std::span<const Vec3<Real>> x) override { update_von_mises_stress(x); }
  std::span<const Real> von_mises_per_element() const { return von_mises_element_; }
  std::span<const Real> von_mises_per_node() const { return von_mises_node_; }
  bool computes_von_mises_stress() const;

  void check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const override;
  void apply(const TopologyChange& change) override;
  std::vector<double> model_values() const override;

  void set_threads(int threads) override { threads_ = threads < 1 ? 1 : threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes* times) override { times_ = times; }
  std::size_t memory_bytes() const override;

 private:
  void initialise_element(Index t);
  Real young_modulus_of(Index t) const;
  Real poisson_ratio_of(Index t) const;
  // The elements' schedule and their constants in its order, then lay_out_blocks.
  void schedule();
  // The rows of blocks, each edge's two entries in them and its elements in schedule order
  // (tetrahedron_fem_stiffness_rows.cpp, with the assembly and the product).
  void lay_out_blocks();
  void check_size(std::span<const Vec3<Real>> v, const char* what) const;
  // The element's frame at its points p (world to element, SOFA's R_0_2; identity for small).
  static Mat3<Real> frame(const Element& element, const TetPoints<Real>& p, TetrahedronFEMMethod method);
  // The element's displacement D at its points p in that frame (SOFA's D of the method).
  static std::array<Vec3<Real>, 4> displacement_in_frame(const Element& element, const TetPoints<Real>& p,
                                                         TetrahedronFEMMethod method, const Mat3<Real>& frame);
  // The same, computing the frame into `frame`.
  static std::array<Vec3<Real>, 4> displacement(const Element& element, const TetPoints<Real>& p,
                                                TetrahedronFEMMethod method, Mat3<Real>& frame);
  // body(first, count, points, frames) for the elements at positions [begin, end) of the schedule,
  // in batches of consecutive positions [first, first + count), with their points and frames.
  template <class Body>
  void for_each_batch(Index begin, Index end, std::span<const Vec3<Real>> x, const Body& body) const;
  // body(t, points, frame) for the elements at positions [begin, end) of the schedule, in order.
  template <class Body>
  void for_each_element(Index begin, Index end, std::span<const Vec3<Real>> x, const Body& body) const;
  // Every element's forces into f (batched or element by element); with kLinearise also their
  // rotations and stiffness blocks.
  template <bool kLinearise>
  void accumulate(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f);
  // Whether forces go through the batched kernels (tetrahedron_fem_kernels.h): large, polar and svd
  // without plasticity or updateStiffnessMatrix.
  bool batched() const;
  // The forces of a batch (schedule positions first .. first + count - 1) into f; with kLinearise
  // also each element's rotation and stiffness blocks.
  template <bool kLinearise>
  void accumulate_batch(Index first, Index count, const TetPoints<Real>* points, const Mat3<Real>* frames,
                        std::span<Vec3<Real>> f);
  // Forces of element t at its points p, in its frame, into f; with kLinearise also its rotation.
  template <bool kLinearise>
  void accumulate_element(Index t, const TetPoints<Real>& p, const Mat3<Real>& frame, std::span<Vec3<Real>> f);
  // Element t's w = R g (the gradients in the world) and K's values k1, k2, from its rotation.
  void store_element_stiffness(Index t);
  // The blocks of R J K J^T R^T from each element's w, k1, k2 (assemble_blocks in the .cpp).
  void assemble_blocks();
  void refresh_blocks();
  void ensure_linearisation() const;

  std::shared_ptr<TetMesh> mesh_;
  std::vector<Vec3<Real>> rest_positions_;
  Parameters parameters_;
  bool young_per_tetrahedron_ = false, poisson_per_tetrahedron_ = false;
  std::vector<Element> elements_;
  ScatterSchedule schedule_;
  // What the batched kernels read of each element, in schedule order (positions of schedule_.order),
  // so that a batch reads consecutive memory: rest positions in the rest frame, J's and K's values.
  struct BatchedConstants {
    Real rest[4][3];
    Real gradient[4][3];
    Real material[3];
  };
  std::vector<BatchedConstants> batched_constants_;
  // A 3×3 block as three columns of four values (the fourth zero), aligned: each column one
  // packet, read and added to without shuffles or loads across cache lines.
  struct alignas(4 * sizeof(Real)) PaddedBlock {
    Real value[12];
    Mat3<Real> matrix() const;
  };
  std::vector<PaddedBlock> point_blocks_;  // block (v, v)
  // Row v of the assembled blocks: entries [row_begin_[v], row_begin_[v + 1]) of row_neighbour_
  // (the other point of each mesh edge around v) and row_blocks_ (block (v, neighbour)). Both
  // blocks of an edge are kept, so that the product reads each row straight through.
  std::vector<Index> row_begin_, row_neighbour_;
  std::vector<PaddedBlock> row_blocks_;
  struct alignas(4 * sizeof(Real)) PaddedPoint {  // add_dforce's dx, four values per point
    Real value[4];
  };
  mutable std::vector<PaddedPoint> padded_dx_;
  // What an element's stiffness blocks are made of at the last linearisation, per tetrahedron.
  struct ElementStiffness {
    std::array<Vec3<Real>, 4> w;
    Real k1 = 0, k2 = 0;
  };
  std::vector<ElementStiffness> element_stiffness_;
  // Per mesh edge e, its elements in schedule order: entries [edge_incidence_begin_[e],
  // edge_incidence_begin_[e + 1]) of edge_incidences_, each with its local edge (k, l) and whether
  // that runs along the mesh edge (u, v) (+1) or against it (-1).
  struct EdgeIncidence {
    Index element = 0;
    signed char local_edge = 0, along = 1;
  };
  std::vector<Index> edge_incidence_begin_;
  std::vector<EdgeIncidence> edge_incidences_;
  // Per mesh edge (u, v): the entries of block (u, v) in row u and of block (v, u) in row v.
  std::vector<std::array<Index, 2>> edge_entries_;
  std::vector<Vec3<Real>> last_positions_;
  bool stale_ = false;  // a topological change came after the last add_force
  std::vector<Real> von_mises_element_, von_mises_node_;
  std::vector<Eigen::Matrix<Real, 3, 4>> shape_derivatives_;  // von Mises only; made on first use
  int threads_ = 1;
  PhaseTimes* times_ = nullptr;
};

}  // namespace fastcorot
