// The mass of one rigid body, SOFA's RigidMass<3> (Sofa/framework/DefaultType/src/sofa/defaulttype/
// RigidMass.h), and how SOFA's UniformMass<Rigid3> gives every rigid of a state the same one
// (Sofa/Component/Mass/src/sofa/component/mass/UniformMass.inl and .cpp, its `.rigid` reader).
//
// Conventions, SOFA's: `inertia` is the inertia matrix per unit mass, in the world frame, and it
// is NOT rotated with the body: M (v, ω) = (m v, m·inertia ω) whatever the orientation. There is
// no gyroscopic term (ω × Iω) anywhere. Gravity acts on the translation only (weight m g, no
// torque). In solver vectors a rigid is two Vec3 blocks [linear, angular] (state/rigid3.h), so
// its 6×6 mass block is block-diagonal: (m I₃, m·inertia).
#pragma once

#include "fastcorot/core/types.h"

#include <optional>
#include <span>
#include <string>

namespace fastcorot {

template <class Real>
struct RigidMass {
  Real mass = 1;                                       // m
  Real volume = 1;                                     // read and kept, used by no force
  Mat3<Real> inertia = Mat3<Real>::Identity();         // per unit mass, world frame

  // SOFA's inertiaMassMatrix: inertia · mass.
  Mat3<Real> inertia_mass() const { return inertia * mass; }
  // The translation part of the weight, m g (the angular part is zero).
  Vec3<Real> weight(const Vec3<Real>& gravity) const { return gravity * mass; }
};

// The two diagonal 3×3 blocks of a rigid's 6×6 mass matrix.
template <class Real>
struct RigidMassBlocks {
  Mat3<Real> linear;   // m I₃
  Mat3<Real> angular;  // m · inertia
};

template <class Real>
RigidMassBlocks<Real> mass_blocks(const RigidMass<Real>& m);

// SOFA's UniformMass<Rigid3>::addMDx: out += factor M dx for every rigid, dx and out as 2 #rigids
// Vec3 blocks [v0, ω0, v1, ω1, ...]. As SOFA, the mass is scaled by factor first:
// out_v += (factor m) dv, out_ω += (factor m·inertia) dω.
template <class Real>
void add_m_dx(const RigidMass<Real>& m, std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor);

// A RigidMass from the text of a `vertexMass` attribute of UniformMass<Rigid3>: "mass volume
// i00 i01 i02 i10 ... i22" (11 numbers, SOFA's RigidMass operator>>). SOFA's stream reader stops
// at the end of a shorter text and keeps the defaults for the rest (volume 1, inertia identity),
// warning that it could not read the whole value; so 1 number (mass) and 2 numbers (mass, volume)
// are taken that way. Other counts, non-finite values and a negative mass throw fastcorot::Error
// naming `where`.
template <class Real>
RigidMass<Real> parse_rigid_mass(std::span<const double> values, const std::string& where);

// What a SOFA `.rigid` file sets (UniformMass.cpp, loadFromFileRigidImpl). Its first line
// (`Xsp 3.0`) is skipped unread; then keywords, each followed by its numbers, across lines:
//   vertexMass m   volm V   inrt (9 numbers, row by row)   cntr|center (3 numbers)
//   frme (4)   grav (3)   visc, stck, step, prec (1 each)   #... (a comment to the end of the line)
// SOFA reads the centre, frame, gravity and solver keys and uses none of them; so does this.
// `mass` is not a keyword there (SOFA reports it as unknown, so does this).
struct RigidFile {
  std::optional<double> vertex_mass;
  std::optional<double> volume;
  std::optional<Mat3<double>> inertia;
  std::optional<Vec3<double>> center;  // not used by SOFA
};

// Reads a `.rigid` file. Throws fastcorot::Error "file:line: ..." for an unknown keyword, a
// missing or malformed or non-finite number, and "file: cannot open" for a missing file.
RigidFile read_rigid_file(const std::string& path);

// Where UniformMass<Rigid3> takes its per-rigid mass from (the attributes as written, the file
// already read). SOFA's init, in order: start from vertexMass (default RigidMass: 1, 1, identity);
// a file overrides the fields it names, and a `vertexMass` in the file counts as a vertexMass
// attribute and discards totalMass when the scene gave no vertexMass; then totalMass, if it is
// (still) set, sets the mass to totalMass / #rigids and keeps the inertia (identity when no
// vertexMass nor file gave one). Neither vertexMass, totalMass nor a file is an error, as SOFA's.
template <class Real>
struct UniformRigidMassInput {
  std::optional<RigidMass<Real>> vertex_mass;  // `vertexMass`
  std::optional<double> total_mass;            // `totalMass`
  std::optional<RigidFile> file;               // `filename`, read
};

// The per-rigid mass of UniformMass<Rigid3> over `rigid_count` rigids (its `indices`, all by
// default). Throws fastcorot::Error naming `where` and the attribute for a negative or non-finite
// mass or totalMass, or for no mass information at all.
template <class Real>
RigidMass<Real> uniform_rigid_mass(const UniformRigidMassInput<Real>& input, Index rigid_count,
                                   const std::string& where);

}  // namespace fastcorot
