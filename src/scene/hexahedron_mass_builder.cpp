#include "hexahedron_mass_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/hexahedron_fem_mass.h"

namespace fastcorot::scene_detail {

Mass<double> build_hexahedron_fem_mass(SceneData& data, Component& c, const HexahedronFEMForceField<double>& field,
                                       std::span<const Vec3<double>> rest) {
  try {
    if (c.has("massMatrices")) throw make_error("massMatrices: element masses given by hand are not supported (they are computed)");
    return hexahedron_fem_mass<double>(field, rest, data.real(c, "density", 1.0), data.boolean(c, "lumpedMass", false));
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

}  // namespace fastcorot::scene_detail
