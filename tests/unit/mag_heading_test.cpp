// Magnetometer heading measurement and the observer of Henriksson eq. 4.2.
#include "headingd/core/mag_heading_observer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "headingd/core/heading_definition.hpp"
#include "headingd/core/mag_disturbance.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kPi;
using test::kRadPerDeg;
using test::Random;

const Vec3 kFieldNed(20.0, 0.0, 45.0);  // µT: 20 north, 0 east, 45 down (dip ≈ 66°)

TEST(MagHeading, MeasuredHeadingIsTheTrueYawForAnyTiltAndWrongYaw) {
  // The EKF attitude has the true tilt but a wrong heading; the field measured in body axes
  // by the true attitude gives the true heading and innovation = true - wrong (wrapped).
  int checked = 0;
  for (double roll_deg = -80.0; roll_deg <= 80.0; roll_deg += 20.0) {
    for (double pitch_deg = -80.0; pitch_deg <= 80.0; pitch_deg += 20.0) {
      for (double yaw_deg = -180.0; yaw_deg < 180.0; yaw_deg += 30.0) {
        for (double error_deg : {-170.0, -45.0, -1.0, 0.0, 3.0, 90.0, 179.0}) {
          const double roll = roll_deg * kRadPerDeg, pitch = pitch_deg * kRadPerDeg, yaw = yaw_deg * kRadPerDeg;
          const double wrong_yaw = yaw + error_deg * kRadPerDeg;
          const Quat truth = test::fromYawPitchRoll(yaw, pitch, roll);
          const Quat estimate = test::fromYawPitchRoll(wrong_yaw, pitch, roll);
          const Vec3 mag_b = truth.inverse() * kFieldNed;

          const MagHeadingMeasurement m = measureMagHeading(estimate, mag_b, 0.1);
          ASSERT_TRUE(m.valid);
          EXPECT_NEAR(test::angleDifference(measuredHeading(estimate, m), yaw), 0.0, 1e-9)
              << roll_deg << " " << pitch_deg << " " << yaw_deg << " " << error_deg;
          EXPECT_NEAR(m.innovation_rad, wrapAngle(yaw - wrong_yaw), 1e-9)
              << roll_deg << " " << pitch_deg << " " << yaw_deg << " " << error_deg;
          EXPECT_GT(m.innovation_rad, -kPi);
          EXPECT_LE(m.innovation_rad, kPi);
          EXPECT_NEAR(m.horizontal_uT, 20.0, 1e-9);
          EXPECT_NEAR(m.dip_rad, std::atan2(45.0, 20.0), 1e-9);
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 9 * 9 * 12 * 7);
}

TEST(MagHeading, WorksThroughPitchNinety) {
  // No Euler angles in the measurement: even at pitch 90° (yaw undefined) the innovation
  // still says how far to turn about the vertical.
  const Quat truth = headingRotation(0.4) * Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()));
  const Quat estimate = headingRotation(-0.3) * Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()));
  const MagHeadingMeasurement m = measureMagHeading(estimate, truth.inverse() * kFieldNed, 0.1);
  ASSERT_TRUE(m.valid);
  EXPECT_NEAR(m.innovation_rad, 0.7, 1e-12);
  EXPECT_LT(test::angleBetween(applyHeadingCorrection(estimate, m.innovation_rad, 1.0), truth), 1e-12);
}

TEST(MagHeading, NorthEastComponentGivesTheMagneticHeading) {
  // With declination δ (field towards north-east), the heading measured is from magnetic
  // north: the true yaw minus δ.
  const Vec3 field(20.0, 2.0, 45.0);
  const double declination = std::atan2(2.0, 20.0);
  const Quat truth = test::fromYawPitchRoll(1.0, 0.2, -0.3);
  const MagHeadingMeasurement m = measureMagHeading(truth, truth.inverse() * field, 0.1);
  ASSERT_TRUE(m.valid);
  EXPECT_NEAR(measuredHeading(truth, m), 1.0 - declination, 1e-12);
}

TEST(MagHeading, VerticalFieldGivesNoHeading) {
  const Quat q = test::fromYawPitchRoll(0.5, 0.1, 0.2);
  EXPECT_FALSE(measureMagHeading(q, q.inverse() * Vec3(0.0, 0.0, 50.0), 0.1).valid);
  // Nearly vertical: horizontal share 0.05 < 0.1.
  EXPECT_FALSE(measureMagHeading(q, q.inverse() * Vec3(2.5, 0.0, 50.0), 0.1).valid);
  EXPECT_TRUE(measureMagHeading(q, q.inverse() * Vec3(6.0, 0.0, 50.0), 0.1).valid);
  // No field at all.
  EXPECT_FALSE(measureMagHeading(q, Vec3::Zero(), 0.0).valid);
}

TEST(MagHeading, ObserverGain) {
  // Eq. 4.2 with K = 1 - exp(-dt/τ).
  EXPECT_NEAR(magObserverGain(0.01, 10.0), 1.0 - std::exp(-0.001), 1e-15);
  for (double dt : {1e-4, 0.005, 0.01, 0.1, 1.0}) {
    for (double tau : {0.5, 10.0, 15.0, 100.0}) {
      EXPECT_NEAR(magObserverGain(dt, tau), -std::expm1(-dt / tau), 1e-12) << dt << " " << tau;
    }
  }
  EXPECT_NEAR(magObserverGain(0.01, 10.0), 0.001, 1e-6);
  EXPECT_EQ(magObserverGain(0.0, 10.0), 0.0);
  EXPECT_NEAR(magObserverGain(1000.0, 1.0), 1.0, 1e-12);
  // The time constant holds at any rate: n steps of dt equal one step of n·dt.
  const double k_small = magObserverGain(0.01, 5.0);
  EXPECT_NEAR(1.0 - std::pow(1.0 - k_small, 100), magObserverGain(1.0, 5.0), 1e-12);
}

TEST(MagHeading, HeadingCorrectionChangesYawOnly) {
  Random rng(51);
  for (int i = 0; i < 500; ++i) {
    const double yaw = rng.uniform(-kPi, kPi), pitch = rng.uniform(-1.5, 1.5), roll = rng.uniform(-kPi, kPi);
    const Quat q = test::fromYawPitchRoll(yaw, pitch, roll);
    const double innovation = rng.uniform(-kPi, kPi), gain = rng.uniform(0.0, 1.0);
    const Quat corrected = applyHeadingCorrection(q, innovation, gain);

    EXPECT_NEAR(corrected.norm(), 1.0, 1e-15);
    const EulerAngles before = eulerZyx(q), after = eulerZyx(corrected);
    EXPECT_NEAR(test::angleDifference(after.yaw_rad, before.yaw_rad + gain * innovation), 0.0, 1e-9) << i;
    EXPECT_NEAR(after.pitch_rad, before.pitch_rad, 1e-9) << i;
    EXPECT_NEAR(test::angleDifference(after.roll_rad, before.roll_rad), 0.0, 1e-9) << i;
    // What the accelerometer sees (gravity in body axes) is unchanged.
    EXPECT_LT((corrected.inverse() * Vec3::UnitZ() - q.inverse() * Vec3::UnitZ()).norm(), 1e-14) << i;
  }
}

TEST(MagHeading, FullGainCorrectionAlignsWithTheField) {
  Random rng(52);
  for (int i = 0; i < 100; ++i) {
    const Quat truth = rng.unitQuat();
    const Quat tilt_only = headingRotation(rng.uniform(-kPi, kPi)) * truth;  // same tilt, wrong heading
    const MagHeadingMeasurement m = measureMagHeading(tilt_only, truth.inverse() * kFieldNed, 0.1);
    ASSERT_TRUE(m.valid);
    EXPECT_LT(test::angleBetween(applyHeadingCorrection(tilt_only, m.innovation_rad, 1.0), truth), 1e-9) << i;
  }
}

// ---------------------------------------------------------------- disturbance (§4.2)

// The low-pass tests only (no WMM reference): τ = 3 s, 3 µT, 0.07 rad.
MagDisturbanceParams lowPassParams() {
  MagDisturbanceParams p{};
  p.time_constant_s = 3.0;
  p.max_norm_deviation_uT = 3.0;
  p.max_dip_deviation_rad = 0.07;
  return p;
}
MagDisturbanceDetector lowPassDetector() { return MagDisturbanceDetector(lowPassParams()); }

bool disturbed(const MagDisturbance& verdict) { return verdict.any(); }

// A field of this strength (µT); its direction does not matter where the detector's
// allowance for a residual hard iron is 0.
Vec3 fieldOf(double norm_uT) { return Vec3(0.0, 0.0, norm_uT); }

TEST(MagDisturbance, SteadyFieldIsNeverDisturbed) {
  MagDisturbanceDetector d = lowPassDetector();
  Random rng(53);
  for (int i = 0; i < 2000; ++i) {
    EXPECT_FALSE(disturbed(d.update(fieldOf(49.0 + rng.normal(0.2)), 1.15 + rng.normal(0.005), 0.01))) << i;
  }
}

TEST(MagDisturbance, ANoisyMagnetometersFirstSecondsAreNotTakenForADisturbance) {
  // A phone's magnetometer with 1.5 µT of noise per axis, at the estimator's thresholds
  // (1.5 µT, 4°): while the noise floors are not known (2 s), the tests take the largest
  // threshold a floor could give; at the configured ones 121 of the first 200 samples were flagged.
  MagDisturbanceParams p{};
  p.time_constant_s = 3.0;
  p.max_norm_deviation_uT = 1.5;
  p.max_dip_deviation_rad = 0.07;
  MagDisturbanceDetector d(p);
  Random rng(54);
  const Vec3 field(15.0, 2.0, 48.0);
  int flagged_first = 0, flagged_later = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 m = field + rng.gaussian(1.5);
    const double dip = std::atan2(m.z(), m.head<2>().norm());
    (i < 200 ? flagged_first : flagged_later) += disturbed(d.update(m, dip, 0.01)) ? 1 : 0;
  }
  std::printf("flagged: %d of the first 200 samples, %d of the next 800\n", flagged_first, flagged_later);
  EXPECT_LE(flagged_first, 2);
  EXPECT_LE(flagged_later, 8);
  // Once the floors are known a step of 4 floors is a disturbance again.
  EXPECT_TRUE(disturbed(d.update(field + Vec3(0.0, 0.0, 12.0), std::atan2(60.0, field.head<2>().norm()), 0.01)));
}

TEST(MagDisturbance, StrengthStepIsDisturbedUntilTheLowPassFollows) {
  // Eq. 4.5: Δm = ||m| - |m_lp|| against the threshold; a lasting change is accepted again
  // once the low-pass (τ = 3 s) has followed it: 5 µT · e^{-t/τ} < 3 µT after ~1.5 s.
  MagDisturbanceDetector d = lowPassDetector();
  for (int i = 0; i < 500; ++i) ASSERT_FALSE(disturbed(d.update(fieldOf(49.0), 1.15, 0.01)));
  EXPECT_TRUE(disturbed(d.update(fieldOf(54.0), 1.15, 0.01)));
  EXPECT_NEAR(d.normDeviation(), 5.0, 1e-9);
  int count = 1;
  for (int i = 0; i < 500; ++i) count += disturbed(d.update(fieldOf(54.0), 1.15, 0.01)) ? 1 : 0;
  EXPECT_GT(count, 100);  // for more than a second
  EXPECT_LT(count, 250);  // and not for much longer than the low-pass needs
  EXPECT_FALSE(disturbed(d.update(fieldOf(54.0), 1.15, 0.01)));
}

TEST(MagDisturbance, DipChangeIsDisturbed) {
  MagDisturbanceDetector d = lowPassDetector();
  for (int i = 0; i < 500; ++i) ASSERT_FALSE(disturbed(d.update(fieldOf(49.0), 1.15, 0.01)));
  EXPECT_FALSE(disturbed(d.update(fieldOf(49.0), 1.15 + 0.05, 0.01)));  // below 0.07 rad
  EXPECT_TRUE(disturbed(d.update(fieldOf(49.0), 1.15 + 0.1, 0.01)));
  EXPECT_GT(d.dipDeviation(), 0.07);
}

// The strength test's allowance for a residual hard iron (mag_disturbance.hpp): a sensor
// tumbling at 1 rad/s about its x axis in a clean 49 µT field, with 3.5 µT of hard iron left
// by its calibration, sees the strength swing by up to ±3.5 µT.
struct Tumbling {
  int strength_flags = 0, samples = 0;
};
Tumbling tumble(double residual_hard_iron_uT) {
  MagDisturbanceParams p{};
  p.time_constant_s = 3.0;
  p.max_norm_deviation_uT = 1.5;
  p.max_dip_deviation_rad = 0.07;
  p.residual_hard_iron_uT = residual_hard_iron_uT;
  MagDisturbanceDetector d(p);
  const Vec3 field_ned(20.0, 0.0, 45.0), hard_iron(0.0, 2.5, 2.5);
  const double dip = std::atan2(45.0, 20.0);
  Quat q_nb = Quat::Identity();
  Tumbling t;
  for (int i = 0; i < 3000; ++i, ++t.samples) {
    const Quat increment = gyroIncrement(Vec3(1.0, 0.0, 0.0), 0.01);
    q_nb = (q_nb * increment).normalized();
    d.advance(increment);
    t.strength_flags += d.update(Vec3(q_nb.conjugate() * field_ned + hard_iron), dip, 0.01).norm_jump ? 1 : 0;
  }
  return t;
}

TEST(MagDisturbance, TheStrengthAResidualHardIronSwingsAsTheSensorTurnsIsNotADisturbance) {
  const Tumbling without = tumble(0.0), with = tumble(3.0);
  std::printf("strength flags of %d samples: %d without the allowance, %d with it\n", with.samples,
              without.strength_flags, with.strength_flags);
  EXPECT_GT(without.strength_flags, without.samples / 10);  // the test alone flags the turning
  EXPECT_LT(with.strength_flags, with.samples / 100);
}

TEST(MagDisturbance, AFieldThatTurnsAndStrengthensWhileTheSensorStaysStillIsStillDisturbed) {
  // A magnet brought near a sensor at rest: the field turns by 30° in the sensor's axes and
  // gains 5 µT over half a second. The gyro says the sensor did not turn: no allowance.
  MagDisturbanceParams p{};
  p.time_constant_s = 3.0;
  p.max_norm_deviation_uT = 1.5;
  p.max_dip_deviation_rad = 1.0;  // the strength test alone
  p.residual_hard_iron_uT = 3.0;
  MagDisturbanceDetector d(p);
  const Quat still = Quat::Identity();
  const Vec3 field(20.0, 0.0, 45.0);
  for (int i = 0; i < 500; ++i) {
    d.advance(still);
    ASSERT_FALSE(d.update(field, 1.15, 0.01).any());
  }
  bool flagged = false;
  for (int i = 1; i <= 50; ++i) {
    const double share = i / 50.0;
    const Vec3 turned = Eigen::AngleAxisd(share * 30.0 * kRadPerDeg, Vec3::UnitX()) * field;
    d.advance(still);
    flagged = flagged || d.update(Vec3(turned.normalized() * (field.norm() + 5.0 * share)), 1.15, 0.01).norm_jump;
  }
  EXPECT_TRUE(flagged);
  EXPECT_LT(d.turnedRad(), 0.01);
}

// The same with the return to the field from before the disturbance (0.5 s, the default).
MagDisturbanceDetector returningDetector() {
  MagDisturbanceParams p = lowPassParams();
  p.back_to_before_s = 0.5;
  return MagDisturbanceDetector(p);
}

// Samples (at 100 Hz) until the detector says clean again after `spike_s` of a 300 µT
// field with a wrong dip that then returns to 49 µT, 1.15 rad.
int samplesDisturbedAfterASpike(MagDisturbanceDetector& d, double spike_s) {
  for (int i = 0; i < 500; ++i) EXPECT_FALSE(disturbed(d.update(fieldOf(49.0), 1.15, 0.01)));
  for (int i = 0; i < static_cast<int>(spike_s * 100); ++i) EXPECT_TRUE(disturbed(d.update(fieldOf(300.0), 0.3, 0.01)));
  int count = 0;
  while (disturbed(d.update(fieldOf(49.0), 1.15, 0.01)) && count < 100'000) ++count;
  return count;
}

TEST(MagDisturbance, AFieldBackWhereItWasBeforeAPassingMagnetIsCleanAgainAfterAShortWhile) {
  // The low-passes alone: ln(251 / 3) = 4.4 time constants, 13 s.
  MagDisturbanceDetector low_passes = lowPassDetector();
  EXPECT_GT(samplesDisturbedAfterASpike(low_passes, 5.0), 1000);
  // Back within the thresholds of the strength and dip it had while clean: the 50th sample
  // back (0.5 s) is clean.
  MagDisturbanceDetector d = returningDetector();
  EXPECT_EQ(samplesDisturbedAfterASpike(d, 5.0), 49);
  // And the low-passes restart there: the next samples are clean, and a new disturbance is
  // measured from there.
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(disturbed(d.update(fieldOf(49.0), 1.15, 0.01)));
  EXPECT_TRUE(disturbed(d.update(fieldOf(54.0), 1.15, 0.01)));
  EXPECT_NEAR(d.normDeviation(), 5.0, 0.01);
}

TEST(MagDisturbance, ALastingChangeOrAShortCrossingOfTheOldFieldWaitsForTheLowPasses) {
  MagDisturbanceDetector d = returningDetector();
  for (int i = 0; i < 500; ++i) ASSERT_FALSE(disturbed(d.update(fieldOf(49.0), 1.15, 0.01)));
  // A magnet attached: the strength moves to 70 µT and stays; as the sensor turns it passes
  // through the old strength and dip for 0.4 s now and then.
  int disturbed_samples = 0;
  for (int i = 0; i < 300; ++i) disturbed_samples += disturbed(d.update(fieldOf(70.0), 1.15, 0.01)) ? 1 : 0;
  for (int i = 0; i < 40; ++i) disturbed_samples += disturbed(d.update(fieldOf(49.0), 1.15, 0.01)) ? 1 : 0;
  for (int i = 0; i < 300; ++i) disturbed_samples += disturbed(d.update(fieldOf(70.0), 1.15, 0.01)) ? 1 : 0;
  // The crossing is back at the old field for less than 0.5 s: no return, all disturbed.
  EXPECT_GT(disturbed_samples, 500);
  // The lasting change is accepted once the low-pass has followed it, as without the return.
  int more = 0;
  while (disturbed(d.update(fieldOf(70.0), 1.15, 0.01)) && more < 100'000) ++more;
  EXPECT_LT(more, 1000);
}

// The low-pass tests and a learned field (no WMM): first after 5 s clean, a new one after 20 s.
MagDisturbanceDetector learningDetector() {
  MagDisturbanceParams p = lowPassParams();
  p.max_reference_norm_deviation_uT = 5.0;
  p.max_reference_dip_deviation_rad = 0.07;
  p.learn_first_s = 5.0;
  p.learn_new_s = 20.0;
  return MagDisturbanceDetector(p);
}

// Samples of 10 ms of one field until the verdict is clean, at most `limit`; how many were disturbed.
int disturbedFor(MagDisturbanceDetector& d, double norm_uT, double dip_rad, int limit) {
  int n = 0;
  while (n < limit && disturbed(d.update(fieldOf(norm_uT), dip_rad, 0.01))) ++n;
  return n;
}

TEST(MagDisturbance, WithoutAPositionALastingChangeIsDisturbedUntilItHasBeenHomogeneousForTheLearningTime) {
  // A lift's steel cabin: 25 µT more for as long as one stands in it. The relative test alone
  // accepts it once the low-pass has followed (ln(25 / 3) τ = 6.4 s); against the learned field
  // it stays disturbed until it has been homogeneous for 20 s, and the field outside is clean
  // again as soon as the relative test says so.
  MagDisturbanceDetector relative = lowPassDetector(), learning = learningDetector();
  for (int i = 0; i < 1000; ++i) {
    ASSERT_FALSE(disturbed(relative.update(fieldOf(49.0), 1.15, 0.01)));
    ASSERT_FALSE(disturbed(learning.update(fieldOf(49.0), 1.15, 0.01)));
  }
  EXPECT_FALSE(relative.hasLearnedReference());
  EXPECT_TRUE(learning.hasLearnedReference());
  EXPECT_LT(disturbedFor(relative, 74.0, 1.15, 10'000), 700);
  int cabin = 0;
  for (int i = 0; i < 1500; ++i) cabin += disturbed(learning.update(fieldOf(74.0), 1.15, 0.01)) ? 1 : 0;
  EXPECT_EQ(cabin, 1500);                                      // 15 s in the cabin: disturbed throughout
  EXPECT_LT(disturbedFor(learning, 49.0, 1.15, 10'000), 700);  // out again: the learned field
  // Staying in a different field: learned after 20 s of it being homogeneous.
  const int lasting = disturbedFor(learning, 60.0, 1.15, 10'000);
  EXPECT_GT(lasting, 1900);
  EXPECT_LT(lasting, 2300);
  EXPECT_FALSE(disturbed(learning.update(fieldOf(60.0), 1.15, 0.01)));
  // A WMM reference replaces the learned field.
  learning.setReference(60.0, 1.15 + 0.2);
  EXPECT_FALSE(learning.hasLearnedReference());
  EXPECT_TRUE(learning.update(fieldOf(60.0), 1.15, 0.01).dip_reference);
}

TEST(MagDisturbance, TheLearnedFieldFollowsASlowDrift) {
  // 8 µT over 200 s (a walk across a building whose field weakens slowly): the learned field
  // lags 0.04 µT/s × 20 s = 0.8 µT behind, far inside the 5 µT bound; never disturbed.
  MagDisturbanceDetector d = learningDetector();
  int flagged = 0;
  for (int i = 0; i < 20'000; ++i) flagged += disturbed(d.update(fieldOf(49.0 - 0.0004 * i), 1.15, 0.01)) ? 1 : 0;
  EXPECT_EQ(flagged, 0);
}

TEST(MagDisturbance, FirstSampleIsNotDisturbed) {
  MagDisturbanceDetector d = lowPassDetector();
  EXPECT_FALSE(disturbed(d.update(fieldOf(500.0), -1.0, 0.01)));
  EXPECT_EQ(d.normDeviation(), 0.0);
  EXPECT_EQ(d.dipDeviation(), 0.0);
}

}  // namespace
}  // namespace headingd::core
