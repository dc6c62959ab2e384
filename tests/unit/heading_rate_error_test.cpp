// A constant error of the vertical rate (a gyro bias about the axis that stays vertical, with
// no rest to learn it from) must not leave a lasting heading offset while the field is clean:
// the heading observer alone (Henriksson eq. 4.2) settles at δ·τ behind; its integral term
// (vertical_rate_error.hpp) learns δ and takes it off on a steady heading where the field is
// known to be clean (a recent GPS fix, or a stretch where the disturbance tests do not fire),
// and is not taught a rate by a field whose error changes with the heading, nor by a
// building's field that the tests flag only part of the time.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "headingd/core/estimator.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kRadPerDeg;

const Vec3 kFieldNed(20.0, 2.0, 45.0);  // µT

struct HeadingErrors {
  double at_60_s = 0.0;
  double worst_after_300_s = 0.0;
  double worst_in_last_minute = 0.0;
  double vertical_rate_correction = 0.0;  // at the end
  double worst_horizontal_bias = 0.0;     // of the gyro bias estimate, body x and y
};

struct Motion {
  std::function<Quat(double t)> attitude;          // q_nb at time t
  Vec3 rate_ned_rad_s = Vec3::Zero();              // its constant rate about NED (0 between turns)
  std::function<Vec3(double t)> rate_at;           // or a rate that changes (NED), when given
  std::function<Vec3(double t)> acceleration_ned;  // m/s², when given
};

// `duration_s` at 100 Hz of `motion`, the gyro reading `bias` too much; with `fix` the WMM's
// field is set once a second, as the heading pipeline does at each GPS fix. `field_at` gives
// the field the sensor sees (NED, µT) at a time and heading, when it is not kFieldNed.
using FieldAt = std::function<Vec3(double t, double heading_rad)>;
HeadingErrors runWithBias(const Motion& motion, const Vec3& bias, const EstimatorParams& p, std::uint32_t seed,
                          double duration_s, bool fix, const FieldAt& field_at = {}) {
  test::Random rng(seed);
  const double dt = 0.01;
  const double declination = std::atan2(kFieldNed.y(), kFieldNed.x());
  const double inclination = std::atan2(kFieldNed.z(), kFieldNed.head<2>().norm());
  Estimator est(p);
  HeadingErrors e;
  const int samples = static_cast<int>(std::llround(duration_s / dt));
  for (int i = 0; i < samples; ++i) {
    const double t = i * dt;
    const Quat q = motion.attitude(t);
    const Vec3 rate_ned = motion.rate_at ? motion.rate_at(t) : motion.rate_ned_rad_s;
    if (fix && i % 100 == 0) est.setReferenceField(kFieldNed.norm(), inclination);
    const Vec3 field = field_at ? field_at(t, yawZyx(q)) : kFieldNed;
    ImuSample s;
    s.t_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    s.gyro_rad_s = q.inverse() * rate_ned + bias + rng.gaussian(0.01);
    const Vec3 acceleration = motion.acceleration_ned ? motion.acceleration_ned(t) : Vec3::Zero();
    s.accel_m_s2 = q.inverse() * (acceleration - Vec3(0.0, 0.0, 9.81)) + rng.gaussian(0.05);
    s.mag_uT = q.inverse() * field + rng.gaussian(0.5);
    est.process(s);
    const double error = std::abs(wrapAngle(est.output().yaw_rad - (yawZyx(q) - declination)));
    if (std::abs(t - 60.0) < dt / 2) e.at_60_s = error;
    if (t >= 300.0) e.worst_after_300_s = std::max(e.worst_after_300_s, error);
    if (t >= duration_s - 60.0) e.worst_in_last_minute = std::max(e.worst_in_last_minute, error);
    e.worst_horizontal_bias = std::max(e.worst_horizontal_bias, est.output().gyro_bias_rad_s.head<2>().norm());
  }
  e.vertical_rate_correction = est.output().vertical_rate_correction_rad_s;
  return e;
}

const Quat kTilt = test::fromYawPitchRoll(0.0, 10.0 * kRadPerDeg, 20.0 * kRadPerDeg);

// Turning at a steady 0.3 rad/s about the vertical (too fast to be taken for rest), the sensor
// tilted by 10° and 20°.
Motion steadyTurn() {
  const double rate = 0.3;
  return {[rate](double t) { return Quat(headingRotation(rate * t) * kTilt); }, Vec3(0.0, 0.0, rate), {}, {}};
}

// Walking on a fixed heading: the trunk sways ±3° at the stride's 1 Hz and bounces ±2 m/s² at
// the steps' 2 Hz (never still for the rest test), the sensor tilted by 10° and 20°.
Motion walkingOnAHeading(double heading_rad) {
  constexpr double kSway = 3.0 * kRadPerDeg, kOmega = 2.0 * 3.14159265358979323846;
  return {[=](double t) { return Quat(headingRotation(heading_rad + kSway * std::sin(kOmega * t)) * kTilt); },
          Vec3::Zero(), [=](double t) { return Vec3(0.0, 0.0, kSway * kOmega * std::cos(kOmega * t)); },
          [=](double t) { return Vec3(0.0, 0.0, 2.0 * std::sin(2.0 * kOmega * t)); }};
}

const Vec3 kVerticalBias(0.0, 0.0, 0.01);  // 10 mrad/s about body z, near vertical

TEST(HeadingRateError, TheTermItselfLearnsAConstantVerticalBias) {
  EstimatorParams without;
  without.mag_rate_error_time_constant_s = 0.0;
  const HeadingErrors alone = runWithBias(steadyTurn(), kVerticalBias, without, 1, 600.0, true);
  // The observer alone: the offset δ·τ (0.01 · 15 s = 8.6°) stays.
  EXPECT_GT(alone.worst_after_300_s, 6.0 * kRadPerDeg);
  // And the gravity update's turns, which see the tilted part of the rate error turning
  // with the heading, are not taken for a horizontal bias (the sensor keeps turning).
  EXPECT_LT(alone.worst_horizontal_bias, 0.002);
  // The term with none of its conditions (no fix needed, no steady heading), critically damped.
  EstimatorParams with_integral;
  with_integral.mag_rate_error_time_constant_s = 60.0;
  with_integral.mag_rate_error_max_reference_age_s = 0.0;
  with_integral.mag_rate_error_settle_s = 0.0;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const HeadingErrors with = runWithBias(steadyTurn(), kVerticalBias, with_integral, seed, 600.0, false);
    EXPECT_LT(with.worst_after_300_s, 1.0 * kRadPerDeg) << "seed " << seed;
    // The vertical part of the rate error is learned and taken off: body z is tilted by 10°
    // and 20° from the vertical, so 0.01 · cos 10° · cos 20°.
    EXPECT_NEAR(with.vertical_rate_correction, -0.01 * std::cos(10.0 * kRadPerDeg) * std::cos(20.0 * kRadPerDeg), 0.001)
        << "seed " << seed;
  }
}

TEST(HeadingRateError, ByDefaultAWalkInACleanFieldOnASteadyHeadingLeavesNoLastingOffset) {
  const EstimatorParams defaults;
  const double expected = -0.01 * std::cos(10.0 * kRadPerDeg) * std::cos(20.0 * kRadPerDeg);
  // Outdoors with a fix, and without one (no receiver, or no sky) where the disturbance tests
  // do not fire.
  for (const bool fix : {true, false}) {
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
      const HeadingErrors clean = runWithBias(walkingOnAHeading(1.0), kVerticalBias, defaults, seed, 900.0, fix);
      std::printf("%s, seed %u: worst heading error in the last minute %.2f deg, rate learned %.2f mrad/s\n",
                  fix ? "with a fix" : "without a fix", seed, clean.worst_in_last_minute / kRadPerDeg,
                  1e3 * clean.vertical_rate_correction);
      EXPECT_LT(clean.worst_in_last_minute, 1.0 * kRadPerDeg) << "fix " << fix << " seed " << seed;
      EXPECT_NEAR(clean.vertical_rate_correction, expected, 0.001) << "fix " << fix << " seed " << seed;
    }
  }
  // Only with a fix (the setting at 0): the term does not learn, the observer's offset δ·τ stays.
  EstimatorParams fix_needed = defaults;
  fix_needed.mag_rate_error_max_set_aside_share = 0.0;
  const HeadingErrors indoors = runWithBias(walkingOnAHeading(1.0), kVerticalBias, fix_needed, 1, 900.0, false);
  std::printf("only with a fix, none: worst heading error in the last minute %.2f deg\n",
              indoors.worst_in_last_minute / kRadPerDeg);
  EXPECT_EQ(indoors.vertical_rate_correction, 0.0);
  EXPECT_GT(indoors.worst_in_last_minute, 6.0 * kRadPerDeg);
}

// A building's field, without a fix and without any rate error: after a minute outdoors the
// walker goes in, where the steel turns the field by up to 25°, differently from place to
// place (slowly, as the walk goes on), and in every 10 s raises it by 40 % for 4 s (which the
// disturbance tests flag); the rest of the time it looks clean. Its lasting innovations are
// not a rate error, and the tests firing around them say the field here is not to be trusted.
TEST(HeadingRateError, ABuildingsFieldThatTheTestsFlagPartOfTheTimeIsNotLearnedAsARateError) {
  const FieldAt building = [](double t, double) {
    if (t < 60.0) return kFieldNed;
    const double turn = 25.0 * kRadPerDeg * std::sin(2.0 * 3.14159265358979323846 * (t - 60.0) / 300.0);
    const bool flagged_part = std::fmod(t, 10.0) < 4.0;
    return Vec3(headingRotation(turn) * kFieldNed * (flagged_part ? 1.4 : 1.0));
  };
  const EstimatorParams defaults;
  EstimatorParams ungated = defaults;
  ungated.mag_rate_error_max_reference_age_s = 0.0;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const HeadingErrors gated =
        runWithBias(walkingOnAHeading(1.0), Vec3::Zero(), defaults, seed, 600.0, false, building);
    const HeadingErrors eager =
        runWithBias(walkingOnAHeading(1.0), Vec3::Zero(), ungated, seed, 600.0, false, building);
    std::printf("seed %u: learned rate %.2f mrad/s, %.2f mrad/s from any field that looks clean\n", seed,
                1e3 * std::abs(gated.vertical_rate_correction), 1e3 * std::abs(eager.vertical_rate_correction));
    // What it has is what the noise taught it in the clean minute outdoors.
    EXPECT_LT(std::abs(gated.vertical_rate_correction), 0.1e-3) << "seed " << seed;
    // The building does teach a rate where nothing gates it: the test above is not vacuous.
    EXPECT_GT(std::abs(eager.vertical_rate_correction), 1e-3) << "seed " << seed;
  }
}

// Walking (as above) legs of 60 s on four headings, turning 90° in 3 s between them, through a field
// whose error depends on the heading (a calibration's residual hard iron: ±5°), without any
// rate error: the innovations after each turn are the field's, not a rate error's.
Motion legsOfAWalk() {
  constexpr double kLegS = 60.0, kTurnS = 3.0, kTurn = 90.0 * kRadPerDeg;
  const auto heading = [=](double t) {
    const double leg = std::floor(t / (kLegS + kTurnS));
    const double into = t - leg * (kLegS + kTurnS);
    return leg * kTurn + (into > kLegS ? kTurn * (into - kLegS) / kTurnS : 0.0);
  };
  const auto rate = [=](double t) {
    const double into = std::fmod(t, kLegS + kTurnS);
    return Vec3(0.0, 0.0, into > kLegS ? kTurn / kTurnS : 0.0);
  };
  const Motion walking = walkingOnAHeading(0.0);
  return {[=](double t) { return Quat(headingRotation(heading(t)) * walking.attitude(t)); }, Vec3::Zero(),
          [=](double t) { return Vec3(rate(t) + walking.rate_at(t)); }, walking.acceleration_ned};
}

TEST(HeadingRateError, AFieldErrorThatChangesWithTheHeadingIsNotLearnedAsARateError) {
  const FieldAt residual_hard_iron = [](double, double heading_rad) {
    return Vec3(headingRotation(5.0 * kRadPerDeg * std::sin(heading_rad + 0.5)) * kFieldNed);
  };
  const EstimatorParams defaults;
  EstimatorParams unsettled = defaults;
  unsettled.mag_rate_error_settle_s = 0.0;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const HeadingErrors settled =
        runWithBias(legsOfAWalk(), Vec3::Zero(), defaults, seed, 630.0, true, residual_hard_iron);
    const HeadingErrors eager =
        runWithBias(legsOfAWalk(), Vec3::Zero(), unsettled, seed, 630.0, true, residual_hard_iron);
    std::printf("seed %u: learned rate %.2f mrad/s settled, %.2f mrad/s without the steady heading\n", seed,
                1e3 * std::abs(settled.vertical_rate_correction), 1e3 * std::abs(eager.vertical_rate_correction));
    EXPECT_LT(std::abs(settled.vertical_rate_correction), 0.5e-3) << "seed " << seed;
  }
}

}  // namespace
}  // namespace headingd::core
