#include "picture_options.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fastcorot::cli {

Eigen::Vector3d parse_vector(const std::string& text, const std::string& option) {
  std::string spaced = text;
  std::replace(spaced.begin(), spaced.end(), ',', ' ');
  std::istringstream in(spaced);
  Eigen::Vector3d v;
  std::string rest;
  if (!(in >> v.x() >> v.y() >> v.z()) || (in >> rest) || !v.allFinite()) {
    throw make_error(option, " \"", text, "\": expected three finite numbers X,Y,Z");
  }
  return v;
}

DrawOptions draw_options(const PictureOptions& options) {
  DrawOptions draw;
  draw.tetrahedra = parse_tetrahedron_drawing(options.drawing);
  draw.surface_edges = options.surface_edges;
  if (options.constraints != "on" && options.constraints != "off") {
    throw make_error("--constraints \"", options.constraints, "\": expected on or off");
  }
  draw.constraints = options.constraints == "on";
  if (!(options.constraint_force_scale >= 0 && std::isfinite(options.constraint_force_scale))) {
    throw make_error("--constraint-force-scale ", options.constraint_force_scale,
                     ": must be a finite length per unit of force >= 0 (0: chosen per frame)");
  }
  draw.constraint_force_scale = options.constraint_force_scale;
  if (options.contacts != "on" && options.contacts != "off") {
    throw make_error("--contacts \"", options.contacts, "\": expected on or off");
  }
  draw.contacts = options.contacts == "on";
  return draw;
}

CameraOptions camera_options(const PictureOptions& options) {
  CameraOptions camera;
  if (!options.camera_eye.empty()) camera.eye = parse_vector(options.camera_eye, "--camera-eye");
  if (!options.camera_target.empty())
    camera.target = parse_vector(options.camera_target, "--camera-target");
  if (!options.camera_up.empty()) {
    camera.up = parse_vector(options.camera_up, "--camera-up");
    if (camera.up->norm() == 0)
      throw make_error("--camera-up \"", options.camera_up, "\": must not be zero");
  }
  if (!(options.camera_fov > 0 && options.camera_fov < 180)) {
    throw make_error("--camera-fov ", options.camera_fov, ": must be in (0, 180) degrees");
  }
  if (!std::isfinite(options.camera_azimuth)) throw make_error("--camera-azimuth must be finite");
  if (!(std::abs(options.camera_elevation) < 90)) {
    throw make_error("--camera-elevation ", options.camera_elevation,
                     ": must be in (-90, 90) degrees");
  }
  camera.fov_y_degrees = options.camera_fov;
  camera.azimuth_degrees = options.camera_azimuth;
  camera.elevation_degrees = options.camera_elevation;
  return camera;
}

}  // namespace fastcorot::cli
