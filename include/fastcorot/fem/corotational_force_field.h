// CorotationalForceField<Real>: SOFA's FastTetrahedralCorotationalForceField over a whole
// tetrahedral mesh (SPEC.md). It owns the rest data of every tetrahedron (shape vectors, scaled Lamé
// values, rest rotation) and the linearisation of the last `add_force` call: one rotation per
// tetrahedron and one 3×3 stiffness block per mesh edge, which `add_dforce` and the matrix assembly
// reuse until the next `add_force`. Vertex arrays are spans of #V points (Vec3); forces accumulate
// into the output (they are added, never overwritten).
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/fem/rotation_method.h"
#include "fastcorot/fem/tetrahedron_element.h"
#include "fastcorot/topology/tet_mesh.h"

#include <Eigen/SparseCore>

#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
class CorotationalForceField {
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

  const TetMesh& mesh() const { return *mesh_; }
  const Parameters& parameters() const { return parameters_; }
  RotationMethod method() const { return parameters_.method; }

  // f += forces at positions x (#V points each); records each tetrahedron's rotation and rebuilds
  // the edge stiffness blocks used by add_dforce and the assembly.
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f);

  // df += K(x_last) dx · (k_factor + b_factor · rayleighStiffness), K = df/dx as SPEC assembles it
  // from the edge blocks of the last add_force (rest state before the first one).
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor,
                  Real b_factor = 0) const;

  // Adds (k_factor + b_factor · rayleighStiffness) · df/dx into `sink`, block (i, j) at scalar row
  // offset + 3i and column offset + 3j.
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const;

  // The 3#V × 3#V matrix k_factor · df/dx (row = 3 · vertex + axis).
  Eigen::SparseMatrix<Real> stiffness_matrix(Real k_factor = 1) const;

  // Sum over tetrahedra of U_t = -1/2 sum_j u_j . g_j at positions x (rotations taken at x).
  // SOFA returns 0 here; this is the energy whose gradient is -f for `none`.
  Real potential_energy(std::span<const Vec3<Real>> x) const;

  // Switches the rotation method; recomputes the rest rotations and resets the linearisation to
  // the rest state.
  void set_method(RotationMethod method);

  // Adds tetrahedra over existing points (their rest data computed from the rest positions; their
  // E and nu are entry 0 of the parameter lists) and removes tetrahedra by index (per-tetrahedron
  // data follows). The shared mesh is modified; edge blocks are rebuilt.
  void add_tetrahedra(std::span<const Tetrahedron> tetrahedra);
  void remove_tetrahedra(std::span<const Index> indices);

  // Recomputes the edges of each tetrahedron and their orientations from the mesh, then the edge
  // blocks (SOFA's updateTopologyInformation).
  void update_topology_information();

  // Rotation of each tetrahedron at the last add_force (identity before the first).
  std::span<const Mat3<Real>> rotations() const { return rotations_; }
  // Signed rest volume V of each tetrahedron (SOFA's sign convention).
  std::vector<Real> rest_volumes() const;
  std::span<const TetrahedronRest<Real>> rest_data() const { return rest_; }
  // Stiffness block K_E of each mesh edge (SPEC.md, "Stiffness").
  std::span<const Mat3<Real>> edge_stiffness() const { return edge_stiffness_; }

 private:
  TetrahedronRest<Real> compute_rest(Index t) const;
  void rebuild_edge_stiffness();
  void check_size(std::span<const Vec3<Real>> v, const char* what) const;

  std::shared_ptr<TetMesh> mesh_;
  std::vector<Vec3<Real>> rest_positions_;
  Parameters parameters_;
  std::vector<LameParameters<Real>> lame_;  // per tetrahedron
  std::vector<TetrahedronRest<Real>> rest_;
  std::vector<Mat3<Real>> rotations_;
  std::vector<Mat3<Real>> edge_stiffness_;
};

}  // namespace fastcorot
