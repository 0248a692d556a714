// Lamé parameters of an isotropic linear elastic material from Young's modulus E and Poisson's
// ratio nu: mu = E / (2 (1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu)). Units follow E (Pa when
// lengths are in metres). The checks are NaN-safe and name the offending value.
#pragma once

namespace fastcorot {

template <class Real>
struct LameParameters {
  Real mu;      // shear modulus
  Real lambda;  // first Lamé parameter
};

// Throws fastcorot::Error unless E > 0 and 0 <= nu < 0.5 (both finite).
template <class Real>
LameParameters<Real> lame_parameters(Real young_modulus, Real poisson_ratio);

}  // namespace fastcorot
