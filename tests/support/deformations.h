// Deterministic test configurations: random rotations and affine or perturbed deformations of a
// set of rest points, and conversions between point arrays and flat vectors.
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/Geometry>

#include <random>
#include <vector>

namespace fastcorot::testing {

inline Mat3<double> random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

// x_i = rotation · (stretch · p_i) + translation
inline std::vector<Vec3<double>> affine_map(const std::vector<Vec3<double>>& points,
                                            const Mat3<double>& rotation, const Mat3<double>& stretch,
                                            const Vec3<double>& translation) {
  std::vector<Vec3<double>> out;
  for (const auto& p : points) out.push_back(rotation * (stretch * p) + translation);
  return out;
}

// Adds uniform noise of the given amplitude to every coordinate.
inline std::vector<Vec3<double>> perturbed(std::vector<Vec3<double>> points, double amplitude,
                                           std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (auto& p : points) p += Vec3<double>(u(rng), u(rng), u(rng));
  return points;
}

inline Eigen::VectorXd flatten(const std::vector<Vec3<double>>& points) {
  Eigen::VectorXd flat(3 * static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) flat.segment<3>(3 * static_cast<Eigen::Index>(i)) = points[i];
  return flat;
}

inline std::vector<Vec3<double>> unflatten(const Eigen::VectorXd& flat) {
  std::vector<Vec3<double>> points(static_cast<std::size_t>(flat.size() / 3));
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = flat.segment<3>(3 * static_cast<Eigen::Index>(i));
  return points;
}

template <class Real>
std::vector<Vec3<Real>> cast_points(const std::vector<Vec3<double>>& points) {
  std::vector<Vec3<Real>> out;
  for (const auto& p : points) out.push_back(p.cast<Real>());
  return out;
}

}  // namespace fastcorot::testing
