// The point rotations SOFA's rotation finders report (its BaseRotationFinder::getRotations), read by
// the warp preconditioners: those of the first force field of the system that is one, in the
// system's order.
//   TetrahedronFEMForceField: the mean over the point's tetrahedra of R_e R0_e^T (node_rotations.h).
//   HexahedronFEMForceField: the polar factor of (I + sum over the point's hexahedra of
//     R_e R0_e^T) / (their count), R_e and R0_e the element frames (frame = R · world) now and at
//     rest: SOFA starts the sum at the identity before dividing by the count, and so it is here.
#pragma once

#include "fastcorot/sim/mechanical_system.h"

#include <optional>
#include <vector>

namespace fastcorot {

// Whether the system has a rotation finder.
template <class Real>
bool has_rotation_finder(const MechanicalSystem<Real>& system);

// One block per point of the system (identity for a point in no element), or nothing when the
// system has no rotation finder. `initial` caches the hexahedra's rest frames between calls (filled
// at the first call with a HexahedronFEMForceField, from system.state.rest_position).
template <class Real>
std::optional<std::vector<Mat3<Real>>> find_rotations(const MechanicalSystem<Real>& system,
                                                      std::vector<Mat3<Real>>& initial);

}  // namespace fastcorot
