// Henriksson §3.1 around the EKF: the accelerometer disturbance level d_k and the R level
// chosen from it with hysteresis, the background gyro-only attitudes for back-tracking, and
// the gyroscope bias from rest.
#include <gtest/gtest.h>

#include <vector>

#include "headingd/core/accel_disturbance.hpp"
#include "headingd/core/gyro_frame_low_pass.hpp"
#include "headingd/core/background_attitudes.hpp"
#include "headingd/core/estimator_params.hpp"
#include "headingd/core/gyro_bias_estimator.hpp"
#include "headingd/core/low_pass.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::Random;

constexpr double kG = 9.81;

// ---------------------------------------------------------------- low-pass, d_k (eq. 3.1)

TEST(LowPassAlpha, MatchesHenrikssonEq34) {
  // Eq. 2.17 with the thesis' 121 Hz (T_s = 0.0083 s) and τ = 1 s gives eq. 3.4's α = 0.9918.
  EXPECT_NEAR(lowPassAlpha(0.0083, 1.0), 0.9918, 5e-5);
  EXPECT_NEAR(lowPassAlpha(0.0083, 1.0), std::exp(-0.0083 / 1.0083), 1e-12);
  // Eq. 2.17 at other rates and time constants, small and large T_s/τ.
  for (double dt : {1e-4, 0.0025, 0.01, 0.05, 0.5}) {
    for (double tau : {0.1, 1.0, 3.0, 100.0}) {
      EXPECT_NEAR(lowPassAlpha(dt, tau), std::exp(-dt / (tau + dt)), 1e-12) << dt << " " << tau;
    }
  }
}

TEST(LowPass, FirstInputInitialisesThenEq213) {
  LowPass<double> f(1.0);
  EXPECT_FALSE(f.initialised());
  EXPECT_EQ(f.update(5.0, 0.01), 5.0);
  const double alpha = lowPassAlpha(0.01, 1.0);
  EXPECT_NEAR(f.update(1.0, 0.01), alpha * 5.0 + (1.0 - alpha) * 1.0, 1e-14);
}

TEST(AccelDisturbanceLevel, FollowsEq31) {
  AccelDisturbanceLevel d(kG, 1.0);
  EXPECT_EQ(d.value(), 0.0);
  const double alpha = lowPassAlpha(0.0083, 1.0);
  // |a| = g + 2 along an arbitrary direction: (|a| - g)² = 4.
  const Vec3 a = Vec3(1.0, -2.0, 3.0).normalized() * (kG + 2.0);
  const double d1 = d.update(a, 0.0083);
  EXPECT_NEAR(d1, (1.0 - alpha) * 4.0, 1e-12);
  EXPECT_NEAR(d1, 0.0082 * 4.0, 1e-4);  // 1 - 0.9918 from the thesis
  // |a| = g - 1: (|a| - g)² = 1; the previous value decays with α.
  const double d2 = d.update(Vec3(0.0, 0.0, -(kG - 1.0)), 0.0083);
  EXPECT_NEAR(d2, alpha * d1 + (1.0 - alpha) * 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(d.value(), d2);
}

TEST(AccelDisturbanceLevel, SettlesAtTheSquaredDeviationWithItsTimeConstant) {
  // A constant deviation c: after τ the level is at 1 - 1/e of c², at any sample rate
  // (that is what eq. 2.17's α is for).
  const double c = 3.0;
  for (double dt : {0.0025, 0.0083, 0.02}) {
    AccelDisturbanceLevel d(kG, 1.0);
    const int n = static_cast<int>(std::lround(1.0 / dt));
    for (int i = 0; i < n; ++i) d.update(Vec3(0.0, 0.0, kG + c), dt);
    EXPECT_NEAR(d.value() / (c * c), 1.0 - std::exp(-1.0), 0.01) << "dt " << dt;
    for (int i = 0; i < 20 * n; ++i) d.update(Vec3(0.0, kG + c, 0.0), dt);
    EXPECT_NEAR(d.value(), c * c, 1e-6) << "dt " << dt;
  }
}

TEST(AccelDisturbanceLevel, RestIsZero) {
  AccelDisturbanceLevel d(kG, 1.0);
  for (int i = 0; i < 100; ++i) d.update(Vec3(3.0, 4.0, -std::sqrt(kG * kG - 25.0)), 0.01);
  EXPECT_NEAR(d.value(), 0.0, 1e-20);
}

// ---------------------------------------------------------------- accelerometer pre-filter

TEST(GyroFrameLowPass, ZeroTimeConstantPassesTheRawSample) {
  GyroFrameLowPass f(0.0);
  Random rng(34);
  for (int i = 0; i < 100; ++i) {
    const Vec3 a = rng.vector(-20.0, 20.0);
    EXPECT_EQ(f.update(rng.vector(-3.0, 3.0), a, 0.01), a);
  }
}

TEST(GyroFrameLowPass, GravityPassesWhileTheBodyTurns) {
  // In the gyro-integrated frame gravity is constant, so it comes out unfiltered in the
  // current body axes however fast the body turns.
  GyroFrameLowPass f(2.0);
  const Vec3 w(0.8, -1.5, 2.0);
  const double dt = 0.01;
  Quat q = test::fromYawPitchRoll(0.3, 0.4, -0.5);
  for (int i = 0; i < 1000; ++i) {
    q = q * Quat(Eigen::AngleAxisd(w.norm() * dt, w.normalized()));
    const Vec3 gravity_b = q.inverse() * Vec3(0.0, 0.0, -kG);
    EXPECT_LT((f.update(w, gravity_b, dt) - gravity_b).norm(), 1e-9) << i;
  }
}

TEST(GyroFrameLowPass, AttenuatesOscillatingAcceleration) {
  // 3 m/s² at 2 Hz (steps) on top of gravity, body still: the output keeps gravity and keeps
  // little of the oscillation.
  GyroFrameLowPass f(1.0);
  const double dt = 0.01;
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = Vec3(3.0 * std::sin(2.0 * 2.0 * test::kPi * i * dt), 0.0, -kG);
    const Vec3 out = f.update(Vec3::Zero(), a, dt);
    if (i > 500) worst = std::max(worst, (out - Vec3(0.0, 0.0, -kG)).norm());
  }
  EXPECT_LT(worst, 0.3);  // first order at τ = 1 s: about 3 / (2π·2·1) ≈ 0.24
}

TEST(GyroFrameLowPass, RestartForgetsTheHistory) {
  GyroFrameLowPass f(1.0);
  for (int i = 0; i < 100; ++i) f.update(Vec3(0.0, 0.0, 1.0), Vec3(0.0, 0.0, -kG), 0.01);
  f.restart();
  const Vec3 a(1.0, 2.0, -9.0);
  EXPECT_LT((f.update(Vec3::Zero(), a, 0.01) - a).norm(), 1e-15);
}

// ---------------------------------------------------------------- R levels with hysteresis

TEST(MotionLevelSelector, DefaultThresholdsAreTheThesisValues) {
  const EstimatorParams p;
  EXPECT_EQ(p.disturbance_up_to_walking, 2.0);
  EXPECT_EQ(p.disturbance_up_to_running, 40.0);
  EXPECT_EQ(p.disturbance_down_to_standing, 1.0);
  EXPECT_EQ(p.disturbance_down_to_walking, 20.0);
}

TEST(MotionLevelSelector, StepsUpAndDownWithHysteresis) {
  const EstimatorParams p;
  MotionLevelSelector s(p);
  EXPECT_EQ(s.level(), MotionLevel::kStanding);
  EXPECT_EQ(s.update(1.5), MotionLevel::kStanding);  // between down and up: stays
  EXPECT_EQ(s.update(2.0), MotionLevel::kStanding);  // "above" 2 is strict
  EXPECT_EQ(s.update(2.5), MotionLevel::kWalking);
  EXPECT_EQ(s.update(1.5), MotionLevel::kWalking);   // d = 1.5 after walking stays walking
  EXPECT_EQ(s.update(30.0), MotionLevel::kWalking);  // below the step up to running
  EXPECT_EQ(s.update(41.0), MotionLevel::kRunning);
  EXPECT_EQ(s.update(30.0), MotionLevel::kRunning);  // between 20 and 40: stays running
  EXPECT_EQ(s.update(19.0), MotionLevel::kWalking);
  EXPECT_EQ(s.update(1.0), MotionLevel::kWalking);   // "below" 1 is strict
  EXPECT_EQ(s.update(0.9), MotionLevel::kStanding);  // d = 0.9 goes to standing
  EXPECT_EQ(s.level(), MotionLevel::kStanding);
}

TEST(MotionLevelSelector, MovesOneLevelPerSample) {
  const EstimatorParams p;
  MotionLevelSelector s(p);
  EXPECT_EQ(s.update(100.0), MotionLevel::kWalking);
  EXPECT_EQ(s.update(100.0), MotionLevel::kRunning);
  EXPECT_EQ(s.update(0.0), MotionLevel::kWalking);
  EXPECT_EQ(s.update(0.0), MotionLevel::kStanding);
}

TEST(MotionLevelSelector, UsesTheConfiguredThresholds) {
  EstimatorParams p;
  p.disturbance_up_to_walking = 5.0;
  p.disturbance_down_to_standing = 4.0;
  MotionLevelSelector s(p);
  EXPECT_EQ(s.update(4.5), MotionLevel::kStanding);
  EXPECT_EQ(s.update(5.5), MotionLevel::kWalking);
  EXPECT_EQ(s.update(4.5), MotionLevel::kWalking);
  EXPECT_EQ(s.update(3.5), MotionLevel::kStanding);
}

TEST(MotionLevel, AccelNoiseForEachLevelAndNames) {
  EstimatorParams p;
  p.accel_noise_standing_m_s2 = 0.1;
  p.accel_noise_walking_m_s2 = 0.2;
  p.accel_noise_running_m_s2 = 0.3;
  EXPECT_EQ(accelNoiseFor(MotionLevel::kStanding, p), 0.1);
  EXPECT_EQ(accelNoiseFor(MotionLevel::kWalking, p), 0.2);
  EXPECT_EQ(accelNoiseFor(MotionLevel::kRunning, p), 0.3);
  // Defaults step by the thesis' factor 10 in variance.
  const EstimatorParams d;
  EXPECT_NEAR(std::pow(d.accel_noise_walking_m_s2 / d.accel_noise_standing_m_s2, 2), 10.0, 0.02);
  EXPECT_NEAR(std::pow(d.accel_noise_running_m_s2 / d.accel_noise_walking_m_s2, 2), 10.0, 0.02);
  EXPECT_STREQ(motionLevelName(MotionLevel::kStanding), "standing");
  EXPECT_STREQ(motionLevelName(MotionLevel::kWalking), "walking");
  EXPECT_STREQ(motionLevelName(MotionLevel::kRunning), "running");
}

// ---------------------------------------------------------------- background attitudes

TEST(BackgroundAttitudes, RestartStaggersByHalfAPeriod) {
  BackgroundAttitudes b(10.0);
  const Quat q = test::fromYawPitchRoll(0.3, 0.2, 0.1);
  b.restart(q);
  EXPECT_DOUBLE_EQ(b.oldestAge(), 5.0);
  EXPECT_EQ(b.oldest().coeffs(), q.coeffs());
}

TEST(BackgroundAttitudes, FirstUpdateStartsFromTheEstimate) {
  BackgroundAttitudes b(10.0);
  const Quat q = test::fromYawPitchRoll(-1.0, 0.2, 0.1);
  b.update(Vec3(1.0, 2.0, 3.0), 0.01, q);
  EXPECT_EQ(b.oldest().coeffs(), q.coeffs());
  EXPECT_DOUBLE_EQ(b.oldestAge(), 5.0);
}

TEST(BackgroundAttitudes, IntegratesTheGyroAloneIgnoringTheEstimate) {
  BackgroundAttitudes b(10.0);
  const Quat q0 = test::fromYawPitchRoll(0.5, -0.1, 0.3);
  b.restart(q0);
  const Vec3 w(0.2, -0.5, 0.9);
  const double dt = 0.01;
  for (int i = 0; i < 300; ++i) b.update(w, dt, Quat::Identity());  // estimate is elsewhere
  const Quat expected = q0 * Quat(Eigen::AngleAxisd(w.norm() * 3.0, w.normalized()));
  EXPECT_LT(test::angleBetween(b.oldest(), expected), 1e-10);
  EXPECT_NEAR(b.oldestAge(), 8.0, 1e-9);
}

TEST(BackgroundAttitudes, ResetsAreStaggeredAndTheOldestIsAtLeastHalfAPeriodOld) {
  const double period = 10.0, dt = 0.01;
  BackgroundAttitudes b(period);
  const Vec3 w(0.0, 0.3, -0.2);
  std::vector<Quat> estimates;  // the estimate handed in at each step
  auto estimateAt = [](int k) { return headingRotation(0.01 * k) * test::fromYawPitchRoll(0.0, 0.1, 0.2); };
  estimates.push_back(estimateAt(0));
  b.restart(estimates[0]);

  int resets_seen = 0;
  double last_age = b.oldestAge();
  for (int k = 1; k <= 2900; ++k) {  // 29 s
    estimates.push_back(estimateAt(k));
    b.update(w, dt, estimates.back());
    const double age = b.oldestAge();
    EXPECT_GE(age, 0.5 * period - 1e-9) << "step " << k;
    EXPECT_LT(age, period) << "step " << k;
    if (age < last_age) {
      // The other one was just reset; the oldest is the one reset half a period ago, from the
      // estimate of that step, and integrated with the gyro since.
      ++resets_seen;
      const int steps = static_cast<int>(std::lround(age / dt));
      const Quat expected = estimates[k - steps] * Quat(Eigen::AngleAxisd(w.norm() * steps * dt, w.normalized()));
      EXPECT_LT(test::angleBetween(b.oldest(), expected), 1e-9) << "step " << k;
      EXPECT_NEAR(age, 0.5 * period, 2 * dt);
    }
    last_age = age;
  }
  EXPECT_EQ(resets_seen, 5);  // at 5, 10, 15, 20 and 25 s
}

// ---------------------------------------------------------------- gyro bias from rest

struct RestSamples {
  Vec3 bias;
  double gyro_noise;
  Random rng{31};
  Vec3 gyro() { return bias + rng.gaussian(gyro_noise); }
  Vec3 accel() { return Vec3(0.3, -0.2, -std::sqrt(kG * kG - 0.13)) + rng.gaussian(0.02); }
};

TEST(GyroBiasEstimator, EstimatesAConstantBiasAtRest) {
  const EstimatorParams p;
  GyroBiasEstimator est(p);
  RestSamples rest{Vec3(0.01, -0.02, 0.005), 0.0005};
  const double dt = 0.01;
  EXPECT_FALSE(est.atRest());
  for (int i = 0; i < 600; ++i) est.update(rest.gyro(), rest.accel(), dt);  // 6 s
  EXPECT_TRUE(est.atRest());
  EXPECT_GT(est.restSeconds(), 4.0);
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(est.bias()(axis), rest.bias(axis), 1e-4) << "axis " << axis;
}

TEST(GyroBiasEstimator, RestNeedsTheMinimumDuration) {
  const EstimatorParams p;  // rest_min_duration_s = 1.5
  GyroBiasEstimator est(p);
  RestSamples rest{Vec3(0.01, 0.0, 0.0), 0.0005};
  for (int i = 0; i < 140; ++i) est.update(rest.gyro(), rest.accel(), 0.01);
  EXPECT_FALSE(est.atRest());
  EXPECT_EQ(est.bias(), Vec3::Zero());
  for (int i = 0; i < 20; ++i) est.update(rest.gyro(), rest.accel(), 0.01);
  EXPECT_TRUE(est.atRest());
}

TEST(GyroBiasEstimator, BiasAboveTheRestThresholdButWithinTheClampIsLearnedFromColdStart) {
  // RestDetector's contract: "a bias larger than the threshold must not keep the detector
  // from ever seeing rest". 0.05 rad/s (2.9°/s, common for uncalibrated MEMS) is above
  // rest_gyro_threshold_rad_s (0.035) and below bias_max_rad_s (0.1).
  const EstimatorParams p;
  GyroBiasEstimator est(p);
  RestSamples rest{Vec3(0.04, -0.02, 0.02), 0.0005};
  for (int i = 0; i < 1000; ++i) est.update(rest.gyro(), rest.accel(), 0.01);  // 10 s at rest
  EXPECT_TRUE(est.atRest());
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(est.bias()(axis), rest.bias(axis), 1e-3) << "axis " << axis;
}

TEST(GyroBiasEstimator, MotionIsNotRest) {
  const EstimatorParams p;
  GyroBiasEstimator est(p);
  Random rng(32);
  const double dt = 0.01;
  for (int i = 0; i < 1000; ++i) {
    const double t = i * dt;
    // Hand-held motion: rates of ~1 rad/s that change, accelerations of a few m/s².
    const Vec3 gyro(std::sin(2.0 * t), std::cos(1.3 * t), 0.5 * std::sin(3.1 * t));
    const Vec3 accel = Vec3(2.0 * std::sin(5.0 * t), 0.0, -kG) + rng.gaussian(0.3);
    est.update(gyro, accel, dt);
    EXPECT_FALSE(est.atRest()) << "t " << t;
  }
  EXPECT_EQ(est.bias(), Vec3::Zero());
  EXPECT_EQ(est.restSeconds(), 0.0);
}

TEST(GyroBiasEstimator, ASteadySlowTurnIsNotRest) {
  // A turn faster than any plausible bias (bias_max_rad_s) is not rest from a cold start...
  const EstimatorParams p;
  GyroBiasEstimator cold(p);
  Random rng(33);
  for (int i = 0; i < 1000; ++i) {
    cold.update(Vec3(0.0, 0.0, 1.5 * p.bias_max_rad_s) + rng.gaussian(0.0005), Vec3(0, 0, -kG) + rng.gaussian(0.02),
                0.01);
    EXPECT_FALSE(cold.atRest()) << i;
  }
  EXPECT_EQ(cold.bias(), Vec3::Zero());

  // ...and once the bias is known, a steady turn of a few °/s on top of it is not rest either.
  GyroBiasEstimator warm(p);
  RestSamples rest{Vec3(0.01, 0.0, -0.01), 0.0005};
  for (int i = 0; i < 500; ++i) warm.update(rest.gyro(), rest.accel(), 0.01);
  ASSERT_TRUE(warm.atRest());
  const Vec3 learned = warm.bias();
  for (int i = 0; i < 1000; ++i) warm.update(rest.gyro() + Vec3(0.0, 0.0, 0.05), rest.accel(), 0.01);
  EXPECT_FALSE(warm.atRest());
  EXPECT_LT((warm.bias() - learned).norm(), 2e-3);  // at most the first moments of the turn leak in
}

TEST(GyroBiasEstimator, BiasIsHeldDuringMotion) {
  const EstimatorParams p;
  GyroBiasEstimator est(p);
  RestSamples rest{Vec3(-0.015, 0.01, 0.02), 0.0005};
  const double dt = 0.01;
  for (int i = 0; i < 500; ++i) est.update(rest.gyro(), rest.accel(), dt);
  ASSERT_TRUE(est.atRest());
  const Vec3 learned = est.bias();
  const double rest_seconds = est.restSeconds();
  for (int i = 0; i < 500; ++i) {
    const double t = i * dt;
    const Vec3 gyro = rest.bias + Vec3(1.5 * std::sin(2.0 * t), 0.8, -0.4 * std::cos(t));
    const Vec3 accel(3.0 * std::sin(4.0 * t), 1.0, -kG + 2.0 * std::cos(6.0 * t));
    EXPECT_EQ(est.update(gyro, accel, dt), learned) << "t " << t;
  }
  EXPECT_FALSE(est.atRest());
  EXPECT_EQ(est.restSeconds(), rest_seconds);
}

TEST(GyroBiasEstimator, BiasFollowsADriftAtRest) {
  // After the first rest, the low-pass (τ = bias_time_constant_s) follows a slow change.
  const EstimatorParams p;
  GyroBiasEstimator est(p);
  RestSamples rest{Vec3(0.01, 0.0, 0.0), 0.0005};
  for (int i = 0; i < 500; ++i) est.update(rest.gyro(), rest.accel(), 0.01);
  rest.bias = Vec3(0.015, 0.0, 0.0);
  const int ten_tau = static_cast<int>(10.0 * p.bias_time_constant_s / 0.01);
  for (int i = 0; i < ten_tau; ++i) est.update(rest.gyro(), rest.accel(), 0.01);
  EXPECT_NEAR(est.bias().x(), 0.015, 1e-4);
}

}  // namespace
}  // namespace headingd::core
