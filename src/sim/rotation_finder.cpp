#include "fastcorot/sim/rotation_finder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/rotation.h"
#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/fem/node_rotations.h"

namespace fastcorot {

namespace {

template <class Real>
const ForceField<Real>* rotation_finder(const MechanicalSystem<Real>& system) {
  for (const auto& field : system.force_fields) {
    if (field->component() == "TetrahedronFEMForceField" || field->component() == "HexahedronFEMForceField") {
      return field.get();
    }
  }
  return nullptr;
}

template <class Real>
std::vector<Mat3<Real>> hexahedra_rotations(const MechanicalSystem<Real>& system, const HexahedronFEMForceField<Real>& field,
                                            std::vector<Mat3<Real>>& initial) {
  const auto hexahedra = field.hexahedra();
  if (initial.size() != hexahedra.size()) {
    // The element frames at rest: those a copy of the field records there.
    HexahedronFEMForceField<Real> at_rest = field;
    std::vector<Vec3<Real>> f(system.state.rest_position.size(), Vec3<Real>::Zero());
    at_rest.add_force(system.state.rest_position, f);
    initial.resize(hexahedra.size());
    for (std::size_t h = 0; h < hexahedra.size(); ++h) initial[h] = at_rest.rotation(static_cast<Index>(h));
  }
  const auto points = static_cast<std::size_t>(system.size());
  std::vector<Mat3<Real>> sum(points, Mat3<Real>::Identity());
  std::vector<int> count(points, 0);
  for (std::size_t h = 0; h < hexahedra.size(); ++h) {
    const Mat3<Real> turn = field.rotation(static_cast<Index>(h)) * initial[h].transpose();
    for (Index v : hexahedra[h]) {
      if (v < 0 || static_cast<std::size_t>(v) >= points) {
        throw make_error("HexahedronFEMForceField: point ", v, " outside a state of ", points);
      }
      sum[static_cast<std::size_t>(v)] += turn;
      ++count[static_cast<std::size_t>(v)];
    }
  }
  for (std::size_t i = 0; i < points; ++i) {
    sum[i] = count[i] == 0 ? Mat3<Real>::Identity() : polar_factor<Real>(sum[i] / static_cast<Real>(count[i]));
  }
  return sum;
}

}  // namespace

template <class Real>
bool has_rotation_finder(const MechanicalSystem<Real>& system) {
  return rotation_finder(system) != nullptr;
}

template <class Real>
std::optional<std::vector<Mat3<Real>>> find_rotations(const MechanicalSystem<Real>& system,
                                                      std::vector<Mat3<Real>>& initial) {
  const ForceField<Real>* field = rotation_finder(system);
  if (!field) return std::nullopt;
  if (const auto* hexahedra = dynamic_cast<const HexahedronFEMForceField<Real>*>(field)) {
    return hexahedra_rotations(system, *hexahedra, initial);
  }
  return node_rotations(*field, system.size());
}

template bool has_rotation_finder(const MechanicalSystem<float>&);
template bool has_rotation_finder(const MechanicalSystem<double>&);
template std::optional<std::vector<Mat3<float>>> find_rotations(const MechanicalSystem<float>&, std::vector<Mat3<float>>&);
template std::optional<std::vector<Mat3<double>>> find_rotations(const MechanicalSystem<double>&, std::vector<Mat3<double>>&);

}  // namespace fastcorot
