#include "fastcorot/core/lame.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace fastcorot {
namespace {

TEST(LameParameters, MatchesTheTextbookFormulas) {
  // E = 1000, nu = 0.3: mu = 1000 / 2.6, lambda = 300 / (1.3 * 0.4), worked by hand.
  const auto lame = lame_parameters(1000.0, 0.3);
  EXPECT_NEAR(lame.mu, 384.61538461538464, 1e-12);
  EXPECT_NEAR(lame.lambda, 576.92307692307691, 1e-12);
  const auto lame_f = lame_parameters(1000.0f, 0.3f);
  EXPECT_NEAR(lame_f.mu, 384.615f, 1e-3f);
  EXPECT_NEAR(lame_f.lambda, 576.923f, 1e-3f);
}

TEST(LameParameters, ZeroPoissonRatioHasNoLambda) {
  const auto lame = lame_parameters(2000.0, 0.0);
  EXPECT_EQ(lame.lambda, 0.0);
  EXPECT_DOUBLE_EQ(lame.mu, 1000.0);
}

std::string error_of(double young, double poisson) {
  try {
    lame_parameters(young, poisson);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(LameParameters, RejectsBadValuesNamingTheAttribute) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double young : {0.0, -1.0, nan, inf}) {
    EXPECT_NE(error_of(young, 0.3).find("youngModulus"), std::string::npos) << young;
  }
  for (double poisson : {0.5, 0.7, -0.1, nan}) {
    EXPECT_NE(error_of(1000.0, poisson).find("poissonRatio"), std::string::npos) << poisson;
  }
  EXPECT_NE(error_of(-5.0, 0.3).find("-5"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
