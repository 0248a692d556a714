// SOFA's regions of interest (Sofa.Component.Engine.Select): BoxROI (axis-aligned and oriented
// boxes), SphereROI (balls, BoxROI's rules with its own edge and triangle angle filters), PlaneROI
// (slabs over a parallelogram) and PairBoxROI (the shell between two boxes), with
// their outputs: the points and elements (edges, triangles, quads, tetrahedra, hexahedra) inside,
// and for BoxROI and SphereROI those outside. Read from
// SOFA's BoxROI.inl, SphereROI.inl, BaseROI.inl and PlaneROI.inl (master 2a278d891f): bounds are inclusive, a
// point is in the region when it is in any of the shapes, outputs keep the input order, and each
// point or element appears once.
#include "scene_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

// SOFA's Vec::normalize: divides by the norm unless it is at most machine epsilon, when the vector
// is left as it is (zero for a degenerate shape).
Vec3<double> normalized(const Vec3<double>& v) {
  const double norm = v.norm();
  return norm > std::numeric_limits<double>::epsilon() ? Vec3<double>(v / norm) : v;
}

// A box over the parallelogram p0 p1 p2 (p3 = p0 + p2 - p1), `depth` thick about its plane: BoxROI's
// orientedBox and PlaneROI's plane, each given as 10 numbers (p0, p1, p2, depth). The two engines
// build the side planes' normals slightly differently (PlaneROI from corners lifted by depth / 2,
// BoxROI from the normal itself and a corner lifted by depth); the normals agree up to sign unless
// depth is zero, and the test takes absolute values.
struct Slab {
  Vec3<double> p0, p2, normal, plane0, plane1, plane2, plane3;
  double width = 0, length = 0, depth = 0;

  Slab(const double* v, bool as_plane_roi) {
    p0 = {v[0], v[1], v[2]};
    const Vec3<double> p1(v[3], v[4], v[5]);
    p2 = {v[6], v[7], v[8]};
    depth = v[9];
    normal = normalized((p1 - p0).cross(p2 - p0));
    const Vec3<double> p3 = p0 + (p2 - p1);
    if (as_plane_roi) {
      const Vec3<double> p4 = p0 + normal * (depth / 2);
      const Vec3<double> p6 = p2 + normal * (depth / 2);
      plane0 = normalized((p1 - p0).cross(p4 - p0));
      plane1 = normalized((p2 - p3).cross(p6 - p3));
      plane2 = normalized((p3 - p0).cross(p4 - p0));
      plane3 = normalized((p2 - p1).cross(p6 - p2));
    } else {
      const Vec3<double> p6 = p2 + normal * depth;
      plane0 = normalized((p1 - p0).cross(normal));
      plane1 = normalized((p2 - p3).cross(p6 - p3));
      plane2 = normalized((p3 - p0).cross(normal));
      plane3 = normalized((p2 - p1).cross(p6 - p2));
    }
    width = std::abs((p2 - p0).dot(plane0));
    length = std::abs((p2 - p0).dot(plane2));
  }

  bool contains(const Vec3<double>& p) const {
    const Vec3<double> from0 = p - p0;
    const Vec3<double> from2 = p - p2;
    return std::abs(from0.dot(plane0)) <= width && std::abs(from2.dot(plane1)) <= width &&
           std::abs(from0.dot(plane2)) <= length && std::abs(from2.dot(plane3)) <= length &&
           std::abs(from0.dot(normal)) <= std::abs(depth / 2);
  }
};

// An axis-aligned box from 6 numbers (xmin ymin zmin xmax ymax zmax), reversed bounds swapped as
// SOFA does at init; bounds inclusive.
struct AlignedBox {
  std::array<double, 3> low{}, high{};

  explicit AlignedBox(const double* v) {
    for (std::size_t k = 0; k < 3; ++k) {
      low[k] = std::min(v[k], v[k + 3]);
      high[k] = std::max(v[k], v[k + 3]);
    }
  }
  bool contains(const Vec3<double>& p) const {
    for (int k = 0; k < 3; ++k) {
      if (p[k] < low[static_cast<std::size_t>(k)] || p[k] > high[static_cast<std::size_t>(k)]) return false;
    }
    return true;
  }
};

struct ElementKind {
  const char* elements;    // input data, e.g. "triangles"
  const char* compute;     // its flag, e.g. "computeTriangles"
  const char* indices;     // output, e.g. "triangleIndices"
  const char* in_roi;      // output, e.g. "trianglesInROI"
  const char* out_indices; // BoxROI's output of those outside, or ""
  const char* out_roi;
  int corners;
  const char* singular;
};

constexpr ElementKind kElementKinds[] = {
    {"edges", "computeEdges", "edgeIndices", "edgesInROI", "edgeOutIndices", "edgesOutROI", 2, "edge"},
    {"triangles", "computeTriangles", "triangleIndices", "trianglesInROI", "triangleOutIndices", "trianglesOutROI", 3,
     "triangle"},
    {"quads", "computeQuads", "quadIndices", "quadsInROI", "", "", 4, "quad"},
    {"tetrahedra", "computeTetrahedra", "tetrahedronIndices", "tetrahedraInROI", "tetrahedronOutIndices",
     "tetrahedraOutROI", 4, "tetrahedron"},
    {"hexahedra", "computeHexahedra", "hexahedronIndices", "hexahedraInROI", "", "", 8, "hexahedron"}};

// SOFA's other spellings of BoxROI's and SphereROI's data.
std::string canonical_name(const std::string& name) {
  if (name == "pointIndices") return "indices";  // SphereROI's
  if (name == "quad") return "quads";
  if (name == "computeQuad") return "computeQuads";
  if (name == "quadInROI") return "quadsInROI";
  return name;
}

}  // namespace

Numbers SceneData::region_of_interest(Component& c, const std::string& asked) {
  // BoxROI and SphereROI share SOFA's BaseROI: its outputs, strict rule and outputs of what is out.
  const bool sphere_roi = c.type() == "SphereROI";
  const bool box_roi = c.type() == "BoxROI" || sphere_roi;
  const std::string name = canonical_name(asked);
  if (name == "position") return rest_positions_around(c);
  if (c.type() == "PairBoxROI") {
    // The points in inclusiveBox and not in includedBox.
    if (name != "indices" && name != "pointsInROI") return {};
    const Numbers& outer = data(c, "inclusiveBox");
    const Numbers& inner = data(c, "includedBox");
    if (outer.size() != 6 || inner.size() != 6) {
      throw make_error(c.where(), ": inclusiveBox and includedBox need 6 numbers each");
    }
    const AlignedBox inclusive(outer.data()), included(inner.data());
    const auto positions = points(c, "position");
    Numbers out;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      if (!inclusive.contains(positions[i]) || included.contains(positions[i])) continue;
      if (name == "indices") {
        out.push_back(static_cast<double>(i));
      } else {
        out.insert(out.end(), {positions[i].x(), positions[i].y(), positions[i].z()});
      }
    }
    return out;
  }
  if (box_roi && !sphere_roi && name == "box") return c.has("orientedBox") ? Numbers{} : Numbers{0, 0, 0, 1, 1, 1};
  if (!box_roi && name == "plane") return Numbers(10, 0.0);  // SOFA's default: one all-zero plane

  // The shapes.
  std::vector<AlignedBox> boxes;
  std::vector<Slab> slabs;
  const auto read_slabs = [&](const char* data_name) {
    const Numbers& values = data(c, data_name);
    if (values.size() % 10 != 0) {
      throw make_error(c.where(), ": ", data_name, " needs 10 numbers each (three corners p0 p1 p2 and a depth), got ",
                       values.size());
    }
    for (std::size_t s = 0; s < values.size(); s += 10) slabs.emplace_back(&values[s], !box_roi);
  };
  std::vector<std::pair<Vec3<double>, double>> spheres;  // centre, radius
  if (sphere_roi) {
    const auto centres = points(c, "centers");
    Numbers radii = data(c, "radii");
    if (radii.size() == 1) radii.assign(centres.size(), radii[0]);  // one radius for every centre, as SOFA
    if (radii.size() != centres.size()) {
      throw make_error(c.where(), ": ", centres.size(), " centers but ", radii.size(), " radii (one each, or one for all)");
    }
    for (std::size_t k = 0; k < centres.size(); ++k) spheres.emplace_back(centres[k], radii[k]);
  } else if (box_roi) {
    const Numbers& box = data(c, "box");
    if (box.size() % 6 != 0) {
      throw make_error(c.where(), ": box needs 6 numbers per box (xmin ymin zmin xmax ymax zmax), got ", box.size());
    }
    for (std::size_t b = 0; b < box.size(); b += 6) boxes.emplace_back(&box[b]);
    if (c.has("orientedBox")) read_slabs("orientedBox");
  } else {
    read_slabs("plane");
  }
  const auto in_box = [&](const Vec3<double>& p) {
    for (const auto& box : boxes) {
      if (box.contains(p)) return true;
    }
    for (const auto& slab : slabs) {
      if (slab.contains(p)) return true;
    }
    for (const auto& [centre, radius] : spheres) {
      if ((p - centre).squaredNorm() <= radius * radius) return true;
    }
    return false;
  };
  // SphereROI's filters: an edge whose direction is within edgeAngle (degrees) of `direction`, a
  // triangle whose normal (p2 - p0) × (p1 - p0) is within triAngle of `normal`, is left out; 0: none.
  const double edge_angle = sphere_roi ? real(c, "edgeAngle", 0.0) : 0.0;
  const double triangle_angle = sphere_roi ? real(c, c.has("triAngle") || !c.has("angle") ? "triAngle" : "angle", 0.0) : 0.0;
  const Vec3<double> direction = edge_angle > 0 ? normalized(vec3(c, "direction", Vec3<double>::Zero())) : Vec3<double>::Zero();
  const Vec3<double> normal = triangle_angle > 0 ? normalized(vec3(c, "normal", Vec3<double>::Zero())) : Vec3<double>::Zero();
  const auto passes_filter = [&](const std::vector<Vec3<double>>& p) {
    if (p.size() == 2 && edge_angle > 0) {
      return std::abs(normalized(p[1] - p[0]).dot(direction)) < std::abs(std::cos(edge_angle * M_PI / 180.0));
    }
    if (p.size() == 3 && triangle_angle > 0) {
      return normalized((p[2] - p[0]).cross(p[1] - p[0])).dot(normal) < std::cos(triangle_angle * M_PI / 180.0);
    }
    return true;
  };

  const bool rest_alias = sphere_roi && !c.has("position") && c.has("rest_position");  // SphereROI's other name
  const auto positions = points(c, rest_alias ? "rest_position" : "position");
  const auto emit_point = [&](Numbers& out, std::size_t i, bool as_index) {
    if (as_index) {
      out.push_back(static_cast<double>(i));
    } else {
      out.insert(out.end(), {positions[i].x(), positions[i].y(), positions[i].z()});
    }
  };
  if (name == "indices" || name == "pointsInROI" || name == "nbIndices" || name == "indicesOut" ||
      name == "pointsOutROI") {
    const bool inside_wanted = name == "indices" || name == "pointsInROI" || name == "nbIndices";
    Numbers out;
    std::size_t count = 0;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      if (in_box(positions[i]) != inside_wanted) continue;
      ++count;
      emit_point(out, i, name == "indices" || name == "indicesOut");
    }
    if (name == "nbIndices") return {static_cast<double>(count)};
    return out;
  }

  for (const ElementKind& kind : kElementKinds) {
    const bool in_out = name == kind.indices || name == kind.in_roi;
    const bool out_out = box_roi && *kind.out_indices && (name == kind.out_indices || name == kind.out_roi);
    if (!in_out && !out_out) continue;
    const std::string elements_name = kind.elements;
    if (!box_roi && (elements_name == "quads" || elements_name == "hexahedra")) return {};  // not PlaneROI's
    std::string flag = kind.compute;
    if (flag == "computeQuads" && !c.has(flag) && c.has("computeQuad")) flag = "computeQuad";
    if (!boolean(c, flag, true)) return {};
    // The elements given, else those of the node's topology (triangles: of its triangle container first).
    Numbers elements;
    if (c.has(elements_name) || (elements_name == "quads" && c.has("quad"))) {
      elements = data(c, c.has(elements_name) ? elements_name : "quad");
    } else if (Component* container = elements_name == "triangles" ? triangle_container_of(*c.node) : nullptr) {
      elements = data(*container, "triangles");
    } else if (Component* topology = topology_of(*c.node)) {
      elements = data(*topology, elements_name);
    }
    const auto corners = static_cast<std::size_t>(kind.corners);
    if (elements.size() % corners != 0) {
      throw make_error(c.where(), ": ", elements_name, " needs ", corners, " point indices per ", kind.singular);
    }
    // BoxROI (strict, the default): an element whose points are all in the region, else one whose
    // centre is. PlaneROI: one whose points are all in one of its planes.
    const bool strict = boolean(c, "strict", true);
    const auto selected = [&](std::size_t e) {
      std::vector<Vec3<double>> points;
      Vec3<double> centre = Vec3<double>::Zero();
      for (std::size_t j = 0; j < corners; ++j) {
        const auto v = static_cast<std::size_t>(elements[e * corners + j]);
        if (v >= positions.size()) {
          throw make_error(c.where(), ": ", kind.singular, " ", e, " has point ", v, " of ", positions.size());
        }
        points.push_back(positions[v]);
        centre += positions[v] / static_cast<double>(corners);
      }
      if (!box_roi) {
        for (const auto& slab : slabs) {
          bool all = true;
          for (const auto& p : points) all = all && slab.contains(p);
          if (all) return true;
        }
        return false;
      }
      if (!strict) return in_box(centre) && passes_filter(points);
      for (const auto& p : points) {
        if (!in_box(p)) return false;
      }
      return passes_filter(points);
    };
    const bool want_inside = in_out;
    const bool as_indices = name == kind.indices || name == kind.out_indices;
    Numbers out;
    for (std::size_t e = 0; e < elements.size() / corners; ++e) {
      if (selected(e) != want_inside) continue;
      if (as_indices) {
        out.push_back(static_cast<double>(e));
      } else {
        out.insert(out.end(), elements.begin() + static_cast<std::ptrdiff_t>(e * corners),
                   elements.begin() + static_cast<std::ptrdiff_t>((e + 1) * corners));
      }
    }
    return out;
  }
  return {};
}

}  // namespace fastcorot::scene_detail
