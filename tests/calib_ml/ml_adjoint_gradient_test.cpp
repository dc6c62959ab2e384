// The reverse-mode gradient of K&S eq. 6 (ml_adjoint_gradient.hpp): the same value as the
// double evaluation, the same gradient as the Jets, and central differences (Richardson-
// extrapolated, so that their own error is far below the 1e-5 asked of the comparison).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "headingd/calib/ml/ml_adjoint_gradient.hpp"
#include "headingd/calib/ml/ml_calibration.hpp"
#include "ml_cost_fixture.hpp"

namespace headingd::calib {
namespace {

using Fixture = test::MlCostFixture;
using test::makeMlCostFixture;

double costAt(const Fixture& f, const MlParameters& theta) {
  double c = 0.0;
  EXPECT_TRUE(mlCostWithAdjointGradient(f.data, theta.data(), c, nullptr));
  return c;
}

// dcost/dθ_i by central differences with one Richardson step: error O(h⁴).
double centralDerivative(const Fixture& f, int i, double h) {
  const auto central = [&](double step) {
    MlParameters plus = f.theta, minus = f.theta;
    plus[i] += step;
    minus[i] -= step;
    return (costAt(f, plus) - costAt(f, minus)) / (2.0 * step);
  };
  return (4.0 * central(h / 2.0) - central(h)) / 3.0;
}

TEST(MlAdjointGradient, ValueEqualsDoubleValue) {
  const Fixture f = makeMlCostFixture(1);
  double plain = 0.0, with_gradient = 0.0;
  MlParameters gradient{};
  ASSERT_TRUE(mlCostWithAdjointGradient(f.data, f.theta.data(), plain, nullptr));
  ASSERT_TRUE(mlCostWithAdjointGradient(f.data, f.theta.data(), with_gradient, gradient.data()));
  EXPECT_TRUE(std::isfinite(plain));
  EXPECT_NEAR(plain, with_gradient, 1e-12 * std::abs(plain));
}

void expectMatchesJets(const Fixture& f) {
  double c_rev = 0.0, c_jet = 0.0;
  MlParameters g_rev{}, g_jet{};
  ASSERT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kAdjoint, c_rev, &g_rev));
  ASSERT_TRUE(evaluateMlCost(f.data, f.theta, MlGradient::kAutomatic, c_jet, &g_jet));
  EXPECT_NEAR(c_rev, c_jet, 1e-12 * std::abs(c_jet));
  for (int i = 0; i < kMlParameterCount; ++i) {
    // Both are exact; they differ only by the rounding of different sums.
    EXPECT_NEAR(g_rev[i], g_jet[i], 1e-9 * std::abs(g_jet[i]) + 1e-9) << "parameter " << i;
  }
}

TEST(MlAdjointGradient, MatchesJetGradient) { expectMatchesJets(makeMlCostFixture(1)); }

TEST(MlAdjointGradient, MatchesJetGradientWithDecimation) { expectMatchesJets(makeMlCostFixture(4)); }

TEST(MlAdjointGradient, MatchesCentralDifferences) {
  const Fixture f = makeMlCostFixture(1);
  double cost = 0.0;
  MlParameters g{};
  ASSERT_TRUE(mlCostWithAdjointGradient(f.data, f.theta.data(), cost, g.data()));
  double worst = 0.0;
  for (int i = 0; i < kMlParameterCount; ++i) {
    const double numeric = centralDerivative(f, i, 1e-3);
    const double relative = std::abs(g[i] - numeric) / std::max(std::abs(numeric), 1e-300);
    worst = std::max(worst, relative);
    EXPECT_LT(relative, 1e-5) << "parameter " << i << ": reverse " << g[i] << ", central " << numeric;
  }
  char worst_text[32];
  std::snprintf(worst_text, sizeof worst_text, "%.3g", worst);
  RecordProperty("worst_relative_error", worst_text);
}

TEST(MlAdjointGradient, FailsWhereTheCostFails) {
  Fixture f = makeMlCostFixture(1);
  // det D < 0: outside θ's domain (ml_likelihood.hpp).
  for (int c = 0; c < 3; ++c) f.theta[ml_index::kD + c] = -f.theta[ml_index::kD + c];
  double cost = 0.0;
  MlParameters g{};
  EXPECT_FALSE(mlCostWithAdjointGradient(f.data, f.theta.data(), cost, g.data()));
  EXPECT_FALSE(evaluateMlCost(f.data, f.theta, MlGradient::kAdjoint, cost, &g));
}

}  // namespace
}  // namespace headingd::calib
