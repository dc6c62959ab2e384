// Where the accelerometer saturates, learned from the readings (accel_clipping.hpp): the
// limit of an axis that clips is found, every clipped reading is flagged, and readings that
// pile up near their largest value for another reason (a shaken sensor's sinusoid, gravity at
// rest) or a heavy tail that reaches far are not taken for clipping.
#include "headingd/core/accel_clipping.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::Random;

constexpr double kG = 9.80665;
constexpr double kDt = 0.01;  // 100 Hz

// A runner's phone along the arm: gravity on -x, and at every stride (0.35 s) an impact of
// 1-4 g more along -x, half a sine 0.1 s long, plus 0.5 m/s² of noise on each axis.
Vec3 runningReading(double t_s, Random& rng, const std::vector<double>& impact_g) {
  constexpr double kStrideS = 0.35;
  const auto stride = static_cast<std::size_t>(t_s / kStrideS);
  const double in_stride = t_s - static_cast<double>(stride) * kStrideS;
  const double peak = impact_g[stride % impact_g.size()] * kG;
  const double impact = in_stride < 0.1 ? peak * std::sin(std::numbers::pi * in_stride / 0.1) : 0.0;
  return Vec3(-kG - impact, 0.0, 0.0) + rng.vector(-0.5, 0.5);
}

std::vector<double> impacts(Random& rng) {
  std::vector<double> g(400);
  for (double& x : g) x = rng.uniform(1.0, 4.0);
  return g;
}

Vec3 clippedAt(const Vec3& v, double full_scale) { return v.cwiseMax(-full_scale).cwiseMin(full_scale); }

TEST(AccelClipDetector, FindsTheLimitOfAnAxisThatClipsAndFlagsEveryClippedReading) {
  Random rng(5);
  const std::vector<double> g = impacts(rng);
  AccelClipDetector detector;
  const double full_scale = 2.0 * kG;
  int clipped = 0, flagged_clipped = 0, flagged_other = 0;
  for (int k = 0; k < 6000; ++k) {
    const double t = k * kDt;
    const Vec3 reading = clippedAt(runningReading(t, rng, g), full_scale);
    const Vec3 flags = detector.update(reading, kDt);
    if (t < 5.0) continue;  // learning
    const bool is_clipped = reading.x() <= -full_scale;
    clipped += is_clipped;
    flagged_clipped += is_clipped && flags.x() == -1.0;
    flagged_other += !is_clipped && !flags.isZero();
    EXPECT_EQ(flags.y(), 0.0);
    EXPECT_EQ(flags.z(), 0.0);
  }
  ASSERT_GT(clipped, 500);
  EXPECT_EQ(flagged_clipped, clipped);
  EXPECT_LT(flagged_other, clipped / 5);  // only readings within 6 % of the limit
  EXPECT_GT(detector.clipFrom(0, true), 0.93 * full_scale);
  EXPECT_LE(detector.clipFrom(0, true), full_scale);
  EXPECT_EQ(detector.clipFrom(0, false), std::numeric_limits<double>::infinity());
}

TEST(AccelClipDetector, TheSameRunReadToEightGIsNotClipped) {
  Random rng(5);
  const std::vector<double> g = impacts(rng);
  AccelClipDetector detector;
  for (int k = 0; k < 6000; ++k) {
    EXPECT_TRUE(detector.update(clippedAt(runningReading(k * kDt, rng, g), 8.0 * kG), kDt).isZero()) << k;
  }
  EXPECT_EQ(detector.clipFrom(0, true), std::numeric_limits<double>::infinity());
}

TEST(AccelClipDetector, AShakenSensorsSinusoidIsNotClipping) {
  // A sinusoid spends most of its time near its peaks (its values' density grows towards
  // them): 11 % of the samples within 6 % of the amplitude, 2.4 times as many as in the 6 %
  // below. Clipping piles far more up.
  Random rng(7);
  for (const double frequency_hz : {1.0, 2.5, 4.0}) {
    for (const double amplitude_g : {2.0, 3.0, 6.0}) {
      AccelClipDetector detector;
      int flagged = 0;
      for (int k = 0; k < 12000; ++k) {
        const double t = k * kDt;
        const Vec3 reading(amplitude_g * kG * std::sin(2.0 * std::numbers::pi * frequency_hz * t), 0.0, -kG);
        flagged += !detector.update(reading + rng.vector(-0.05, 0.05), kDt).isZero();
      }
      EXPECT_EQ(flagged, 0) << frequency_hz << " Hz, " << amplitude_g << " g";
    }
  }
}

TEST(AccelClipDetector, RestAndNonFiniteReadingsFlagNothing) {
  Random rng(9);
  AccelClipDetector detector;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3000; ++k) {
    EXPECT_TRUE(detector.update(Vec3(0.0, 0.0, -kG) + rng.vector(-0.05, 0.05), kDt).isZero());
    EXPECT_TRUE(detector.update(Vec3(nan, -nan, nan), kDt).isZero());
    EXPECT_TRUE(detector.update(Vec3(inf, -inf, 1e308), kDt).isZero());
  }
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(detector.clipFrom(axis, false), inf);
    EXPECT_EQ(detector.clipFrom(axis, true), inf);
  }
}

TEST(AccelClipDetector, AnAxisStuckBeyondOneAndAHalfGIsAtItsLimit) {
  // A reading that does not move at all is an axis at its rail: after the first second's
  // count it is flagged.
  AccelClipDetector detector;
  int flagged = 0;
  for (int k = 0; k < 300; ++k) flagged += detector.update(Vec3(0.0, 30.0, -kG), kDt).y() == 1.0;
  EXPECT_GE(flagged, 190);
  EXPECT_LE(detector.clipFrom(1, false), 30.0);
}

}  // namespace
}  // namespace headingd::core
