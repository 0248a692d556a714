#include "fastcorot/render/camera.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fastcorot {

namespace {

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

// Eye-space axes: right, up and back (from the target toward the eye).
struct ViewBasis {
  Eigen::Vector3d right, up, back;
};

ViewBasis view_basis(const Camera& camera) {
  ViewBasis basis;
  basis.back = (camera.eye - camera.target).normalized();
  basis.right = camera.up.cross(basis.back).normalized();
  basis.up = basis.back.cross(basis.right);
  return basis;
}

}  // namespace

Eigen::Matrix4d Camera::view_matrix() const {
  const ViewBasis b = view_basis(*this);
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = b.right.transpose();
  view.block<1, 3>(1, 0) = b.up.transpose();
  view.block<1, 3>(2, 0) = b.back.transpose();
  view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * eye;
  return view;
}

Eigen::Matrix4d Camera::projection_matrix(double aspect, double near, double far) const {
  const double f = 1.0 / std::tan(radians(fov_y_degrees) / 2);
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = f / aspect;
  projection(1, 1) = f;
  projection(2, 2) = (far + near) / (near - far);
  projection(2, 3) = 2 * far * near / (near - far);
  projection(3, 2) = -1;
  return projection;
}

std::optional<Eigen::Vector2d> Camera::project(const Eigen::Vector3d& p, int width,
                                               int height) const {
  const Eigen::Vector4d q = view_matrix() * p.homogeneous();
  if (q.z() >= 0) return std::nullopt;
  const double f = 1.0 / std::tan(radians(fov_y_degrees) / 2);
  const double aspect = static_cast<double>(width) / height;
  const double ndc_x = f / aspect * q.x() / -q.z();
  const double ndc_y = f * q.y() / -q.z();
  return Eigen::Vector2d((ndc_x + 1) / 2 * width, (1 - ndc_y) / 2 * height);
}

void Camera::orbit(double yaw, double pitch) {
  const Eigen::Vector3d axis = up.normalized();
  Eigen::Vector3d offset = Eigen::AngleAxisd(yaw, axis) * (eye - target);
  // Keep the eye at least 1 degree away from either pole: looking along `up` has no defined right.
  const double limit = radians(89);
  const double elevation = std::asin(std::clamp(offset.normalized().dot(axis), -1.0, 1.0));
  const double new_elevation = std::clamp(elevation + pitch, -limit, limit);
  const Eigen::Vector3d right = axis.cross(offset).normalized();
  offset = Eigen::AngleAxisd(-(new_elevation - elevation), right) * offset;
  eye = target + offset;
}

void Camera::pan(double right, double upward) {
  const ViewBasis b = view_basis(*this);
  const double height = 2 * (eye - target).norm() * std::tan(radians(fov_y_degrees) / 2);
  const Eigen::Vector3d shift = (right * b.right + upward * b.up) * height;
  eye += shift;
  target += shift;
}

void Camera::zoom(double factor) {
  if (factor > 0 && std::isfinite(factor)) eye = target + (eye - target) * factor;
}

Camera frame_camera(const Eigen::AlignedBox3d& bounds, const Eigen::Vector3d& gravity,
                    double aspect, const CameraOptions& options) {
  if (bounds.isEmpty() || !bounds.min().allFinite() || !bounds.max().allFinite()) {
    throw make_error("camera: nothing to frame (the scene's extent is empty or not finite)");
  }
  if (!(aspect > 0) || !std::isfinite(aspect))
    throw make_error("camera: aspect ratio ", aspect, " must be > 0");
  if (!(options.fov_y_degrees > 0 && options.fov_y_degrees < 180)) {
    throw make_error("camera: field of view ", options.fov_y_degrees,
                     " degrees must be in (0, 180)");
  }
  if (!(options.margin >= 1) || !std::isfinite(options.margin)) {
    throw make_error("camera: margin ", options.margin, " must be >= 1");
  }
  const bool falls = gravity.allFinite() && gravity.norm() > 0;
  Eigen::Vector3d up =
      options.up ? *options.up : (falls ? Eigen::Vector3d(-gravity) : Eigen::Vector3d::UnitY());
  if (!up.allFinite() || !(up.norm() > 0))
    throw make_error("camera: the up direction must be a non-zero vector");
  up.normalize();

  Eigen::AlignedBox3d box = bounds;
  if (falls && options.room_below > 0) {
    const Eigen::Vector3d drop =
        gravity.normalized() * options.room_below * bounds.sizes().maxCoeff();
    for (int c = 0; c < 8; ++c)
      box.extend(bounds.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) + drop);
  }

  Camera camera;
  camera.fov_y_degrees = options.fov_y_degrees;
  camera.up = up;
  camera.target = options.target ? *options.target : box.center();
  if (options.eye) {
    camera.eye = *options.eye;
    if (!camera.eye.allFinite() || !camera.target.allFinite() ||
        (camera.eye - camera.target).norm() == 0) {
      throw make_error("camera: the eye must be finite and away from the target");
    }
    if ((camera.eye - camera.target).normalized().cross(up).norm() < 1e-9) {
      throw make_error("camera: the view direction is parallel to up; give another --camera-up");
    }
    return camera;
  }

  // Broadside: look across the longest horizontal extent, then turn and raise the eye.
  Eigen::Vector3d along = Eigen::Vector3d::Zero();
  double longest = -1;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d horizontal =
        Eigen::Vector3d::Unit(axis) - Eigen::Vector3d::Unit(axis).dot(up) * up;
    if (horizontal.norm() < 0.1) continue;
    const double extent = box.sizes()[axis] * horizontal.norm();
    if (extent > longest + 1e-12 * box.sizes().maxCoeff()) {
      longest = extent;
      along = horizontal.normalized();
    }
  }
  const Eigen::Vector3d broadside = along.cross(up).normalized();
  const double azimuth = radians(options.azimuth_degrees),
               elevation = radians(options.elevation_degrees);
  const Eigen::Vector3d back =
      (std::cos(elevation) * (std::cos(azimuth) * broadside + std::sin(azimuth) * along) +
       std::sin(elevation) * up)
          .normalized();
  if (back.cross(up).norm() < 1e-9)
    throw make_error("camera: an elevation of ±90 degrees looks along up");
  const Eigen::Vector3d right = up.cross(back).normalized();
  const Eigen::Vector3d view_up = back.cross(right);

  // The smallest distance at which every corner lies inside the frustum, shrunk by the margin.
  const double tan_y = std::tan(radians(options.fov_y_degrees) / 2), tan_x = tan_y * aspect;
  auto fit_distance = [&] {
    double distance = 0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d p =
          box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) - camera.target;
      const double depth = p.dot(back);
      distance = std::max({distance, depth + options.margin * std::abs(p.dot(right)) / tan_x,
                           depth + options.margin * std::abs(p.dot(view_up)) / tan_y});
    }
    return distance > 0 ? distance : 1.0;  // a single point: any distance shows it
  };
  double distance = fit_distance();
  // Perspective makes the box's picture lopsided about its centre: unless the target is given,
  // move it to centre the picture, then fit again (a few rounds converge).
  for (int round = 0; round < 4 && !options.target; ++round) {
    Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d p =
          box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) - camera.target;
      const double depth = distance - p.dot(back);
      const Eigen::Vector2d screen(p.dot(right) / depth, p.dot(view_up) / depth);
      low = low.cwiseMin(screen);
      high = high.cwiseMax(screen);
    }
    const Eigen::Vector2d centre = (low + high) / 2;
    camera.target += distance * (centre.x() * right + centre.y() * view_up);
    distance = fit_distance();
  }
  camera.eye = camera.target + distance * back;
  return camera;
}

}  // namespace fastcorot
