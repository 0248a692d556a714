#include "fastcorot/core/lame.h"

#include "fastcorot/core/error.h"

#include <cmath>

namespace fastcorot {

template <class Real>
LameParameters<Real> lame_parameters(Real young_modulus, Real poisson_ratio) {
  // Written as negated acceptance tests so that NaN is rejected too.
  if (!(young_modulus > 0) || !std::isfinite(young_modulus)) {
    throw make_error("youngModulus = ", young_modulus, ": must be a finite value > 0");
  }
  if (!(poisson_ratio >= 0 && poisson_ratio < Real(0.5))) {
    throw make_error("poissonRatio = ", poisson_ratio, ": must satisfy 0 <= nu < 0.5");
  }
  const Real mu = young_modulus / (2 * (1 + poisson_ratio));
  const Real lambda = young_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  return {mu, lambda};
}

template LameParameters<float> lame_parameters(float, float);
template LameParameters<double> lame_parameters(double, double);

}  // namespace fastcorot
