// The rotation of each point that SOFA's TetrahedronFEMForceField reports to the components that
// ask for one (its RotationFinder, read by the warp preconditioners): the mean, over the
// tetrahedra that hold the point, of each element's rotation from its rest frame, R_e R0_e^T.
// SOFA computes the polar factor of that mean and leaves it unused, so the mean itself is what it
// reports, and so it is here.
#pragma once

#include "fastcorot/fem/force_field.h"

#include <vector>

namespace fastcorot {

// One 3×3 block per point of a state of `points` points: the mean of field.rotations() over the
// tetrahedra of field.mesh() that hold the point (identity for a point in none). Throws
// fastcorot::Error when the mesh names a point outside [0, points) or the rotations are not one
// per tetrahedron.
template <class Real>
std::vector<Mat3<Real>> node_rotations(const ForceField<Real>& field, Index points);

}  // namespace fastcorot
