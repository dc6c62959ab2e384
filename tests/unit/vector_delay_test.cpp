// A vector sensor's delay against the gyro is learned from a turning sensor's data
// (vector_delay_estimator.hpp): a field sampled Δ before each row, or a slower magnetometer
// repeated between its samples, against a gyro that reads the rate over each row's interval;
// and a noisy gyro's rows, which hide a delay that chains over a longer span show.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "headingd/core/vector_delay_estimator.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

const Vec3 kFieldNed(15.0, 1.0, 48.0);  // µT

// A sensor turning about all three axes at rates that change with every "stride" (1-2.3 Hz,
// up to 3 rad/s), its attitude integrated at 10 kHz so that it is known at any instant.
class TurningSensor {
 public:
  static constexpr double kStep = 1e-4;
  explicit TurningSensor(double duration_s) {
    Quat q = Quat::Identity();
    const auto n = static_cast<std::size_t>(duration_s / kStep) + 2;
    attitude_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      attitude_.push_back(q);
      const Vec3 w = rate(static_cast<double>(i) * kStep + 0.5 * kStep);
      q = (q * gyroIncrement(w, kStep)).normalized();
    }
  }
  static Vec3 rate(double t) {
    return {3.0 * std::sin(2.0 * test::kPi * 1.1 * t), 2.0 * std::sin(2.0 * test::kPi * 1.7 * t + 1.0),
            1.5 * std::sin(2.0 * test::kPi * 2.3 * t + 2.0) + 0.3};
  }
  // The rate over (t - dt, t], as a gyro that integrates over its sample interval reads it.
  static Vec3 meanRate(double t, double dt) {
    Vec3 sum = Vec3::Zero();
    constexpr int kParts = 50;
    for (int i = 0; i < kParts; ++i) sum += rate(t - dt + (i + 0.5) * dt / kParts);
    return sum / kParts;
  }
  Vec3 fieldInSensor(double t) const {
    const auto i = static_cast<std::size_t>(std::llround(std::max(t, 0.0) / kStep));
    return attitude_[std::min(i, attitude_.size() - 1)].conjugate() * kFieldNed;
  }

 private:
  std::vector<Quat> attitude_;
};

struct Learned {
  double candidate_s;
  double sigma_s;
  double max_held_s;
};

// Rows at 100 Hz for 60 s; the magnetometer samples at mag_rate_hz (0: every row) the field
// as it was `delay_s` before its own sample time, with white noise.
Learned learn(double delay_s, double mag_rate_hz, std::uint32_t seed, double gyro_noise_rad_s = 0.005,
              double min_span_s = 0.0) {
  constexpr double kDuration = 60.0, kDt = 0.01;
  static const TurningSensor sensor(kDuration + 1.0);
  test::Random rng(seed);
  VectorDelayParams params;
  params.min_span_s = min_span_s;
  VectorDelayEstimator estimator(params);
  Vec3 mag = Vec3::Zero();
  long long last_sample = -1;
  Learned out{0.0, 0.0, 0.0};
  for (int k = 1; k < static_cast<int>(kDuration / kDt); ++k) {
    const double t = k * kDt;
    const double period = mag_rate_hz > 0.0 ? 1.0 / mag_rate_hz : kDt;
    const auto j = static_cast<long long>(std::floor(t / period + 1e-9));
    if (j != last_sample) {
      last_sample = j;
      mag = sensor.fieldInSensor(static_cast<double>(j) * period - delay_s) + rng.gaussian(0.3);
    }
    const Vec3 gyro = TurningSensor::meanRate(t, kDt) + rng.gaussian(gyro_noise_rad_s);
    estimator.update(gyro, &mag, true, kDt);
    out.max_held_s = std::max(out.max_held_s, estimator.heldS());
  }
  out.candidate_s = estimator.candidateS();
  out.sigma_s = estimator.sigmaS();
  return out;
}

// The regression is linear in Δ: at 3 rad/s turning 1-2 Hz, a long delay comes out a few per
// cent short (60 ms: 57 ms), which still takes almost all of the lag's error away.
TEST(VectorDelay, ALateFieldSampledWithEveryRowIsLearnedWithin2MsOr5Percent) {
  for (const double delay : {0.0, 0.012, 0.03, 0.06}) {
    const Learned l = learn(delay, 0.0, 1);
    EXPECT_NEAR(l.candidate_s, delay, std::max(0.002, 0.05 * delay)) << "delay " << delay << " s, sigma " << l.sigma_s;
    EXPECT_LT(l.sigma_s, 0.002);
    EXPECT_EQ(l.max_held_s, 0.0) << "a noisy field never repeats itself";
  }
}

TEST(VectorDelay, AFieldAheadOfTheGyroGivesANegativeDelay) {
  const Learned l = learn(-0.008, 0.0, 2);
  EXPECT_NEAR(l.candidate_s, -0.008, 0.002);
}

TEST(VectorDelay, ASlowerMagnetometerIsHeldAndItsFreshSamplesGiveTheirDelay) {
  // 40 Hz on 100 Hz rows: samples at 0, 25, 50, 75 ms reach the rows at 0, 30, 50, 80 ms, 2.5
  // ms late on average, and are then repeated for 1-2 rows.
  const Learned l = learn(0.025, 40.0, 3);
  EXPECT_NEAR(l.candidate_s, 0.025 + 0.0025, 0.002) << "sigma " << l.sigma_s;
  EXPECT_NEAR(l.max_held_s, 0.02, 1e-9);
}

// Over one row the change of a noisy gyro's rate is mostly noise, and a regression on a noisy
// regressor comes out short (towards zero); over chains of a second the change is the turn's.
// Rows of a consumer gyro (0.3 rad/s per sample: a phone's worst at 100 Hz is 0.02, this
// exaggerates it so that the turns' one-row changes, up to 0.2 rad/s, drown).
TEST(VectorDelay, ANoisyGyroHidesTheDelayRowByRowAndChainsOfASecondShowIt) {
  const Learned row_by_row = learn(0.03, 0.0, 4, 0.3, 0.0);
  const Learned chained = learn(0.03, 0.0, 4, 0.3, 1.0);
  std::printf("30 ms: row by row %.1f ms (sigma %.1f), chains of 1 s %.1f ms (sigma %.1f)\n",
              1e3 * row_by_row.candidate_s, 1e3 * row_by_row.sigma_s, 1e3 * chained.candidate_s, 1e3 * chained.sigma_s);
  EXPECT_LT(row_by_row.candidate_s, 0.5 * 0.03) << "sigma " << row_by_row.sigma_s;
  EXPECT_NEAR(chained.candidate_s, 0.03, 0.003) << "sigma " << chained.sigma_s;
}

TEST(VectorDelay, NothingIsLearnedFromADisturbedFieldOrWhenSwitchedOff) {
  VectorDelayParams off;
  off.max_delay_s = 0.0;
  VectorDelayEstimator switched_off(off), disturbed(VectorDelayParams{});
  const TurningSensor sensor(11.0);
  for (int k = 1; k < 1000; ++k) {
    const double t = k * 0.01;
    const Vec3 mag = sensor.fieldInSensor(t - 0.03);
    const Vec3 gyro = TurningSensor::meanRate(t, 0.01);
    switched_off.update(gyro, &mag, true, 0.01);
    disturbed.update(gyro, &mag, false, 0.01);
  }
  EXPECT_EQ(switched_off.candidateS(), 0.0);
  EXPECT_EQ(disturbed.candidateS(), 0.0);
  EXPECT_FALSE(std::isfinite(disturbed.sigmaS()));
}

TEST(VectorDelay, TheCandidateIsUsedOnlyWhereItMakesTheAngleToTheDownSteadier) {
  VectorDelayEstimator e(VectorDelayParams{});
  const Vec3 down(0.0, 0.0, 1.0);
  // The delayed field keeps its dip, the default one swings by ±0.1 of its sine.
  for (int k = 0; k < 500; ++k) {
    const double swing = 0.1 * std::sin(0.3 * k);
    e.scoreDownAngle(down, Vec3(std::sqrt(1.0 - (0.8 + swing) * (0.8 + swing)), 0.0, 0.8 + swing), Vec3(0.6, 0.0, 0.8),
                     true, 0.01);
  }
  EXPECT_TRUE(e.useCandidate());
  for (int k = 0; k < 200'000; ++k) {  // the other way round, long enough to outweigh the first
    const double swing = 0.1 * std::sin(0.3 * k);
    e.scoreDownAngle(down, Vec3(0.6, 0.0, 0.8), Vec3(std::sqrt(1.0 - (0.8 + swing) * (0.8 + swing)), 0.0, 0.8 + swing),
                     true, 0.01);
  }
  EXPECT_FALSE(e.useCandidate());
}

}  // namespace
}  // namespace headingd::core
