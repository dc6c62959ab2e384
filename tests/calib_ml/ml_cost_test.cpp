// The cost of K&S eq. 6: the Jet evaluation gives the same value as the double one, and its
// exact gradient agrees with central differences.
#include <gtest/gtest.h>

#include <cmath>

#include "headingd/calib/ml/ml_calibration.hpp"
#include "ml_cost_fixture.hpp"

namespace headingd::calib {
namespace {

using Fixture = test::MlCostFixture;
using test::makeMlCostFixture;

TEST(MlCost, JetValueEqualsDoubleValue) {
  const Fixture f = makeMlCostFixture();
  double plain = 0.0, with_gradient = 0.0;
  MlParameters gradient{};
  ASSERT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, plain, nullptr));
  ASSERT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, with_gradient, &gradient));
  EXPECT_NEAR(plain, with_gradient, 1e-9 * std::abs(plain));
  EXPECT_TRUE(std::isfinite(plain));
}

TEST(MlCost, AutomaticGradientMatchesCentralDifferences) {
  const Fixture f = makeMlCostFixture();
  double c_ad = 0.0, c_nd = 0.0;
  MlParameters g_ad{}, g_nd{};
  ASSERT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, c_ad, &g_ad));
  ASSERT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kNumericCentral, c_nd, &g_nd));
  double max_abs = 0.0;
  for (double g : g_ad) max_abs = std::max(max_abs, std::abs(g));
  for (int i = 0; i < kMlParameterCount; ++i) {
    // Central differences are good to a few 1e-6 relative here; the exact gradient is not
    // the one that would be off.
    EXPECT_NEAR(g_ad[i], g_nd[i], 1e-5 * max_abs + 1e-4 * std::abs(g_ad[i])) << "parameter " << i;
  }
}

TEST(MlCost, RejectsANonPositiveDefiniteInnovation) {
  Fixture f = makeMlCostFixture();
  // D = 0 and Σm → 0: the magnetometer innovation covariance vanishes.
  for (int i = 0; i < 9; ++i) f.theta[ml_index::kD + i] = 0.0;
  for (int i : {0, 2, 5}) f.theta[ml_index::kMagCov + i] = -400.0;
  double cost = 0.0;
  EXPECT_FALSE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, cost, nullptr));
}

// The mirror of the other dip sign is outside θ's domain once the place is known: the cost
// at a negative dip is refused with kDown and accepted without a sign.
TEST(MlCost, RefusesTheDipSignThePlaceRulesOut) {
  Fixture f = makeMlCostFixture();
  f.theta[ml_index::kDip] = -std::abs(f.theta[ml_index::kDip]);
  double cost = 0.0;
  f.data.expected_dip_sign = DipSign::kUnknown;
  EXPECT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, cost, nullptr));
  f.data.expected_dip_sign = DipSign::kDown;
  EXPECT_FALSE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, cost, nullptr));
  f.data.expected_dip_sign = DipSign::kUp;
  EXPECT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, cost, nullptr));
}

}  // namespace
}  // namespace headingd::calib
