// The accelerometer pre-filter that averages longer round a bend (turn_blended_low_pass.hpp):
// a body turning steadily about the vertical with a centripetal acceleration fixed in its
// axes, turns back and forth, fast rotation, and the filter switched off.
#include <gtest/gtest.h>

#include <cmath>

#include "headingd/core/gyro_frame_low_pass.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/turn_blended_low_pass.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 0.01;

// Level body turning at rate_rad_s about NED down with centripetal_m_s2 along its y axis (the
// inside of the bend, a fixed direction in the body). Returns the angle (rad) between the
// filter's output and the specific force of gravity alone after 60 s, and the last weight.
struct BendResult {
  double lean_rad;
  double weight;
};
BendResult roundABend(double short_s, double long_s, double rate_rad_s, double centripetal_m_s2) {
  TurnBlendedLowPass filter(short_s, long_s);
  SteadyTurnWeight turning(short_s, 0.5, 3.5);
  const Vec3 gyro(0.0, 0.0, rate_rad_s);
  const Vec3 down_s = Vec3::UnitZ();
  const Vec3 gravity_b(0.0, 0.0, -kG);  // specific force at rest, level
  const Vec3 accel = gravity_b + Vec3(0.0, centripetal_m_s2, 0.0);
  const Quat increment = gyroIncrement(gyro, kDt);
  Vec3 out = Vec3::Zero();
  double w = 0.0;
  for (int i = 0; i < 6000; ++i) {
    w = turning.update(gyro, down_s, true, kDt);
    out = filter.update(increment, accel, kDt, w);
  }
  return {test::angleBetween(out, gravity_b), w};
}

TEST(TurnBlendedLowPass, RoundABendTheTiltLeansLessIntoTheBend) {
  // 3 m/s at 0.9 rad/s: 2.7 m/s² inward. A low-pass of τ keeps c / √(1 + (Ωτ)²) of it.
  const double c = 3.0 * 0.9;
  const BendResult short_only = roundABend(2.0, 0.0, 0.9, c);
  const BendResult blended = roundABend(2.0, 6.0, 0.9, c);
  const double kept_short = c / std::hypot(1.0, 0.9 * 2.0);
  const double kept_long = c / std::hypot(1.0, 0.9 * 6.0);
  EXPECT_NEAR(short_only.lean_rad, std::atan(kept_short / kG), 0.002);
  EXPECT_NEAR(blended.weight, 1.0, 1e-9);  // 0.9 rad/s is beyond the full-turn rate
  EXPECT_NEAR(blended.lean_rad, std::atan(kept_long / kG), 0.002);
  EXPECT_LT(blended.lean_rad, 0.4 * short_only.lean_rad);
}

TEST(TurnBlendedLowPass, GravityPassesWhateverTheWeight) {
  // Both low-passes keep gravity exactly in the gyro frame, so any blend of them does.
  TurnBlendedLowPass filter(2.0, 6.0);
  test::Random rng(7);
  const Vec3 w(0.8, -1.5, 2.0);
  Quat q = test::fromYawPitchRoll(0.3, 0.4, -0.5);
  for (int i = 0; i < 1000; ++i) {
    q = q * Quat(Eigen::AngleAxisd(w.norm() * kDt, w.normalized()));
    const Vec3 gravity_b = q.inverse() * Vec3(0.0, 0.0, -kG);
    const double weight = rng.uniform(0.0, 1.0);
    EXPECT_LT((filter.update(gyroIncrement(w, kDt), gravity_b, kDt, weight) - gravity_b).norm(), 1e-9) << i;
  }
}

TEST(SteadyTurnWeight, TurnsBackAndForthCountLittle) {
  // A hand turning the sensor ±2 rad/s at 1 Hz about the vertical: the 2 s low-pass keeps
  // 2 / √(1 + (2π · 1 · 2)²) = 0.16 rad/s of its rate, a third of the full-turn rate, and the
  // weight never goes beyond that; at 2 Hz, half as much.
  for (const double hz : {1.0, 2.0}) {
    SteadyTurnWeight turning(2.0, 0.5, 3.5);
    double worst = 0.0;
    for (int i = 0; i < 3000; ++i) {
      const Vec3 gyro(0.0, 0.0, 2.0 * std::sin(2.0 * test::kPi * hz * i * kDt));
      const double w = turning.update(gyro, Vec3::UnitZ(), true, kDt);
      if (i > 1000) worst = std::max(worst, w);
    }
    const double kept = 2.0 / std::hypot(1.0, 2.0 * test::kPi * hz * 2.0);
    EXPECT_NEAR(worst, kept / 0.5, 0.01) << hz << " Hz";
  }
}

TEST(SteadyTurnWeight, GrowsWithTheTurnAndFadesWithFastRotation) {
  const auto settled = [](const Vec3& gyro, const Vec3& down_s) {
    SteadyTurnWeight turning(2.0, 0.5, 3.5);
    double w = 0.0;
    for (int i = 0; i < 3000; ++i) w = turning.update(gyro, down_s, true, kDt);
    return w;
  };
  EXPECT_NEAR(settled(Vec3(0.0, 0.0, 0.25), Vec3::UnitZ()), 0.5, 1e-6);   // half the full-turn rate
  EXPECT_NEAR(settled(Vec3(0.0, 0.0, -0.25), Vec3::UnitZ()), 0.5, 1e-6);  // either way round
  // The vertical is the attitude's, not a sensor axis: a sensor on its side turning about
  // its x axis, which points down.
  EXPECT_NEAR(settled(Vec3(0.4, 0.0, 0.0), Vec3::UnitX()), 0.8, 1e-6);
  // A turn about a horizontal axis is no bend.
  EXPECT_NEAR(settled(Vec3(0.0, 1.0, 0.0), Vec3::UnitZ()), 0.0, 1e-9);
  // 1 rad/s about the vertical with 4.5 rad/s about a horizontal axis: |ω| 4.6 rad/s, a third
  // of the way from 3.5 to 7 rad/s.
  const double fading = settled(Vec3(0.0, 4.5, 1.0), Vec3::UnitZ());
  EXPECT_NEAR(fading, 2.0 - std::hypot(4.5, 1.0) / 3.5, 1e-6);
  EXPECT_NEAR(settled(Vec3(0.0, 7.0, 1.0), Vec3::UnitZ()), 0.0, 1e-9);  // beyond 7 rad/s
}

TEST(SteadyTurnWeight, ASensorTurnedInPlaceIsNoBend) {
  // Turning steadily while the body does not step (standing level): no speed, no bend's
  // acceleration, no weight; once stepping, the weight grows with the low-pass.
  SteadyTurnWeight turning(2.0, 0.5, 3.5);
  const Vec3 gyro(0.0, 0.0, 0.9);
  for (int i = 0; i < 3000; ++i) EXPECT_EQ(turning.update(gyro, Vec3::UnitZ(), false, kDt), 0.0) << i;
  double w = 0.0;
  for (int i = 0; i < 100; ++i) w = turning.update(gyro, Vec3::UnitZ(), true, kDt);
  EXPECT_NEAR(w, 0.9 * (1.0 - std::pow(lowPassAlpha(kDt, 2.0), 100)) / 0.5, 1e-9);
}

TEST(TurnBlendedLowPass, WithoutTheLongTimeConstantItIsTheGyroFrameLowPass) {
  TurnBlendedLowPass blended(2.0, 0.0);
  GyroFrameLowPass plain(2.0, GyroFrameStart::kRunningMean);  // both start as the running mean
  test::Random rng(11);
  for (int i = 0; i < 500; ++i) {
    const Vec3 gyro = rng.vector(-3.0, 3.0);
    const Vec3 a = rng.vector(-20.0, 20.0);
    EXPECT_EQ(blended.update(gyroIncrement(gyro, kDt), a, kDt, 1.0), plain.update(gyro, a, kDt)) << i;
  }
  TurnBlendedLowPass off(0.0, 6.0);  // τ₀ = 0: the raw sample, whatever the weight
  const Vec3 a(1.0, -2.0, -9.0);
  EXPECT_EQ(off.update(Quat::Identity(), a, kDt, 1.0), a);
}

TEST(GyroFrameLowPass, ARunningMeanStartDoesNotCarryItsFirstSample) {
  // A start made in motion (the first sample 10 m/s² off), then 2 s of gravity: started from
  // its first sample a 6 s low-pass still carries exp(-2/6) of the error; started as the
  // running mean, 1/200 of it, and once the running mean is the faster of the two it is the
  // plain low-pass again.
  GyroFrameLowPass first(6.0);
  GyroFrameLowPass mean(6.0, GyroFrameStart::kRunningMean);
  const Vec3 off(0.0, 0.0, -kG - 10.0), gravity(0.0, 0.0, -kG);
  Vec3 y_first = first.update(Vec3::Zero(), off, kDt);
  Vec3 y_mean = mean.update(Vec3::Zero(), off, kDt);
  EXPECT_EQ(y_first, off);
  EXPECT_EQ(y_mean, off);
  for (int i = 1; i < 200; ++i) {
    y_first = first.update(Vec3::Zero(), gravity, kDt);
    y_mean = mean.update(Vec3::Zero(), gravity, kDt);
  }
  EXPECT_NEAR((y_first - gravity).norm(), 10.0 * std::pow(lowPassAlpha(kDt, 6.0), 199), 1e-9);
  EXPECT_NEAR((y_mean - gravity).norm(), 10.0 / 200.0, 1e-9);
  // Once the running mean is the slower of the two (after τ), it is the plain low-pass.
  for (int i = 0; i < 1000; ++i) y_mean = mean.update(Vec3::Zero(), gravity, kDt);
  const Vec3 step(1.0, 0.0, -kG);
  const double alpha = lowPassAlpha(kDt, 6.0);
  EXPECT_LT((mean.update(Vec3::Zero(), step, kDt) - (alpha * y_mean + (1.0 - alpha) * step)).norm(), 1e-12);
}

TEST(TurnBlendedLowPass, RestartForgetsTheHistory) {
  TurnBlendedLowPass filter(2.0, 6.0);
  for (int i = 0; i < 100; ++i) filter.update(Quat::Identity(), Vec3(0.0, 0.0, -kG), kDt, 0.5);
  filter.restart();
  const Vec3 a(1.0, 2.0, -9.0);
  EXPECT_LT((filter.update(Quat::Identity(), a, kDt, 0.5) - a).norm(), 1e-15);
}

}  // namespace
}  // namespace headingd::core
