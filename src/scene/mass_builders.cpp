#include "mass_builders.h"

#include "fastcorot/core/error.h"
#include "element_fem_builders.h"
#include "hexahedron_builders.h"

#include <cmath>
#include <limits>

namespace fastcorot::scene_detail {

namespace {

// SOFA's DiagonalMass on an edge topology: each edge gives density × length / 2 to each end, at the
// rest positions; from totalMass the density is totalMass over the sum with density 1.
Mass<double> edge_mass(SceneData& data, Component& c, Component& topology, const Points<double>& rest) {
  const std::vector<Index> flat = data.indices(topology, "edges");
  if (flat.empty() || flat.size() % 2 != 0) throw make_error("its topology ", topology.where(), " has no edges (2 indices each)");
  for (Index v : flat) {
    if (v < 0 || static_cast<std::size_t>(v) >= rest.size()) {
      throw make_error(topology.where(), ": edges: point ", v, " is out of range [0, ", rest.size(), ")");
    }
  }
  // SOFA's order of precedence: totalMass, then massDensity, then vertexMass; totalMass 1 by default.
  const bool from_total = c.has("totalMass") || (!c.has("massDensity") && !c.has("vertexMass"));
  if (!from_total && !c.has("massDensity")) {
    const Numbers& given = data.data(c, "vertexMass");
    if (given.size() != rest.size()) throw make_error("vertexMass has ", given.size(), " values for ", rest.size(), " points");
    for (double m : given) {
      if (!(m >= 0) || !std::isfinite(m)) throw make_error("vertexMass: ", m, " is not a mass");
    }
    return Mass<double>::lumped(std::vector<double>(given.begin(), given.end()));
  }
  // SOFA's computeVertexMass(density): each edge gives density × length / 2 to each end.
  const auto vertex_masses = [&](double density, double& sum) {
    std::vector<double> masses(rest.size(), 0.0);
    sum = 0;
    for (std::size_t e = 0; e + 1 < flat.size(); e += 2) {
      const double half = density * (rest[static_cast<std::size_t>(flat[e])] - rest[static_cast<std::size_t>(flat[e + 1])]).norm() / 2.0;
      for (Index v : {flat[e], flat[e + 1]}) {
        masses[static_cast<std::size_t>(v)] += half;
        sum += half;
      }
    }
    return masses;
  };
  double sum = 0;
  if (!from_total) {
    const double density = data.real(c, "massDensity", 1.0);
    if (!(density > 0) || !std::isfinite(density)) throw make_error("massDensity = ", density, ": must be > 0");
    return Mass<double>::lumped(vertex_masses(density, sum));
  }
  // initFromTotalMass: the masses of density 1, scaled by totalMass over their sum.
  std::vector<double> masses = vertex_masses(1.0, sum);
  const double total = data.real(c, "totalMass", 1.0);
  if (!(total > 0)) throw make_error("totalMass must be > 0");
  const double density = sum < std::numeric_limits<double>::epsilon() ? 1.0 : total / sum;
  for (double& m : masses) m *= density;
  return Mass<double>::lumped(std::move(masses));
}

}  // namespace

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
    if (type == "DiagonalMass") {
      Component* topology = data.topology_of(c);
      if (topology && topology->type() == "EdgeSetTopologyContainer") return edge_mass(data, c, *topology, rest);
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
