// NetTurn (net_turn.hpp) counts the angle by which the sensor's attitude moves on, not what
// it swings back and forth: a turn counts its angle, a stride's sway or a swung phone counts
// (nearly) nothing, however long it goes on.
#include "headingd/core/net_turn.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kRadPerDeg;

constexpr double kDt = 0.01;

// The angle NetTurn counts while the attitude follows yaw(t), pitch(t), roll(t) for `seconds`.
template <typename Attitude>
double countedOver(double seconds, Attitude attitude) {
  NetTurn turn(2.0, 0.1);
  double counted = 0.0;
  for (int i = 0; i <= static_cast<int>(seconds / kDt); ++i) counted += turn.update(attitude(i * kDt), kDt);
  return counted;
}

TEST(NetTurn, ASwingBackAndForthCountsNothing) {
  // A phone swung in the hand by ±45° once a second, and a walker's sway of ±10° about two
  // axes twice a second, for five minutes, about a tilted mean attitude.
  const double swung = countedOver(300.0, [](double t) {
    return test::fromYawPitchRoll(0.7, 45.0 * kRadPerDeg * std::sin(2.0 * std::numbers::pi * t), 0.2);
  });
  const double swayed = countedOver(300.0, [](double t) {
    const double phase = 4.0 * std::numbers::pi * t;
    return test::fromYawPitchRoll(-1.0 + 10.0 * kRadPerDeg * std::sin(phase), 0.1, 10.0 * kRadPerDeg * std::cos(phase));
  });
  // Over five minutes less than a third of what one quarter turn counts (1.57 rad).
  EXPECT_LT(swung, 0.5);
  EXPECT_LT(swayed, 0.5);
  std::printf("counted over 300 s: swung %.3f rad, swayed %.3f rad\n", swung, swayed);
}

TEST(NetTurn, ATurnCountsItsAngle) {
  // 90° about the vertical in 2 s, then standing still; and a slow 0.05 rad/s turn for 60 s
  // with the stride's sway on top.
  const double quick = countedOver(20.0, [](double t) {
    return test::fromYawPitchRoll(0.5 * std::numbers::pi * std::min(t / 2.0, 1.0), 0.3, -0.1);
  });
  EXPECT_NEAR(quick, 0.5 * std::numbers::pi, 0.1);
  const double slow = countedOver(60.0, [](double t) {
    return test::fromYawPitchRoll(0.05 * t + 10.0 * kRadPerDeg * std::sin(4.0 * std::numbers::pi * t), 0.0, 0.0);
  });
  EXPECT_NEAR(slow, 3.0, 0.3);
}

TEST(NetTurn, CountsEveryAxisAndBothSignsOfTheQuaternion) {
  // A tilt of 60° about the sensor's x axis counts as much as a yaw; q and -q are one attitude.
  NetTurn turn(2.0, 0.1);
  double counted = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = i * kDt;
    Quat q = test::fromYawPitchRoll(0.0, 0.0, 60.0 * kRadPerDeg * std::min(t / 3.0, 1.0));
    if (i % 2 == 1) q.coeffs() = -q.coeffs();
    counted += turn.update(q, kDt);
  }
  EXPECT_NEAR(counted, 60.0 * kRadPerDeg, 0.1);
}

}  // namespace
}  // namespace headingd::core
