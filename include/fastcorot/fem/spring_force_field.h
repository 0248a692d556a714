// SpringForceField<Real>: SOFA's SpringForceField between points of one object, and the springs
// SOFA's MeshSpringForceField makes from a mesh. A spring (a, b) of stiffness ks, damping kd and
// rest length L gives, with u = x_b - x_a, d = |u|, U = u / d and the relative velocity w = v_b - v_a,
//   f = (ks (d - L) + kd (U . w)) U   on a, and -f on b,
// and records the tangent dF/dX = (ks - f/d) U U^T + (f/d) I, which add_dforce and add_stiffness
// use (SOFA's linearisation: the damping force enters through f, its velocity derivative not at
// all). A spring shorter than 1e-9, compressed with elongation_only, or not enabled, gives no force
// and no tangent. The springs may join points of several objects merged into one system
// (merged_objects.h): SOFA's interaction springs between object1 and object2 are the same springs
// on the merged indices.
#pragma once

#include "fastcorot/fem/force_field.h"

#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
struct Spring {
  Index a = 0;
  Index b = 0;
  Real stiffness = 0;
  Real damping = 0;
  Real rest_length = 0;
  bool elongation_only = false;
  bool enabled = true;  // SOFA's `enabled`: false for a broken spring
};

// MeshSpringForceField's stiffnesses and dampings per kind of element (SOFA's names without the
// suffixes); only the edges and the tetrahedra of a tetrahedral mesh are used here.
template <class Real>
struct MeshSpringParameters {
  Real lines_stiffness = 0, lines_damping = 0;
  Real triangles_stiffness = 0, triangles_damping = 0;
  Real quads_stiffness = 0, quads_damping = 0;
  Real tetrahedra_stiffness = 0, tetrahedra_damping = 0;
  Real cubes_stiffness = 0, cubes_damping = 0;
  bool no_compression = false;
};

// The element lists of MeshSpringForceField's topology (SOFA's getLine, getTriangle, ...).
struct SpringTopology {
  std::vector<Edge> lines;
  std::vector<Triangle> triangles;
  std::vector<std::array<Index, 4>> quads;
  std::vector<Tetrahedron> tetrahedra;
  std::vector<std::array<Index, 8>> hexahedra;
};

// The springs of MeshSpringForceField::init: for each kind whose stiffness or damping is not zero,
// in the order lines, triangles, quads, tetrahedra, cubes (hexahedra), every vertex pair of each
// element (pairs (k, j), k < j, in that order) that is not a spring yet; each spring's rest length
// is the distance at `rest`, its stiffness and damping divided by that length (when it exceeds
// machine epsilon).
template <class Real>
std::vector<Spring<Real>> mesh_springs(const SpringTopology& topology, std::span<const Vec3<Real>> rest,
                                       const MeshSpringParameters<Real>& parameters);
// The same on a tetrahedral mesh: its edges, SOFA's triangle array of its tetrahedra, its tetrahedra.
template <class Real>
std::vector<Spring<Real>> mesh_springs(const TetMesh& mesh, std::span<const Vec3<Real>> rest,
                                       const MeshSpringParameters<Real>& parameters);

template <class Real>
class SpringForceField final : public ForceField<Real> {
 public:
  // Throws fastcorot::Error for an index outside the mesh's points, a point paired with itself,
  // a negative or non-finite stiffness, damping, rest length or rayleigh_stiffness.
  SpringForceField(std::shared_ptr<const TetMesh> mesh, std::vector<Spring<Real>> springs,
                   Real rayleigh_stiffness = 0, std::string component = "SpringForceField");

  std::string component() const override { return component_; }
  std::string method_name() const override { return "springs"; }
  // Only the first `count` springs enter add_stiffness and add_diagonal_blocks (the rest act
  // through add_force and add_dforce alone): SOFA's RegularGridSpringForceField computes its grid's
  // springs in addForce/addDForce but assembles only its listed springs (SpringForceField's
  // addKToMatrix/buildStiffnessMatrix). Throws fastcorot::Error when count > springs().size().
  void set_assembled_springs(std::size_t count);
  const TetMesh& mesh() const override { return *mesh_; }
  const std::vector<Spring<Real>>& springs() const { return springs_; }

  void set_velocity(std::span<const Vec3<Real>> v) override { velocity_ = v; }
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                  Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  std::vector<Mat3<Real>> rotations() const override;

  // The springs are fixed at init, as SOFA's MeshSpringForceField does not follow a changing mesh:
  // any topological change of the mesh is refused.
  void check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const override;
  void apply(const TopologyChange& change) override;

  std::vector<double> model_values() const override;
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes* times) override { times_ = times; }
  std::size_t memory_bytes() const override;

 private:
  void forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record);
  Real factor(Real k_factor, Real b_factor) const { return k_factor + b_factor * rayleigh_stiffness_; }

  std::shared_ptr<const TetMesh> mesh_;
  std::vector<Spring<Real>> springs_;
  std::vector<Mat3<Real>> tangent_;  // dF/dX per spring at the last add_force
  std::size_t assembled_ = 0;         // springs [0, assembled_) enter the assembled matrix
  Real rayleigh_stiffness_ = 0;
  std::string component_;
  std::span<const Vec3<Real>> velocity_;
  int threads_ = 1;
  PhaseTimes* times_ = nullptr;
};

}  // namespace fastcorot
