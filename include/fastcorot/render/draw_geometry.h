// What one picture of a simulation shows, as flat lists any renderer can take (OpenGL here, files
// elsewhere): filled triangles with a normal and a colour per corner, line segments and points with
// a colour each. `SceneDrawer` makes one from a Simulation as SOFA shows a scene with its force
// fields displayed: force fields with `drawing` on as shrunk tetrahedra in drawColor1..4
// (tetrahedron_drawing.h), the other objects as their shaded boundary surface, fixed points as
// dots, BoxROI boxes as wire boxes, each rigid body's frame as three axes and the Lagrangian
// constraints' points as markers, bilateral pairs joined, with their forces as arrows, and the
// contacts of the last collision detection as their two points joined, with the normal. Nothing
// here touches OpenGL, so it is testable and usable without a display.
#pragma once

#include "fastcorot/sim/simulation.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <map>
#include <vector>

namespace fastcorot {

// Which force fields are drawn as shrunk tetrahedra: as the scene says (`drawing`), all, or none.
enum class TetrahedronDrawing { scene, all, none };

// Parses "scene", "on" (all) or "off" (none); throws fastcorot::Error naming the value otherwise.
TetrahedronDrawing parse_tetrahedron_drawing(const std::string& text);

struct DrawOptions {
  TetrahedronDrawing tetrahedra = TetrahedronDrawing::scene;
  bool fixed_points = true;
  bool boxes = true;
  bool rigid_frames = true;  // each rigid body's axes: x red, y green, z blue (SOFA's colours)
  bool surface_edges = false;  // outline the boundary triangles (shows the mesh)
  // Lagrangian constraints (a FreeMotionAnimationLoop's): their points as markers, bilateral pairs
  // joined by a segment, and the force each applies at its point as an arrow of length
  // constraint_force_scale × |f|; a scale of 0 chooses one per frame, the largest arrow a tenth of
  // the scene's size (Simulation::scene_size()).
  bool constraints = true;
  double constraint_force_scale = 0;
  // Contacts of the last step's collision detection (Simulation::collisions): each contact's two
  // points (on the first element, on the second) as markers joined by a segment, as SOFA's
  // PenalityContactForceField draws a contact, and its unit normal (first → second) from the second
  // point as a segment contact_normal_length long (0: a twentieth of the scene's size), as SOFA's
  // showNormals draws it. The points are where detection found them, at the step's start.
  bool contacts = true;
  double contact_normal_length = 0;
  Rgba surface_color{0.80f, 0.80f, 0.78f, 1.0f};
  Rgba edge_color{0.15f, 0.15f, 0.17f, 1.0f};
  Rgba fixed_point_color{0.90f, 0.15f, 0.10f, 1.0f};
  Rgba box_color{1.00f, 0.75f, 0.10f, 1.0f};
  Rgba constraint_color{1.00f, 0.00f, 1.00f, 1.0f};           // SOFA's bilateral points: magenta
  Rgba inactive_constraint_color{0.00f, 1.00f, 0.00f, 1.0f};  // and green when inactive
  Rgba constraint_force_color{0.10f, 0.85f, 0.95f, 1.0f};
  Rgba contact_color{1.00f, 0.45f, 0.00f, 1.0f};         // orange: apart from the constraints' colours
  Rgba contact_normal_color{1.00f, 1.00f, 0.00f, 1.0f};  // SOFA's normals: yellow
};

// Triangles: corners i = 3t, 3t+1, 3t+2 of triangle t; one normal and colour per corner.
struct TriangleList {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Rgba> colors;
  std::size_t size() const { return positions.size() / 3; }
};

// Segments: ends 2s and 2s+1 of segment s.
struct LineList {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Rgba> colors;
  std::size_t size() const { return positions.size() / 2; }
};

struct PointList {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Rgba> colors;
  std::size_t size() const { return positions.size(); }
};

struct DrawGeometry {
  TriangleList triangles;
  LineList lines;
  PointList points;
  PointList markers;  // larger points (RenderStyle::marker_size): the constraints' and contacts' points

  // The box holding everything drawn (empty when nothing is).
  Eigen::AlignedBox3d bounds() const;
  // The box a camera frames: the objects (triangles, points and markers) without the lines, since BoxROI
  // boxes often reach far beyond the objects they select from; all of it when there are no
  // triangles or points.
  Eigen::AlignedBox3d framing_bounds() const;
};

// True when force field `field` of `object` is drawn as shrunk tetrahedra under `mode`. An object
// without drawing information (built by hand, not from a scene) counts as `drawing` off.
template <class Real>
bool draws_tetrahedra(const SimulatedObject<Real>& object, std::size_t field,
                      TetrahedronDrawing mode);

// Turns simulations into DrawGeometry. It keeps each mesh's boundary triangles between frames, so
// reuse one drawer across frames. They are recomputed whenever the tetrahedra change (a cut, a
// reload whose new mesh happens to reuse the old one's address): a fingerprint of the tetrahedron
// list is checked each frame, which costs far less than finding the boundary again.
class SceneDrawer {
 public:
  template <class Real>
  DrawGeometry draw(const Simulation<Real>& simulation, const DrawOptions& options);

  // Appends one object's drawing to `geometry`.
  template <class Real>
  void draw_object(const SimulatedObject<Real>& object, const DrawOptions& options,
                   DrawGeometry& geometry);

  // Appends the Lagrangian constraints' drawing (nothing without a constraint stage).
  template <class Real>
  void draw_constraints(const Simulation<Real>& simulation, const DrawOptions& options,
                        DrawGeometry& geometry);

  // Appends the last detection's contacts: per contact two markers and two segments (the points
  // joined, then the normal); nothing without a collision stage or with options.contacts off.
  template <class Real>
  void draw_contacts(const Simulation<Real>& simulation, const DrawOptions& options,
                     DrawGeometry& geometry);

 private:
  const std::vector<BoundaryTriangle>& boundary_of(const TetMesh& mesh);

  struct CachedBoundary {
    Index tetrahedra = -1;
    std::uint64_t fingerprint = 0;
    std::vector<BoundaryTriangle> triangles;
  };
  std::map<const TetMesh*, CachedBoundary> boundaries_;
};

}  // namespace fastcorot
