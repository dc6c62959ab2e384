// Quasi-static field detection (Renaudin & Combettes 2014 §5, quasi_static_field.hpp): a field
// constant in the navigation frame is found while the sensor turns through it; a field that
// turns, changes strength or jumps is not; and in the estimator a slower magnetometer's held
// samples do not pass for a field that turns with the sensor.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "headingd/core/estimator.hpp"
#include "headingd/core/quasi_static_field.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kRadPerDeg;

const Vec3 kFieldNed(20.0, 2.0, 45.0);  // µT
constexpr double kDt = 0.01;            // 100 Hz
constexpr double kNoiseUT = 0.3;        // per axis and sample

QuasiStaticFieldParams magParams() { return {1.0, 0.2, 1.0, 3.0, 1.5}; }

// The sensor turns about a tilted axis at 30 deg/s (the gyro exact but for its noise); at time
// t the navigation frame's field is field_at(t). Returns the share of samples after the first
// window that were quasi-static, and the detector for its counters.
struct TurnedRun {
  double quasi_static_share = 0.0;
  QuasiStaticFieldDetector detector{magParams()};
};
TurnedRun turnThrough(const std::function<Vec3(double)>& field_at, double seconds, std::uint32_t seed) {
  test::Random rng(seed);
  TurnedRun run;
  GyroFrame frame;
  const Vec3 rate = 30.0 * kRadPerDeg * Vec3(0.3, -0.5, 1.0).normalized();
  Quat q_nb = Quat::Identity();
  int counted = 0, quasi_static = 0;
  const int n = static_cast<int>(std::llround(seconds / kDt));
  for (int i = 0; i < n; ++i) {
    const double t = i * kDt;
    const Quat increment = gyroIncrement(rate, kDt);
    q_nb = (q_nb * increment).normalized();
    // The gyro as the estimator hands it over: bias taken off, its white noise left.
    frame.advance(gyroIncrement(rate + rng.gaussian(0.002), kDt));
    const bool qs =
        run.detector.add(q_nb.inverse() * field_at(t) + rng.gaussian(kNoiseUT), frame.frameFromSensor(), kDt);
    if (t >= 1.5) {
      ++counted;
      quasi_static += qs ? 1 : 0;
    }
  }
  run.quasi_static_share = static_cast<double>(quasi_static) / counted;
  return run;
}

TEST(QuasiStaticField, AFieldConstantInTheNavigationFrameIsFoundWhileTheSensorTurns) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    // A disturbed field (not the Earth's: 70 µT) is as good as a clean one if it is static.
    const TurnedRun run = turnThrough([](double) { return Vec3(50.0, -30.0, 40.0); }, 30.0, seed);
    EXPECT_GT(run.quasi_static_share, 0.99) << "seed " << seed;
    EXPECT_EQ(run.detector.periods(), 1u) << "seed " << seed;
    EXPECT_NEAR(run.detector.totalSeconds(), 29.0, 0.05) << "seed " << seed;
    EXPECT_NEAR(run.detector.referenceNorm(), Vec3(50.0, -30.0, 40.0).norm(), 0.2) << "seed " << seed;
  }
}

TEST(QuasiStaticField, AFieldThatTurnsAtConstantStrengthIsNotQuasiStatic) {
  // The field turns about the vertical at 30 deg/s (a magnet turning beside the sensor): its
  // norm stays, so eqs. 33-34 alone would take it; carried through the gyro, its 20 µT of
  // horizontal field sweeps 10.5 µT in a second, a spread of 3 µT about the window's mean.
  const TurnedRun run =
      turnThrough([](double t) { return Vec3(headingRotation(30.0 * kRadPerDeg * t) * kFieldNed); }, 30.0, 1);
  EXPECT_EQ(run.detector.periods(), 0u);
  EXPECT_EQ(run.quasi_static_share, 0.0);
}

TEST(QuasiStaticField, AStrengthThatDriftsEndsThePeriodAgainstItsReference) {
  // Static for 10 s, then the strength grows by 0.5 µT/s: each window's own spread stays small
  // (0.15 µT of drift over 1 s), but within a few seconds the samples leave ξ_ref by more than
  // γ2 = 3 µT (eq. 34), and a new period starts from a new reference once a window passes.
  const TurnedRun run = turnThrough(
      [](double t) { return Vec3(kFieldNed * (1.0 + (t > 10.0 ? 0.5 * (t - 10.0) / kFieldNed.norm() : 0.0))); }, 30.0,
      2);
  EXPECT_GT(run.detector.periods(), 2u);
  EXPECT_GT(run.quasi_static_share, 0.5);
}

TEST(QuasiStaticField, OneOutlierEndsThePeriodAndAWindowPassesBeforeTheNext) {
  const Vec3 outlier_ned = kFieldNed + Vec3(0.0, 0.0, 10.0);  // one sample 10 µT off
  const TurnedRun run =
      turnThrough([&](double t) { return std::abs(t - 10.0) < kDt / 2 ? outlier_ned : kFieldNed; }, 20.0, 3);
  EXPECT_EQ(run.detector.periods(), 2u);
  // Quasi-static from 1 s to 10 s and from 11 s to 20 s (the outlier's window waited out).
  EXPECT_NEAR(run.detector.totalSeconds(), 18.0, 0.05);
}

TEST(QuasiStaticField, ARestartForgetsTheWindowAndKeepsTheCounters) {
  QuasiStaticFieldDetector d(magParams());
  for (int i = 0; i < 200; ++i) d.add(kFieldNed, Quat::Identity(), kDt);
  ASSERT_TRUE(d.quasiStatic());
  d.restart();
  EXPECT_FALSE(d.quasiStatic());
  EXPECT_EQ(d.periods(), 1u);
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(d.add(kFieldNed, Quat::Identity(), kDt)) << i;  // a whole window first
  EXPECT_TRUE(d.add(kFieldNed, Quat::Identity(), kDt));
  EXPECT_EQ(d.periods(), 2u);
}

TEST(QuasiStaticField, AWindowOfZeroTurnsTheDetectionOff) {
  QuasiStaticFieldDetector d({0.0, 0.0, 1.0, 3.0, 1.5});
  for (int i = 0; i < 500; ++i) EXPECT_FALSE(d.add(kFieldNed, Quat::Identity(), kDt));
  EXPECT_EQ(d.periods(), 0u);
}

// The estimator's counters, with a magnetometer at a quarter of the IMU's rate that repeats
// its last reading between its own (a phone): the sensor turns at 30 deg/s about the vertical
// in a static field. Only a new reading is a sample of the field: taken as samples, the
// repeats would count one reading's noise four times in the window's RMS tests.
TEST(QuasiStaticField, TheEstimatorSkipsAHeldFieldSampleAndCountsThePeriods) {
  test::Random rng(7);
  Estimator est;
  Vec3 held = Vec3::Zero();
  const Vec3 rate(0.0, 0.0, 30.0 * kRadPerDeg);
  Quat q_nb = Quat::Identity();
  const int n = 3000;  // 30 s
  int mag_quasi_static = 0;
  for (int i = 0; i < n; ++i) {
    q_nb = (q_nb * gyroIncrement(rate, kDt)).normalized();
    ImuSample s;
    s.t_ns = static_cast<std::int64_t>(i) * 10'000'000;
    s.gyro_rad_s = rate + rng.gaussian(0.002);
    s.accel_m_s2 = q_nb.inverse() * Vec3(0.0, 0.0, -9.81) + rng.gaussian(0.02);
    if (i % 4 == 0) held = q_nb.inverse() * kFieldNed + rng.gaussian(kNoiseUT);
    s.has_mag = true;
    s.mag_uT = held;
    est.process(s);
    mag_quasi_static += est.output().mag_quasi_static ? 1 : 0;
  }
  // 1 s of readings at 25 Hz (the one 1 s old may still be in, as rounding has it)
  EXPECT_NEAR(static_cast<double>(est.magQuasiStatic().windowSamples()), 25.5, 0.5);
  EXPECT_NEAR(static_cast<double>(est.accelQuasiStatic().windowSamples()), 100.5, 0.5);
  const EstimatorCounters c = est.counters();
  EXPECT_EQ(c.qsf_mag_periods, 1u);
  EXPECT_GT(c.qsf_mag_ms, 27'000u);
  EXPECT_GT(mag_quasi_static, 2700);
  // The specific force is gravity alone, also static in the navigation frame.
  EXPECT_EQ(c.qsf_accel_periods, 1u);
  EXPECT_GT(c.qsf_accel_ms, 27'000u);
}

}  // namespace
}  // namespace headingd::core
