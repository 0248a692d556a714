// The one finite-difference harness of the test suite: central differences of a scalar or vector
// function of a flat coordinate vector, used to check every derivative (force = -dE/dx,
// stiffness = df/dx).
#pragma once

#include <Eigen/Core>

#include <functional>

namespace fastcorot::testing {

// Gradient of `energy` at x by central differences with step h.
inline Eigen::VectorXd fd_gradient(const std::function<double(const Eigen::VectorXd&)>& energy,
                                   const Eigen::VectorXd& x, double h) {
  Eigen::VectorXd gradient(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd plus = x, minus = x;
    plus[i] += h;
    minus[i] -= h;
    gradient[i] = (energy(plus) - energy(minus)) / (2 * h);
  }
  return gradient;
}

// Jacobian (rows: outputs, columns: inputs) of `function` at x by central differences with step h.
inline Eigen::MatrixXd fd_jacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& function,
                                   const Eigen::VectorXd& x, double h) {
  const Eigen::VectorXd f0 = function(x);
  Eigen::MatrixXd jacobian(f0.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd plus = x, minus = x;
    plus[i] += h;
    minus[i] -= h;
    jacobian.col(i) = (function(plus) - function(minus)) / (2 * h);
  }
  return jacobian;
}

// max |a - b| / max(max |b|, floor): the relative error measure used against reference values.
template <class A, class B>
double relative_error(const A& a, const B& b, double floor = 1e-300) {
  const double scale = std::max(b.cwiseAbs().maxCoeff(), floor);
  return (a - b).cwiseAbs().maxCoeff() / scale;
}

}  // namespace fastcorot::testing
