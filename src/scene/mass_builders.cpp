#include "mass_builders.h"

#include "fastcorot/core/error.h"
#include "element_fem_builders.h"
#include "hexahedron_builders.h"

#include <cmath>

namespace fastcorot::scene_detail {

Mass<double> build_mass(SceneData& data, Component& c, const Points<double>& rest,
                        const std::function<std::shared_ptr<TetMesh>()>& tetrahedra) {
  const auto n = static_cast<Index>(rest.size());
  const std::string_view type = c.type();
  if (type == "FEMMass") return build_fem_mass(data, c, rest, tetrahedra);
  if (type == "DiagonalMass" || type == "MeshMatrixMass") {
    const std::vector<Hexahedron> hexahedra = hexahedra_of(data, c);
    if (!hexahedra.empty()) return build_hexahedron_mass(data, c, hexahedra, rest);
  }
  try {
    if (type == "UniformMass") {
      double vertex_mass;
      if (c.has("totalMass")) {
        vertex_mass = data.real(c, "totalMass", 0) / static_cast<double>(n);
      } else if (c.has("vertexMass")) {
        vertex_mass = data.real(c, "vertexMass", 0);
      } else {
        throw make_error("neither vertexMass nor totalMass given");
      }
      return Mass<double>::lumped(std::vector<double>(static_cast<std::size_t>(n), vertex_mass));
    }
    const auto mesh = tetrahedra();
    double density = 1;
    const bool from_total = c.has("totalMass") || !c.has("massDensity");
    if (!from_total) density = data.real(c, "massDensity", 1.0);
    if (!(density > 0) || !std::isfinite(density)) throw make_error("massDensity = ", density, ": must be > 0");
    if (type == "DiagonalMass" || (type == "MeshMatrixMass" && data.boolean(c, "lumping", false))) {
      std::vector<double> masses = tetrahedral_lumped_masses<double>(*mesh, rest, 1.0);
      double sum = 0;
      for (double m : masses) sum += m;
      const double factor = from_total ? data.real(c, "totalMass", 1.0) / sum : density;
      if (from_total && !(data.real(c, "totalMass", 1.0) > 0)) throw make_error("totalMass must be > 0");
      for (double& m : masses) m *= factor;
      Mass<double> mass = Mass<double>::lumped(std::move(masses));
      mass.follow_tetrahedra(mesh, factor);
      return mass;
    }
    Eigen::SparseMatrix<double> matrix = tetrahedral_mass_matrix<double>(*mesh, rest, 1.0);
    const double total = matrix.sum();
    const double factor = from_total ? data.real(c, "totalMass", 1.0) / total : density;
    if (from_total && !(data.real(c, "totalMass", 1.0) > 0)) throw make_error("totalMass must be > 0");
    Mass<double> mass = Mass<double>::consistent(matrix * factor);
    mass.follow_tetrahedra(mesh, factor);
    return mass;
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

}  // namespace fastcorot::scene_detail
