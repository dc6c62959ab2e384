// Henriksson §3.1 around the EKF: the accelerometer disturbance level d_k and the R level
// chosen from it with hysteresis, and the gyro-frame low-pass of the accelerometer.
#include <gtest/gtest.h>

#include <vector>

#include "headingd/core/accel_disturbance.hpp"
#include "headingd/core/estimator_params.hpp"
#include "headingd/core/gyro_frame_low_pass.hpp"
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

TEST(MotionLevel, Names) {
  EXPECT_STREQ(motionLevelName(MotionLevel::kStanding), "standing");
  EXPECT_STREQ(motionLevelName(MotionLevel::kWalking), "walking");
  EXPECT_STREQ(motionLevelName(MotionLevel::kRunning), "running");
}

}  // namespace
}  // namespace headingd::core
