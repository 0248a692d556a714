#include "hexahedron_builders.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/hexahedron_faces.h"
#include "fastcorot/topology/regular_grid.h"

#include <Eigen/SparseCore>

#include <cmath>

namespace fastcorot::scene_detail {

bool is_grid_topology(std::string_view type) {
  return type == "RegularGridTopology" || type == "CylinderGridTopology" || type == "SphereGridTopology";
}

std::vector<Hexahedron> topology_hexahedra(SceneData& data, Component& topology) {
  std::vector<Hexahedron> hexahedra;
  if (is_grid_topology(topology.type())) {
    const RegularGrid grid = data.grid(topology);  // a flat grid (one point along an axis) has none
    for (Index k = 0; k + 1 < grid.n[2]; ++k) {
      for (Index j = 0; j + 1 < grid.n[1]; ++j) {
        for (Index i = 0; i + 1 < grid.n[0]; ++i) hexahedra.push_back(grid_cell_corners(grid, i, j, k));
      }
    }
    return hexahedra;
  }
  if (topology.type() != "HexahedronSetTopologyContainer") return hexahedra;
  const std::vector<Index> flat = data.indices(topology, "hexahedra");
  if (flat.size() % 8 != 0) {
    throw make_error(topology.where(), ": hexahedra needs 8 indices per hexahedron, got ", flat.size(), " indices");
  }
  // SOFA sizes the container to its highest index when position is not given; with positions, an
  // index beyond them is an error here (SOFA would read past its points).
  const std::size_t points = data.data(topology, "position").size() / 3;
  hexahedra.resize(flat.size() / 8);
  for (std::size_t h = 0; h < hexahedra.size(); ++h) {
    for (std::size_t j = 0; j < 8; ++j) {
      const Index v = flat[8 * h + j];
      if (points != 0 && static_cast<std::size_t>(v) >= points) {
        throw make_error(topology.where(), ": hexahedra: hexahedron ", h, " names point ", v, ", beyond the ", points,
                         " points of position");
      }
      hexahedra[h][j] = v;
    }
  }
  return hexahedra;
}

std::vector<Tetrahedron> tetrahedron_fem_tetrahedra(SceneData& data, Component& topology) {
  if (is_grid_topology(topology.type())) {
    try {
      return tetrahedron_fem_grid_tetrahedra(data.grid(topology));
    } catch (const Error& error) {
      throw error_at(topology.where(), error);
    }
  }
  // SOFA's TetrahedronFEMForceField takes a topology that is not a grid as cells of a 2 x 1 layer.
  return split_hexahedra(topology_hexahedra(data, topology), 2, 1, true, false);
}

std::vector<Hexahedron> hexahedra_of(SceneData& data, Component& c) {
  Component* topology = data.topology_of(c);
  if (!topology || !data.indices(*topology, "tetrahedra").empty()) return {};
  return topology_hexahedra(data, *topology);
}

std::shared_ptr<HexahedronFEMForceField<double>> build_hexahedron_fem(SceneData& data, Component& c,
                                                                       std::span<const Vec3<double>> rest) {
  try {
    std::vector<Hexahedron> hexahedra = hexahedra_of(data, c);
    if (hexahedra.empty()) {
      throw make_error("its topology has no hexahedra (a grid topology or a HexahedronSetTopologyContainer without "
                       "tetrahedra, in its node or above)");
    }
    HexahedronFEMForceField<double>::Parameters parameters;
    if (c.has("youngModulus")) parameters.young_modulus = data.data(c, "youngModulus");
    if (c.has("poissonRatio")) parameters.poisson_ratio = data.data(c, "poissonRatio");
    if (parameters.young_modulus.empty()) throw make_error("youngModulus is empty");
    if (parameters.poisson_ratio.empty()) throw make_error("poissonRatio is empty");
    parameters.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0.0);
    parameters.method = parse_hexahedron_fem_method(data.text(c, "method", "large"));
    if (data.boolean(c, "updateStiffnessMatrix", false)) {
      throw make_error("updateStiffnessMatrix=\"true\" is not supported (K is that of the rest shape)");
    }
    return std::make_shared<HexahedronFEMForceField<double>>(static_cast<Index>(rest.size()), std::move(hexahedra), rest,
                                                             parameters);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

Mass<double> build_hexahedron_mass(SceneData& data, Component& c, std::span<const Hexahedron> hexahedra,
                                   std::span<const Vec3<double>> rest) {
  const auto n = static_cast<Index>(rest.size());
  for (const Hexahedron& h : hexahedra) {
    for (Index p : h) {
      if (p < 0 || p >= n) throw make_error(c.where(), ": a hexahedron names point ", p, ", outside [0, ", n, ")");
    }
  }
  const bool from_total = c.has("totalMass") || !c.has("massDensity");
  const double total = data.real(c, "totalMass", 1.0);
  const double density = from_total ? 1.0 : data.real(c, "massDensity", 1.0);
  if (from_total && !(total > 0)) throw make_error(c.where(), ": totalMass must be > 0");
  if (!from_total && (!(density > 0) || !std::isfinite(density))) throw make_error(c.where(), ": massDensity must be > 0");
  if (c.type() == "DiagonalMass") {
    std::vector<double> masses(static_cast<std::size_t>(n), 0.0);
    double sum = 0;
    for (const Hexahedron& h : hexahedra) {
      const double share = density * hexahedron_volume<double>(rest, h) / 8.0;
      for (Index p : h) masses[static_cast<std::size_t>(p)] += share;
      sum += 8.0 * share;
    }
    if (from_total) {
      for (double& m : masses) m *= total / sum;
    }
    return Mass<double>::lumped(std::move(masses));
  }
  if (data.boolean(c, "lumping", false)) {
    // SOFA's lumped MeshMatrixMass on hexahedra: each corner's share density V / 20, times its
    // lumping coefficient 2.5 (the row sum: 1/20 + 3/40 = 1/8 of each hexahedron per corner).
    std::vector<double> masses(static_cast<std::size_t>(n), 0.0);
    double sum = 0;
    for (const Hexahedron& h : hexahedra) {
      const double share = density * hexahedron_volume<double>(rest, h) / 20.0;
      for (Index p : h) masses[static_cast<std::size_t>(p)] += share;
      sum += 8.0 * share * 2.5;
    }
    for (double& m : masses) m *= from_total ? 2.5 * total / sum : 2.5;
    return Mass<double>::lumped(std::move(masses));
  }
  std::vector<Eigen::Triplet<double>> entries;
  double sum = 0;
  for (const Hexahedron& h : hexahedra) {
    const double mass = density * hexahedron_volume<double>(rest, h);
    for (Index p : h) entries.emplace_back(p, p, mass / 20.0);
    for (const auto& e : kHexahedronEdges) {
      const Index a = h[static_cast<std::size_t>(e[0])], b = h[static_cast<std::size_t>(e[1])];
      entries.emplace_back(a, b, mass / 40.0);
      entries.emplace_back(b, a, mass / 40.0);
    }
    sum += mass;
  }
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  if (from_total) matrix *= total / sum;
  return Mass<double>::consistent(std::move(matrix));
}

}  // namespace fastcorot::scene_detail
