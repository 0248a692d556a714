// The camera of a picture: a perspective pinhole at `eye` looking at `target` with `up` upwards,
// and the automatic framing that chooses it from the scene's extent. Framing puts "up" against
// gravity, looks broadside at the scene's longest horizontal extent from a raised three-quarter
// view, and backs off until every corner of the box fits with a margin; every choice can be
// overridden (CameraOptions, the `--camera-*` options of the command line). The viewer moves the
// camera with orbit, pan and zoom. Matrices follow OpenGL's conventions (column vectors, a
// right-handed eye space looking down −z, clip depth in [−1, 1]).
#pragma once

#include <Eigen/Geometry>

#include <optional>

namespace fastcorot {

struct Camera {
  Eigen::Vector3d eye{0, 0, 1};
  Eigen::Vector3d target{0, 0, 0};
  Eigen::Vector3d up{0, 1, 0};
  double fov_y_degrees = 30;  // vertical field of view

  // World → eye transform (rigid).
  Eigen::Matrix4d view_matrix() const;
  // Eye → clip transform for an image of the given width / height, with depths near < far > 0.
  Eigen::Matrix4d projection_matrix(double aspect, double near, double far) const;

  // The pixel of world point p in a width × height image (x to the right, y downwards from the top
  // left corner, pixel centres at .5); nullopt when p is behind the eye.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p, int width, int height) const;

  // Turns the eye about the target: `yaw` about `up`, then `pitch` about the horizontal axis of the
  // view (radians, positive raises the eye); the eye never passes over the pole.
  void orbit(double yaw, double pitch);
  // Moves eye and target together across the view, by fractions of the view's height at the target.
  void pan(double right, double upward);
  // Multiplies the distance to the target by `factor` (< 1 comes closer).
  void zoom(double factor);
};

// Choices for automatic framing; what is set here wins.
struct CameraOptions {
  std::optional<Eigen::Vector3d> eye;
  std::optional<Eigen::Vector3d> target;  // default: centres the framed box in the picture
  std::optional<Eigen::Vector3d> up;      // default: against gravity, else +y
  double fov_y_degrees = 30;
  double azimuth_degrees = 30;    // turn about `up` from the broadside view, toward the long axis
  double elevation_degrees = 20;  // eye height above the horizontal plane through the target
  double margin = 1.1;            // > 1 leaves room around the box
  // Fraction of the box's largest extent added below it (along gravity) before framing, so that
  // objects sagging under their weight stay in the picture of a fixed camera; 0 frames the box.
  double room_below = 0.2;
};

// Frames `bounds` for images of aspect ratio width / height. `gravity` gives the default up and the
// room below. Throws fastcorot::Error for an empty or non-finite box, a zero or non-finite up,
// an eye at the target, a field of view outside (0, 180) or a margin below 1.
Camera frame_camera(const Eigen::AlignedBox3d& bounds, const Eigen::Vector3d& gravity,
                    double aspect, const CameraOptions& options = {});

}  // namespace fastcorot
