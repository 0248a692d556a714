// The command-line options shared by `fastcorot run --png` and `fastcorot view` that say what a
// picture looks like: its size, which force fields are drawn as tetrahedra, the constraints, the
// contacts and the camera. They
// are kept as text until the command runs, so that bad values become fastcorot::Error messages
// naming the option (exit status 2) rather than parser failures.
#pragma once

#include "fastcorot/render/camera.h"
#include "fastcorot/render/draw_geometry.h"

#include <optional>
#include <string>

namespace fastcorot::cli {

struct PictureOptions {
  std::string size = "800x450";   // WIDTHxHEIGHT
  std::string drawing = "scene";  // scene, on, off
  std::string camera_eye;         // "X,Y,Z"; empty: automatic framing
  std::string camera_target;
  std::string camera_up;
  double camera_fov = 30;        // degrees, vertical
  double camera_azimuth = 30;    // degrees about up, from the broadside view
  double camera_elevation = 20;  // degrees above the horizontal
  bool surface_edges = false;    // outline the mesh on the boundary surface
  std::string constraints = "on";     // Lagrangian constraints' points, pairs and forces: on, off
  double constraint_force_scale = 0;  // arrow length per unit of force; 0: the largest a tenth of the scene
  std::string contacts = "on";        // the last detection's contacts: points joined, normals: on, off
};

// "X,Y,Z" (commas or spaces); throws fastcorot::Error naming `option` otherwise.
Eigen::Vector3d parse_vector(const std::string& text, const std::string& option);

DrawOptions draw_options(const PictureOptions& options);
CameraOptions camera_options(const PictureOptions& options);

}  // namespace fastcorot::cli
