#include "fastcorot/render/draw_geometry.h"

#include "fastcorot/core/error.h"
#include "fastcorot/render/tetrahedron_drawing.h"

#include <algorithm>
#include <array>

namespace fastcorot {

namespace {

Eigen::Vector3f to_float(const Vec3<double>& v) {
  return v.cast<float>();
}
Eigen::Vector3f to_float(const Vec3<float>& v) {
  return v;
}

void add_triangle(TriangleList& list, const std::array<Eigen::Vector3f, 3>& corners,
                  const Eigen::Vector3f& normal, const Rgba& color) {
  for (const auto& corner : corners) {
    list.positions.push_back(corner);
    list.normals.push_back(normal);
    list.colors.push_back(color);
  }
}

// A mapped visual surface, smooth-shaded: each point's normal is the area-weighted mean of its
// triangles' normals (SOFA's OglModel computes its normals so).
void add_visual_surface(TriangleList& list, const VisualSurface& surface, std::span<const Vec3<double>> x) {
  const std::vector<Vec3<double>> p = surface.points(x);
  std::vector<Vec3<double>> normals(p.size(), Vec3<double>::Zero());
  for (const Triangle& t : surface.triangles) {
    const Vec3<double> n = (p[static_cast<std::size_t>(t[1])] - p[static_cast<std::size_t>(t[0])])
                               .cross(p[static_cast<std::size_t>(t[2])] - p[static_cast<std::size_t>(t[0])]);
    for (Index v : t) normals[static_cast<std::size_t>(v)] += n;
  }
  for (const Triangle& t : surface.triangles) {
    for (Index v : t) {
      const Vec3<double>& n = normals[static_cast<std::size_t>(v)];
      const double length = n.norm();
      list.positions.push_back(p[static_cast<std::size_t>(v)].cast<float>());
      list.normals.push_back(length > 0 ? Eigen::Vector3f((n / length).cast<float>()) : Eigen::Vector3f::Zero());
      list.colors.push_back(surface.color);
    }
  }
}

void add_segment(LineList& list, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                 const Rgba& color) {
  list.positions.push_back(a);
  list.positions.push_back(b);
  list.colors.push_back(color);
  list.colors.push_back(color);
}

void add_box(LineList& list, const DrawnBox& box, const Rgba& color) {
  auto corner = [&](int bits) {
    return Eigen::Vector3f(static_cast<float>((bits & 1) ? box.max.x() : box.min.x()),
                           static_cast<float>((bits & 2) ? box.max.y() : box.min.y()),
                           static_cast<float>((bits & 4) ? box.max.z() : box.min.z()));
  };
  // The 12 edges join corners whose bit patterns differ in one bit.
  for (int bits = 0; bits < 8; ++bits) {
    for (int axis = 1; axis < 8; axis <<= 1) {
      if (!(bits & axis)) add_segment(list, corner(bits), corner(bits | axis), color);
    }
  }
}

// An arrow from `from` along `vector`: the shaft and a head of four strokes, a quarter of the
// length long, spread about any two directions across the shaft.
void add_arrow(LineList& list, const Eigen::Vector3f& from, const Eigen::Vector3f& vector, const Rgba& color) {
  const float length = vector.norm();
  if (!(length > 0)) return;
  const Eigen::Vector3f d = vector / length;
  Eigen::Index smallest = 0;
  d.cwiseAbs().minCoeff(&smallest);
  const Eigen::Vector3f u = d.cross(Eigen::Vector3f::Unit(smallest)).normalized();
  const Eigen::Vector3f v = d.cross(u);
  const Eigen::Vector3f tip = from + vector;
  const Eigen::Vector3f back = tip - 0.25f * vector;
  add_segment(list, from, tip, color);
  const Eigen::Vector3f sides[4] = {u, -u, v, -v};
  for (const Eigen::Vector3f& side : sides) add_segment(list, tip, back + 0.1f * length * side, color);
}

// FNV-1a, one 32-bit vertex index at a time, in order: position-dependent, so a swap-with-last
// renumbering or a tetrahedron replaced by another changes it (up to the rare 64-bit collision).
std::uint64_t fingerprint_of(const TetMesh& mesh) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const Tetrahedron& t : mesh.tetrahedra()) {
    for (Index v : t) {
      hash ^= static_cast<std::uint32_t>(v);
      hash *= 1099511628211ull;
    }
  }
  return hash;
}

}  // namespace

TetrahedronDrawing parse_tetrahedron_drawing(const std::string& text) {
  if (text == "scene") return TetrahedronDrawing::scene;
  if (text == "on") return TetrahedronDrawing::all;
  if (text == "off") return TetrahedronDrawing::none;
  throw make_error("--drawing \"", text,
                   "\": expected scene (as each force field's drawing says), on or off");
}

Eigen::AlignedBox3d DrawGeometry::bounds() const {
  Eigen::AlignedBox3d box;
  for (const auto& p : triangles.positions) box.extend(p.cast<double>());
  for (const auto& p : lines.positions) box.extend(p.cast<double>());
  for (const auto& p : points.positions) box.extend(p.cast<double>());
  for (const auto& p : markers.positions) box.extend(p.cast<double>());
  return box;
}

Eigen::AlignedBox3d DrawGeometry::framing_bounds() const {
  Eigen::AlignedBox3d box;
  for (const auto& p : triangles.positions) box.extend(p.cast<double>());
  for (const auto& p : points.positions) box.extend(p.cast<double>());
  for (const auto& p : markers.positions) box.extend(p.cast<double>());
  return box.isEmpty() ? bounds() : box;
}

template <class Real>
bool draws_tetrahedra(const SimulatedObject<Real>& object, std::size_t field,
                      TetrahedronDrawing mode) {
  if (mode != TetrahedronDrawing::scene) return mode == TetrahedronDrawing::all;
  return field < object.force_field_drawing.size() && object.force_field_drawing[field].drawing;
}

const std::vector<BoundaryTriangle>& SceneDrawer::boundary_of(const TetMesh& mesh) {
  CachedBoundary& cached = boundaries_[&mesh];
  // The count alone misses a removal followed by as many additions, or a new mesh at a freed
  // address with the old count; the fingerprint follows every vertex of every tetrahedron.
  const std::uint64_t fingerprint = fingerprint_of(mesh);
  if (cached.tetrahedra != mesh.num_tetrahedra() || cached.fingerprint != fingerprint) {
    cached.triangles = mesh.boundary_triangles();
    cached.tetrahedra = mesh.num_tetrahedra();
    cached.fingerprint = fingerprint;
  }
  return cached.triangles;
}

template <class Real>
DrawGeometry SceneDrawer::draw(const Simulation<Real>& simulation, const DrawOptions& options) {
  DrawGeometry geometry;
  for (const auto& object : simulation.objects) draw_object(object, options, geometry);
  draw_constraints(simulation, options, geometry);
  draw_contacts(simulation, options, geometry);
  return geometry;
}

template <class Real>
void SceneDrawer::draw_contacts(const Simulation<Real>& simulation, const DrawOptions& options,
                                DrawGeometry& geometry) {
  if (!options.contacts || !simulation.collisions) return;
  const float length = static_cast<float>(options.contact_normal_length > 0
                                              ? options.contact_normal_length
                                              : static_cast<double>(simulation.scene_size()) / 20);
  for (const DetectedContact<Real>& contact : simulation.collisions->contacts()) {
    const Eigen::Vector3f first = to_float(contact.point[0]), second = to_float(contact.point[1]);
    geometry.markers.positions.push_back(first);
    geometry.markers.positions.push_back(second);
    geometry.markers.colors.push_back(options.contact_color);
    geometry.markers.colors.push_back(options.contact_color);
    add_segment(geometry.lines, first, second, options.contact_color);
    add_segment(geometry.lines, second, second + length * to_float(contact.normal), options.contact_normal_color);
  }
}

template <class Real>
void SceneDrawer::draw_constraints(const Simulation<Real>& simulation, const DrawOptions& options,
                                   DrawGeometry& geometry) {
  if (!options.constraints || !simulation.constraints) return;
  ConstraintDrawing drawing;
  simulation.constraints->draw(simulation.objects, simulation.dt, drawing);
  for (const ConstraintDrawing::Point& p : drawing.points) {
    geometry.markers.positions.push_back(to_float(p.position));
    geometry.markers.colors.push_back(p.active ? options.constraint_color : options.inactive_constraint_color);
  }
  for (const auto& [a, b] : drawing.pairs) {
    const ConstraintDrawing::Point& first = drawing.points[a];
    add_segment(geometry.lines, to_float(first.position), to_float(drawing.points[b].position),
                first.active ? options.constraint_color : options.inactive_constraint_color);
  }
  double scale = options.constraint_force_scale;
  if (scale == 0) {
    double largest = 0;
    for (const ConstraintDrawing::Point& p : drawing.points) largest = std::max(largest, p.force.norm());
    if (largest > 0) scale = 0.1 * static_cast<double>(simulation.scene_size()) / largest;
  }
  for (const ConstraintDrawing::Point& p : drawing.points) {
    add_arrow(geometry.lines, to_float(p.position), to_float(Vec3<double>(scale * p.force)),
              options.constraint_force_color);
  }
}

template <class Real>
void SceneDrawer::draw_object(const SimulatedObject<Real>& object, const DrawOptions& options,
                              DrawGeometry& geometry) {
  const auto& x = object.system.state.position;
  const std::span<const Vec3<Real>> positions(x);
  bool drew_tetrahedra = false;
  for (std::size_t f = 0; f < object.system.force_fields.size(); ++f) {
    if (!draws_tetrahedra(object, f, options.tetrahedra)) continue;
    const ForceFieldDrawing drawing =
        f < object.force_field_drawing.size() ? object.force_field_drawing[f] : ForceFieldDrawing{};
    for (const Tetrahedron& t : object.system.force_fields[f]->mesh().tetrahedra()) {
      const auto faces = drawn_tetrahedron_faces<Real>(tetrahedron_points<Real>(t, positions));
      for (std::size_t k = 0; k < 4; ++k) {
        const auto& face = faces[k];
        add_triangle(
            geometry.triangles,
            {to_float(face.corners[0]), to_float(face.corners[1]), to_float(face.corners[2])},
            to_float(face.normal), drawing.colors[k]);
      }
    }
    drew_tetrahedra = true;
  }
  // Visual models mapped onto the object are what SOFA shows by default; without one (or when the
  // tetrahedra are drawn) the object's own boundary.
  bool drew_surfaces = false;
  const std::size_t first_corner = geometry.triangles.positions.size();
  if constexpr (std::is_same_v<Real, double>) {
    if (!drew_tetrahedra) {
      for (const VisualSurface& surface : object.visual_surfaces) {
        add_visual_surface(geometry.triangles, surface, positions);
        drew_surfaces = true;
      }
    }
  }
  if (!drew_tetrahedra && !drew_surfaces && object.mesh) {
    for (const BoundaryTriangle& b : boundary_of(*object.mesh)) {
      const std::array<Eigen::Vector3f, 3> corners = {
          to_float(x[static_cast<std::size_t>(b.vertices[0])]),
          to_float(x[static_cast<std::size_t>(b.vertices[1])]),
          to_float(x[static_cast<std::size_t>(b.vertices[2])])};
      Eigen::Vector3f n = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
      // Outward: away from the vertex of the tetrahedron opposite this face.
      const Index opposite =
          object.mesh->tetrahedron(b.tetrahedron)[static_cast<std::size_t>(b.face)];
      if (n.dot(corners[0] - to_float(x[static_cast<std::size_t>(opposite)])) < 0) n = -n;
      const float length = n.norm();
      add_triangle(geometry.triangles, corners,
                   length > 0 ? Eigen::Vector3f(n / length) : Eigen::Vector3f::Zero(),
                   options.surface_color);
      if (options.surface_edges) {
        for (int e = 0; e < 3; ++e)
          add_segment(geometry.lines, corners[e], corners[(e + 1) % 3], options.edge_color);
      }
    }
  }
  const auto& rigids = object.system.rigids;
  if (options.fixed_points) {
    for (Index i : object.system.fixed) {
      // A rigid's angular block holds a rotation, not a point: its centre is drawn once.
      if (rigids && std::binary_search(rigids->block.begin(), rigids->block.end(), i - 1)) continue;
      geometry.points.positions.push_back(to_float(x[static_cast<std::size_t>(i)]));
      geometry.points.colors.push_back(options.fixed_point_color);
    }
  }
  if (options.rigid_frames && rigids && rigids->size() != 0) {
    // Axes a third of the size of what the object shows (its surfaces and centres: they reach out
    // of a body drawn about its centre), or 1 alone.
    Eigen::AlignedBox3f box;
    for (std::size_t c = first_corner; c < geometry.triangles.positions.size(); ++c) box.extend(geometry.triangles.positions[c]);
    for (std::size_t k = 0; k < rigids->size(); ++k) box.extend(to_float(x[static_cast<std::size_t>(rigids->block[k])]));
    const float diagonal = box.diagonal().norm();
    const float length = diagonal > 0 ? diagonal / 3 : 1.0f;
    const std::array<Rgba, 3> colors = {Rgba{0.9f, 0.1f, 0.1f, 1.0f}, Rgba{0.1f, 0.8f, 0.1f, 1.0f}, Rgba{0.15f, 0.3f, 1.0f, 1.0f}};
    for (std::size_t k = 0; k < rigids->size(); ++k) {
      const RigidCoord<Real> frame = rigids->coord(positions, k);
      const Eigen::Vector3f centre = to_float(frame.center);
      for (int a = 0; a < 3; ++a) {
        const Eigen::Vector3f axis = to_float(frame.rotate(Vec3<Real>::Unit(a)));
        add_segment(geometry.lines, centre, centre + length * axis, colors[static_cast<std::size_t>(a)]);
      }
    }
  }
  if (options.boxes) {
    for (const DrawnBox& box : object.boxes) add_box(geometry.lines, box, options.box_color);
  }
}

template bool draws_tetrahedra(const SimulatedObject<float>&, std::size_t, TetrahedronDrawing);
template bool draws_tetrahedra(const SimulatedObject<double>&, std::size_t, TetrahedronDrawing);
template DrawGeometry SceneDrawer::draw(const Simulation<float>&, const DrawOptions&);
template DrawGeometry SceneDrawer::draw(const Simulation<double>&, const DrawOptions&);
template void SceneDrawer::draw_constraints(const Simulation<float>&, const DrawOptions&, DrawGeometry&);
template void SceneDrawer::draw_constraints(const Simulation<double>&, const DrawOptions&, DrawGeometry&);
template void SceneDrawer::draw_contacts(const Simulation<float>&, const DrawOptions&, DrawGeometry&);
template void SceneDrawer::draw_contacts(const Simulation<double>&, const DrawOptions&, DrawGeometry&);
template void SceneDrawer::draw_object(const SimulatedObject<float>&, const DrawOptions&,
                                       DrawGeometry&);
template void SceneDrawer::draw_object(const SimulatedObject<double>&, const DrawOptions&,
                                       DrawGeometry&);

}  // namespace fastcorot
