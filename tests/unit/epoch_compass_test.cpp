// EpochCompass: the tilt-compensated heading from the means of one GPS epoch interval.
#include "headingd/core/epoch_compass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {
namespace {

const Vec3 kFieldNed(15.0, 0.0, 49.0);  // µT, magnetic north, dip ~73° (Stockholm)
const Vec3 kSpecificForceNed(0.0, 0.0, -9.81);

Quat attitude(double roll, double pitch, double yaw) {
  return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
              Eigen::AngleAxisd(roll, Vec3::UnitX()));
}

TEST(EpochCompass, TiltedStillSensorGivesItsHeading) {
  EpochCompass compass;
  const Quat q = attitude(8.0 * kRadPerDeg, -12.0 * kRadPerDeg, 123.0 * kRadPerDeg);
  const Vec3 mag = q.conjugate() * kFieldNed, accel = q.conjugate() * kSpecificForceNed;
  for (int i = 0; i < 100; ++i) compass.add(Vec3::Zero(), accel, &mag, 0.01);
  const auto heading = compass.takeHeading(50, 0.1);
  ASSERT_TRUE(heading.has_value());
  EXPECT_NEAR(*heading, 123.0 * kRadPerDeg, 1e-9);
}

// The sensor turns 30° about down during the interval while its accelerometer sees an
// oscillating acceleration: the heading is the mean over the interval's samples (the way a
// receiver's course is the mean over the interval), and the oscillation (a whole number of
// periods) leaves the tilt alone.
TEST(EpochCompass, TurningAndAcceleratingSensorGivesItsMeanHeading) {
  EpochCompass compass;
  const double rate = 30.0 * kRadPerDeg;  // rad/s, for 1 s
  for (int i = 1; i <= 100; ++i) {
    const double t = 0.01 * i;
    const Quat q = attitude(5.0 * kRadPerDeg, 3.0 * kRadPerDeg, 40.0 * kRadPerDeg + rate * t);
    const Vec3 body_rate = Vec3(0.0, 0.0, rate);  // about NED down; in body axes:
    const Vec3 gyro = attitude(5.0 * kRadPerDeg, 3.0 * kRadPerDeg, 0.0).conjugate() * body_rate;
    const Vec3 walking_n(2.0 * std::sin(2.0 * std::numbers::pi * 2.0 * t), 0.0,
                         1.5 * std::cos(2.0 * std::numbers::pi * 2.0 * t));
    const Vec3 accel = q.conjugate() * (kSpecificForceNed + walking_n), mag = q.conjugate() * kFieldNed;
    compass.add(gyro, accel, &mag, 0.01);
  }
  const auto heading = compass.takeHeading(50, 0.1);
  ASSERT_TRUE(heading.has_value());
  EXPECT_NEAR(*heading, (40.0 + 30.0 * 0.505) * kRadPerDeg, 0.05 * kRadPerDeg);  // mean of t_i = 0.01 … 1.00 is 0.505 s
}

TEST(EpochCompass, TooFewSamplesOrNoFieldGiveNothingAndStartAnInterval) {
  EpochCompass compass;
  const Vec3 mag = kFieldNed, accel = kSpecificForceNed;
  for (int i = 0; i < 10; ++i) compass.add(Vec3::Zero(), accel, &mag, 0.01);
  EXPECT_FALSE(compass.takeHeading(50, 0.1).has_value());
  for (int i = 0; i < 100; ++i) compass.add(Vec3::Zero(), accel, nullptr, 0.01);
  EXPECT_FALSE(compass.takeHeading(50, 0.1).has_value());  // no magnetometer sample
  for (int i = 0; i < 100; ++i) compass.add(Vec3::Zero(), accel, i % 5 == 0 ? &mag : nullptr, 0.01);
  ASSERT_TRUE(compass.takeHeading(50, 0.1).has_value());  // a slower magnetometer is fine
  const Vec3 vertical_field(0.0, 0.0, 50.0);              // at a magnetic pole: no horizontal field
  for (int i = 0; i < 100; ++i) compass.add(Vec3::Zero(), accel, &vertical_field, 0.01);
  EXPECT_FALSE(compass.takeHeading(50, 0.1).has_value());
}

}  // namespace
}  // namespace headingd::core
