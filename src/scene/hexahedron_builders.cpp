#include "hexahedron_builders.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"

#include <Eigen/SparseCore>

#include <cmath>

namespace fastcorot::scene_detail {

namespace {

// The twelve edges of a hexahedron in SOFA's corner order.
constexpr int kHexahedronEdges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                         {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};

}  // namespace

std::vector<Hexahedron> hexahedra_of(SceneData& data, Component& c) {
  Component* topology = data.topology_of(c);
  if (!topology || !data.indices(*topology, "tetrahedra").empty()) return {};
  std::vector<Hexahedron> hexahedra;
  if (topology->type() == "RegularGridTopology" || topology->type() == "CylinderGridTopology") {
    const RegularGrid grid = data.grid(*topology);
    for (Index k = 0; k + 1 < grid.n[2]; ++k) {
      for (Index j = 0; j + 1 < grid.n[1]; ++j) {
        for (Index i = 0; i + 1 < grid.n[0]; ++i) hexahedra.push_back(grid_cell_corners(grid, i, j, k));
      }
    }
  }
  return hexahedra;
}

std::shared_ptr<HexahedronFEMForceField<double>> build_hexahedron_fem(SceneData& data, Component& c,
                                                                       std::span<const Vec3<double>> rest) {
  try {
    std::vector<Hexahedron> hexahedra = hexahedra_of(data, c);
    if (hexahedra.empty()) {
      throw make_error("its topology has no hexahedra (a RegularGridTopology or CylinderGridTopology without "
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
    throw make_error(c.where(), ": ", error.what());
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
  if (data.boolean(c, "lumping", false)) throw make_error(c.where(), ": lumping on hexahedra is not supported");
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
