#include "element_fem_builders.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/element_fem_force_field.h"
#include "fastcorot/fem/finite_element.h"
#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "hexahedron_builders.h"

#include <Eigen/SparseCore>

#include <cmath>

namespace fastcorot::scene_detail {

namespace {

// The density of node i as SOFA's BaseNodalProperty gives it: its own value, else the last one,
// else 1 (NodalMassDensity's default).
double node_density(const Numbers& property, Index i) {
  if (property.empty()) return 1.0;
  return static_cast<std::size_t>(i) < property.size() ? property[static_cast<std::size_t>(i)] : property.back();
}

Component& nodal_mass_density(SceneData& data, Component& c) {
  if (c.has("nodalMassDensity")) {
    Component& linked = data.resolve_object(*c.node, c.object->attributes.at("nodalMassDensity"), c);
    if (linked.type() != "NodalMassDensity") {
      throw make_error("nodalMassDensity must link a NodalMassDensity, not ", linked.where());
    }
    return linked;
  }
  for (const GraphNode* scope = c.node; scope; scope = scope->parent) {
    for (const auto& other : scope->components) {
      if (other->type() == "NodalMassDensity") return *other;
    }
  }
  throw make_error("no NodalMassDensity in its node or above (and no nodalMassDensity link)");
}

template <int N>
std::vector<std::array<Index, N>> elements_of(SceneData& data, Component& c,
                                              const std::function<std::shared_ptr<TetMesh>()>& tetrahedra) {
  std::vector<std::array<Index, N>> elements;
  if constexpr (N == 4) {
    const auto mesh = tetrahedra();
    for (Index t = 0; t < mesh->num_tetrahedra(); ++t) elements.push_back(mesh->tetrahedron(t));
  } else {
    elements = hexahedra_of(data, c);
    if (elements.empty()) {
      throw make_error("template Vec3,Hexahedron: its topology has no hexahedra (a RegularGridTopology or "
                       "CylinderGridTopology without tetrahedra, in its node, above, or linked by topology)");
    }
  }
  return elements;
}

template <int N>
std::shared_ptr<ForceField<double>> make_field(SceneData& data, Component& c, std::span<const Vec3<double>> rest,
                                               const std::function<std::shared_ptr<TetMesh>()>& tetrahedra,
                                               std::shared_ptr<TetMesh>& drawn) {
  typename ElementFEMForceField<double, N>::Parameters parameters;
  if (c.has("youngModulus")) parameters.young_modulus = data.data(c, "youngModulus");
  if (c.has("poissonRatio")) parameters.poisson_ratio = data.data(c, "poissonRatio");
  if (parameters.young_modulus.empty()) throw make_error("youngModulus is empty");
  if (parameters.poisson_ratio.empty()) throw make_error("poissonRatio is empty");
  parameters.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0.0);
  if (c.type() == "LinearSmallStrainFEMForceField") {
    parameters.method = ElementRotationMethod::none;
  } else if (c.has("rotationMethod")) {
    parameters.method = parse_element_rotation_method(data.text(c, "rotationMethod", ""), N);
  }
  for (const char* strategy : {"computeForceStrategy", "computeForceDerivStrategy"}) {
    const std::string value = data.text(c, strategy, "sequenced");
    if (value != "sequenced" && value != "parallel") {
      throw make_error(strategy, " = \"", value, "\": expected sequenced or parallel");
    }
  }
  auto elements = elements_of<N>(data, c, tetrahedra);
  if constexpr (N == 4) {
    drawn = tetrahedra();
  } else {
    drawn = std::make_shared<TetMesh>(static_cast<Index>(rest.size()), hexahedra_tetrahedra(elements));
  }
  return std::make_shared<ElementFEMForceField<double, N>>(drawn, std::move(elements), rest, std::move(parameters));
}

template <int N>
Eigen::SparseMatrix<double> mass_matrix(SceneData& data, Component& c, std::span<const Vec3<double>> rest,
                                        const std::function<std::shared_ptr<TetMesh>()>& tetrahedra) {
  Component& density_component = nodal_mass_density(data, c);
  const Numbers property = density_component.has("property") ? data.data(density_component, "property") : Numbers{1.0};
  for (std::size_t i = 0; i < property.size(); ++i) {
    if (!std::isfinite(property[i]) || property[i] < 0) {
      throw make_error(density_component.where(), ": property[", i, "] = ", property[i], ": must be finite and >= 0");
    }
  }
  const auto n = static_cast<Index>(rest.size());
  const auto elements = elements_of<N>(data, c, tetrahedra);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(elements.size() * N * N);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    ElementPoints<double, N> corners;
    std::array<double, N> densities;
    for (int j = 0; j < N; ++j) {
      const Index p = elements[e][static_cast<std::size_t>(j)];
      if (p < 0 || p >= n) throw make_error("element ", e, " names point ", p, ", outside [0, ", n, ")");
      corners[static_cast<std::size_t>(j)] = rest[static_cast<std::size_t>(p)];
      densities[static_cast<std::size_t>(j)] = node_density(property, p);
    }
    Eigen::Matrix<double, N, N> M;
    try {
      M = element_mass_matrix<double, N>(corners, densities);
    } catch (const Error& error) {
      throw make_error(N == 4 ? "tetrahedron " : "hexahedron ", e, ": ", error.what());
    }
    for (int a = 0; a < N; ++a) {
      for (int b = 0; b < N; ++b) {
        entries.emplace_back(elements[e][static_cast<std::size_t>(a)], elements[e][static_cast<std::size_t>(b)], M(a, b));
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

}  // namespace

bool is_element_fem(std::string_view type) {
  return type == "CorotationalFEMForceField" || type == "LinearSmallStrainFEMForceField";
}

int element_template_nodes(SceneData& data, Component& c) {
  const std::string name = data.text(c, "template", "");
  const auto comma = name.find(',');
  const std::string values = name.substr(0, comma), element = comma == std::string::npos ? "" : name.substr(comma + 1);
  const bool vec3 = values == "Vec3" || values == "Vec3d";
  if (vec3 && element == "Tetrahedron") return 4;
  if (vec3 && element == "Hexahedron") return 8;
  if (name.empty()) {
    throw make_error(c.where(), ": template is missing: give Vec3,Tetrahedron or Vec3,Hexahedron");
  }
  throw make_error(c.where(), ": template \"", name, "\": only Vec3,Tetrahedron and Vec3,Hexahedron are supported "
                   "(SOFA's Edge, Triangle, Quad, Prism, Pyramid and Vec1/Vec2 variants are not)");
}

std::shared_ptr<ForceField<double>> build_element_fem(SceneData& data, Component& c, std::span<const Vec3<double>> rest,
                                                      const std::function<std::shared_ptr<TetMesh>()>& tetrahedra,
                                                      std::shared_ptr<TetMesh>& drawn) {
  const int nodes = element_template_nodes(data, c);
  try {
    return nodes == 4 ? make_field<4>(data, c, rest, tetrahedra, drawn) : make_field<8>(data, c, rest, tetrahedra, drawn);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

Mass<double> build_fem_mass(SceneData& data, Component& c, std::span<const Vec3<double>> rest,
                            const std::function<std::shared_ptr<TetMesh>()>& tetrahedra) {
  const int nodes = element_template_nodes(data, c);
  try {
    return Mass<double>::consistent(nodes == 4 ? mass_matrix<4>(data, c, rest, tetrahedra)
                                               : mass_matrix<8>(data, c, rest, tetrahedra));
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

}  // namespace fastcorot::scene_detail
