// A magnetometer slower than the IMU, as a CAN IMU sends it: field readings in some epochs
// only (has_mag false in the others). The heading observer (Henriksson eq. 4.2) has its time
// constant in seconds, so it must follow the field as fast whether a reading comes with every
// IMU sample, with every fourth, or is held (repeated) between readings as a phone's is; and
// the heading's sigma must say the same in each.
#include <gtest/gtest.h>

#include <cmath>

#include "headingd/core/estimator.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kRadPerDeg;

const Vec3 kFieldNed(20.0, 2.0, 45.0);  // µT

enum class Delivery { kEverySample, kEveryFourthEpoch, kHeldBetweenReadings };

struct AfterTheTurn {
  double error_after_one_time_constant_rad = 0.0;
  double sigma_after_one_time_constant_rad = 0.0;
};

// 100 Hz, the sensor still and level on a heading of 1 rad; at 60 s the field the sensor sees
// turns by 20° about the vertical (its strength and dip unchanged, so the disturbance tests
// let it through): the observer follows it with its time constant τ. Returns the heading's
// distance from the turned field's at 60 s + τ.
AfterTheTurn turnTheField(Delivery delivery, std::uint32_t seed) {
  EstimatorParams p;
  p.mag_rate_error_time_constant_s = 0.0;  // the observer alone: no integral term
  test::Random rng(seed);
  const double dt = 0.01, turn_at_s = 60.0, turn = 20.0 * kRadPerDeg, tau = p.mag_heading_time_constant_s;
  const Quat q = Quat(headingRotation(1.0));
  Estimator est(p);
  AfterTheTurn out;
  Vec3 held = Vec3::Zero();
  for (int i = 0; i < static_cast<int>(std::llround((turn_at_s + tau) / dt)) + 1; ++i) {
    const double t = i * dt;
    const Vec3 field = t >= turn_at_s ? Vec3(headingRotation(turn) * kFieldNed) : kFieldNed;
    ImuSample s;
    s.t_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    s.gyro_rad_s = rng.gaussian(0.005);
    s.accel_m_s2 = q.inverse() * Vec3(0.0, 0.0, -9.81) + rng.gaussian(0.05);
    const bool reading = delivery == Delivery::kEverySample || i % 4 == 0;
    if (reading) held = q.inverse() * field + rng.gaussian(0.3);
    s.has_mag = reading || delivery == Delivery::kHeldBetweenReadings;
    s.mag_uT = s.has_mag ? held : Vec3::Zero();
    est.process(s);
    if (std::abs(t - (turn_at_s + tau)) < dt / 2) {
      const double declination = std::atan2(kFieldNed.y(), kFieldNed.x());
      out.error_after_one_time_constant_rad = wrapAngle(est.output().yaw_rad - (1.0 - turn - declination));
      out.sigma_after_one_time_constant_rad = est.output().heading_sigma_rad;
    }
  }
  return out;
}

TEST(SlowMagnetometer, TheHeadingFollowsTheFieldWithItsTimeConstantInSecondsAtAnyFieldRate) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const AfterTheTurn every = turnTheField(Delivery::kEverySample, seed);
    const AfterTheTurn fourth = turnTheField(Delivery::kEveryFourthEpoch, seed);
    const AfterTheTurn held = turnTheField(Delivery::kHeldBetweenReadings, seed);
    std::printf(
        "seed %u: after one time constant %.2f / %.2f / %.2f deg behind, sigma %.2f / %.2f / %.2f deg "
        "(every sample / every fourth epoch / held)\n",
        seed, every.error_after_one_time_constant_rad / kRadPerDeg,
        fourth.error_after_one_time_constant_rad / kRadPerDeg, held.error_after_one_time_constant_rad / kRadPerDeg,
        every.sigma_after_one_time_constant_rad / kRadPerDeg, fourth.sigma_after_one_time_constant_rad / kRadPerDeg,
        held.sigma_after_one_time_constant_rad / kRadPerDeg);
    // A first-order follower is e⁻¹ of the turn behind after one time constant: 7.4°.
    for (const AfterTheTurn& run : {every, fourth, held}) {
      EXPECT_NEAR(std::abs(run.error_after_one_time_constant_rad), 20.0 * kRadPerDeg * std::exp(-1.0), 1.0 * kRadPerDeg)
          << "seed " << seed;
    }
    EXPECT_NEAR(fourth.sigma_after_one_time_constant_rad, every.sigma_after_one_time_constant_rad,
                0.1 * every.sigma_after_one_time_constant_rad)
        << "seed " << seed;
  }
}

}  // namespace
}  // namespace headingd::core
