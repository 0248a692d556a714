// The mass of SOFA's HexahedronFEMForceFieldAndMass: a HexahedronFEMForceField that is also its
// object's mass. As SOFA computes it (HexahedronFEMForceFieldAndMass::computeElementMass), each
// hexahedron's 24×24 mass matrix couples each corner only with itself along each axis and has one
// value everywhere it is not zero:
//   M_e(3i+c, 3j+c) = V_e · ρ · q(s_i),  i, j = 0..7, c = 0..2,
// with V_e = |n1 - n0| |n3 - n0| |n4 - n0| of its rest corners (in its rest frame) and q(s) SOFA's
// integrateMass of the corner's signs s = (sx, sy, sz) = ±1, which SOFA evaluates with corner i's
// signs for every j (so q = 8/27 throughout). lumpedMass replaces the matrix by its row sums.
// Gravity does not act through that matrix: each hexahedron gives each of its corners
// ρ |n1 - n0| |n3 - n0| |n4 - n0| / 8 of weight (SOFA's _particleMasses, from the world rest positions).
#pragma once

#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/sim/mass.h"

#include <span>

namespace fastcorot {

// SOFA's integrateMass(sx, sy, sz) / density.
template <class Real>
Real hexahedron_mass_integral(int sx, int sy, int sz);

// The mass (consistent, or lumped) of `field`'s hexahedra with rest positions `rest`, density
// `density`; its gravity masses as above. Throws fastcorot::Error for a density that is not finite
// and > 0 (HexahedronFEMForceFieldAndMass's `density`) or `rest` of the wrong size.
template <class Real>
Mass<Real> hexahedron_fem_mass(const HexahedronFEMForceField<Real>& field, std::span<const Vec3<Real>> rest, Real density,
                               bool lumped);

}  // namespace fastcorot
