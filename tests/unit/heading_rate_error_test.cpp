// A constant error of the vertical rate (a gyro bias about the axis that stays vertical, with
// no rest to learn it from) must not leave a lasting heading offset while the field is clean:
// the heading observer alone (Henriksson eq. 4.2) settles at δ·τ behind; its integral term
// (mag_rate_error_time_constant_s, estimator_params.hpp) learns δ and takes it off.
#include <gtest/gtest.h>

#include <cmath>

#include "headingd/core/estimator.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kDeg;

const Vec3 kFieldNed(20.0, 2.0, 45.0);  // µT

struct HeadingErrors {
  double at_60_s = 0.0;
  double worst_after_300_s = 0.0;
  double vertical_rate_correction = 0.0;  // at the end
  double worst_horizontal_bias = 0.0;     // of the gyro bias estimate, body x and y
};

// Turning at a steady 0.3 rad/s about the vertical (too fast to be taken for rest), the sensor
// tilted by 10° and 20°, its gyro reading `bias` too much, for 600 s at 100 Hz.
HeadingErrors turnWithBias(const Vec3& bias, const EstimatorParams& p, std::uint32_t seed) {
  test::Random rng(seed);
  const Quat tilt = test::fromYawPitchRoll(0.0, 10.0 * kDeg, 20.0 * kDeg);
  const double rate = 0.3, dt = 0.01;
  const double declination = std::atan2(kFieldNed.y(), kFieldNed.x());
  Estimator est(p);
  HeadingErrors e;
  for (int i = 0; i < 60'000; ++i) {
    const double t = i * dt;
    const Quat q = headingRotation(rate * t) * tilt;
    ImuSample s;
    s.t_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    s.gyro_rad_s = tilt.inverse() * Vec3(0.0, 0.0, rate) + bias + rng.gaussian(0.01);
    s.accel_m_s2 = q.inverse() * Vec3(0.0, 0.0, -9.81) + rng.gaussian(0.05);
    s.mag_uT = q.inverse() * kFieldNed + rng.gaussian(0.5);
    est.process(s);
    const double error = std::abs(wrapAngle(est.output().yaw_rad - (yawZyx(q) - declination)));
    if (std::abs(t - 60.0) < dt / 2) e.at_60_s = error;
    if (t >= 300.0) e.worst_after_300_s = std::max(e.worst_after_300_s, error);
    e.worst_horizontal_bias = std::max(e.worst_horizontal_bias, est.output().gyro_bias_rad_s.head<2>().norm());
  }
  e.vertical_rate_correction = est.output().vertical_rate_correction_rad_s;
  return e;
}

TEST(HeadingRateError, AConstantVerticalBiasLeavesNoLastingHeadingOffset) {
  const Vec3 vertical_bias = Vec3(0.0, 0.0, 0.01);  // 10 mrad/s about body z, near vertical
  const EstimatorParams without;  // the default: no integral term
  const HeadingErrors alone = turnWithBias(vertical_bias, without, 1);
  // The observer alone: the offset δ·τ (0.01 · 15 s = 8.6°) stays.
  EXPECT_GT(alone.worst_after_300_s, 6.0 * kDeg);
  // And the gravity update's turns, which see the tilted part of the rate error turning
  // with the heading, are not taken for a horizontal bias (the sensor keeps turning).
  EXPECT_LT(alone.worst_horizontal_bias, 0.002);
  EstimatorParams with_integral;
  with_integral.mag_rate_error_time_constant_s = 60.0;  // 4τ: critically damped (off by default)
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const HeadingErrors with = turnWithBias(vertical_bias, with_integral, seed);
    EXPECT_LT(with.worst_after_300_s, 1.0 * kDeg) << "seed " << seed;
    // The vertical part of the rate error is learned and taken off: body z is tilted by 10°
    // and 20° from the vertical, so 0.01 · cos 10° · cos 20°.
    EXPECT_NEAR(with.vertical_rate_correction, -0.01 * std::cos(10.0 * kDeg) * std::cos(20.0 * kDeg), 0.001)
        << "seed " << seed;
  }
}

}  // namespace
}  // namespace headingd::core
