// The gyro bias's drift model (drifting_bias.hpp): a random walk plus a Gauss-Markov bias
// instability, with measurements of their sum.
#include "headingd/core/drifting_bias.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace headingd::core {
namespace {

DriftingBias::Params params(double walk, double instability, double time_s) {
  return {walk, instability, time_s, /*initial_variance=*/0.05 * 0.05};
}

// Measures the bias as exactly `value` with variance `variance` per axis.
void measure(DriftingBias& b, const Vec3& value, double variance) {
  const Mat3 S = b.covariance() + variance * Mat3::Identity();
  b.correct<3>(Mat3::Identity(), S, Vec3(value - b.bias()));
}

TEST(DriftingBias, WithoutInstabilityItIsTheWalkAlone) {
  DriftingBias b(params(1e-3, 0.0, 30.0));
  measure(b, Vec3(0.01, -0.02, 0.03), 1e-8);
  const double after = b.covariance()(0, 0);
  for (int i = 0; i < 1000; ++i) b.predict(0.01);  // 10 s
  EXPECT_NEAR(b.covariance()(0, 0) - after, 1e-6 * 10.0, 1e-12);
  EXPECT_NEAR(b.bias().y(), -0.02, 1e-6);
}

// After a measurement of the sum only (which part the bias is in stays unknown), the sum's
// variance grows over T by the walk's w² T and the instability's 2σ²(1 - e^(-T/τ)): the g it
// had is forgotten and a new one drawn. So it opens by about σ over tens of seconds, as the
// sensor's bias moves, and after that only as the walk.
TEST(DriftingBias, TheInstabilityOpensTheSumOverItsCorrelationTimeNotForever) {
  const double walk = 1e-4, sigma = 1.2e-3, tau = 30.0;
  DriftingBias b(params(walk, sigma, tau));
  measure(b, Vec3::Zero(), 1e-12);
  const double start = b.covariance()(0, 0);
  EXPECT_LT(start, 1e-11);
  double elapsed = 0.0;
  const auto growthAfter = [&](double seconds) {
    for (; elapsed < seconds - 1e-9; elapsed += 0.01) b.predict(0.01);
    return b.covariance()(0, 0) - start;
  };
  const auto expected = [&](double t) { return walk * walk * t + 2.0 * sigma * sigma * (1.0 - std::exp(-t / tau)); };
  for (const double t : {1.0, 10.0, 30.0, 600.0}) EXPECT_NEAR(growthAfter(t), expected(t), 0.01 * expected(t)) << t;
}

// A bias drawn from the model itself (a walk plus a Gauss-Markov part) and measured every 10 s
// for 2 s of rest: the estimate's error lies within 3 of its stated sigmas in 99 % of the
// samples, and its normalised squared error averages 1 per axis (a filter whose model is the
// truth's claims neither more nor less than it knows).
TEST(DriftingBias, ItsSigmaIsHonestOnABiasThatDriftsAsItsModelSays) {
  const double walk = 1.7e-4, sigma = 1.2e-3, tau = 30.0, dt = 0.01, noise = 2e-3;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::size_t within = 0, count = 0;
  double nees = 0.0;
  for (int run = 0; run < 40; ++run) {
    DriftingBias b(params(walk, sigma, tau));
    Vec3 constant(0.03 * normal(rng), 0.03 * normal(rng), 0.03 * normal(rng));
    Vec3 markov(sigma * normal(rng), sigma * normal(rng), sigma * normal(rng));
    const double decay = std::exp(-dt / tau), markov_step = sigma * std::sqrt(1.0 - decay * decay);
    for (int i = 0; i < 12000; ++i) {  // 120 s
      for (int a = 0; a < 3; ++a) {
        constant[a] += walk * std::sqrt(dt) * normal(rng);
        markov[a] = decay * markov[a] + markov_step * normal(rng);
      }
      b.predict(dt);
      if (i % 1000 == 999) {  // a still block's mean: the bias plus its noise
        const Vec3 truth = constant + markov;
        measure(b, truth + Vec3(noise * normal(rng), noise * normal(rng), noise * normal(rng)), noise * noise);
      }
      const Vec3 error = b.bias() - (constant + markov);
      const Vec3 s = b.covariance().diagonal().cwiseSqrt();
      for (int a = 0; a < 3; ++a) {
        within += std::abs(error[a]) <= 3.0 * s[a] ? 1 : 0;
        nees += error[a] * error[a] / (s[a] * s[a]);
        ++count;
      }
    }
  }
  EXPECT_GE(static_cast<double>(within) / static_cast<double>(count), 0.99);
  EXPECT_NEAR(nees / static_cast<double>(count), 1.0, 0.15);
}

TEST(DriftingBias, TheClampHoldsTheSumAtItsEdge) {
  DriftingBias b(params(1e-4, 1e-3, 30.0));
  measure(b, Vec3(0.3, 0.0, 0.0), 1e-8);
  b.clampTo(0.2);
  EXPECT_NEAR(b.bias().norm(), 0.2, 1e-12);
  EXPECT_NEAR(b.bias().x(), 0.2, 1e-12);
}

}  // namespace
}  // namespace headingd::core
