// Penalty forces that push points out of a region, as SOFA's MechanicalLoad defines them: each
// point found outside where it may be is a contact with a unit-free direction n and gets a force;
// the tangent of a contact is -stiffness n n^T (SOFA's addDForce, which leaves the damping out).
// - PlaneForceField: a point with d = x . n - d0 < 0 (or any d when bilateral) gets
//   f = -stiffness d n + damping d v, scaled down to maxForce when it is larger; n as given.
// - ConicalForceField: a point outside the cone of apex `center`, axis `height` and half-angle
//   `angle` (degrees) is pushed back onto it (SOFA's three cases: beyond the base sphere, beside
//   the cone, above the apex), f = stiffness dist dir - damping (dir . v) dir.
// They act on the points of a state, not on elements: mesh() is the object's mesh (for output).
#pragma once

#include "fastcorot/fem/force_field.h"

#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
class PenaltyForceField : public ForceField<Real> {
 public:
  const TetMesh& mesh() const override { return *mesh_; }
  std::string method_name() const override { return "penalty"; }
  void set_velocity(std::span<const Vec3<Real>> v) override { velocity_ = v; }
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override { forces(x, f, true); }
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override { forces(x, f, false); }
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  std::vector<Mat3<Real>> rotations() const override;
  // Points, not elements: topological changes of the mesh leave them as they are.
  void check_new_tetrahedra(std::span<const Tetrahedron>) const override {}
  void apply(const TopologyChange&) override {}
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes* times) override { times_ = times; }
  std::size_t memory_bytes() const override { return contacts_.size() * sizeof(Contact); }

  struct Contact {
    Index point = 0;
    Vec3<Real> normal = Vec3<Real>::Zero();
  };
  // The contacts of the last add_force.
  const std::vector<Contact>& contacts() const { return contacts_; }

 protected:
  // Throws fastcorot::Error for a negative or non-finite stiffness, damping or rayleigh_stiffness.
  PenaltyForceField(std::shared_ptr<const TetMesh> mesh, Real stiffness, Real damping, Real rayleigh_stiffness);
  // Point i at x with velocity v: whether it is in contact, and then its force, contact direction
  // and penetration depth (for the energy).
  virtual bool contact(const Vec3<Real>& x, const Vec3<Real>& v, Vec3<Real>& force, Vec3<Real>& normal, Real& depth) const = 0;

  Real stiffness_, damping_;

 private:
  void forces(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f, bool record);

  std::shared_ptr<const TetMesh> mesh_;
  Real rayleigh_stiffness_;
  std::vector<Contact> contacts_;
  std::span<const Vec3<Real>> velocity_;
  int threads_ = 1;
  PhaseTimes* times_ = nullptr;
};

template <class Real>
class PlaneForceField final : public PenaltyForceField<Real> {
 public:
  struct Parameters {
    Vec3<Real> normal{Real(0), Real(1), Real(0)};
    Real d = 0;
    Real stiffness = 500;
    Real damping = 5;
    Real max_force = 0;  // 0: no limit
    bool bilateral = false;
    Real rayleigh_stiffness = 0;
  };
  PlaneForceField(std::shared_ptr<const TetMesh> mesh, const Parameters& parameters);
  std::string component() const override { return "PlaneForceField"; }
  std::vector<double> model_values() const override;

 private:
  bool contact(const Vec3<Real>& x, const Vec3<Real>& v, Vec3<Real>& force, Vec3<Real>& normal, Real& depth) const override;
  Parameters p_;
};

template <class Real>
class ConicalForceField final : public PenaltyForceField<Real> {
 public:
  struct Parameters {
    Vec3<Real> center = Vec3<Real>::Zero();
    Vec3<Real> height = Vec3<Real>::Zero();
    Real angle = 10;  // degrees
    Real stiffness = 500;
    Real damping = 5;
    Real rayleigh_stiffness = 0;
  };
  // Throws fastcorot::Error for a zero height.
  ConicalForceField(std::shared_ptr<const TetMesh> mesh, const Parameters& parameters);
  std::string component() const override { return "ConicalForceField"; }
  std::vector<double> model_values() const override;

 private:
  bool contact(const Vec3<Real>& x, const Vec3<Real>& v, Vec3<Real>& force, Vec3<Real>& normal, Real& depth) const override;
  bool inside(const Vec3<Real>& x) const;
  Parameters p_;
};

}  // namespace fastcorot
