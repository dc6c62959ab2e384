// Samples in other units than SI (specific force in g, a field in gauss or nT, a rate in
// degrees per second) are suspected after the first seconds; SI samples, at rest, walking or
// disturbed, are not (core/sensor_units_check.hpp).
#include "headingd/core/sensor_units_check.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace headingd::core {
namespace {

constexpr double kDt = 0.01;

// 12 s of a swaying body: specific force and field turning, their norms about `g` and `field`.
SensorUnitsCheck checked(double g, double field, double rate, bool has_mag = true) {
  SensorUnitsCheck check;
  for (int k = 0; k < 1200; ++k) {
    const double a = 0.3 * std::sin(0.02 * k);
    ImuSample s;
    s.gyro_rad_s = Vec3(rate, 0.1 * std::cos(0.02 * k), 0.0);
    s.accel_m_s2 = g * Vec3(std::sin(a), 0.2 * std::sin(0.5 * k), std::cos(a));
    s.mag_uT = field * Vec3(std::cos(a), std::sin(a), 1.5).normalized();
    s.has_mag = has_mag;
    check.add(s, kDt);
  }
  return check;
}

TEST(SensorUnitsCheck, SiSamplesAreNotSuspected) {
  for (const double field : {22.0, 50.0, 67.0, 150.0}) {  // clean, and disturbed indoors
    const SensorUnitsCheck c = checked(9.81, field, 0.5);
    EXPECT_TRUE(c.decided());
    EXPECT_FALSE(c.accelSuspect() || c.gyroSuspect() || c.magSuspect()) << field << ": " << c.describe();
    EXPECT_EQ(c.describe(), "");
  }
  EXPECT_FALSE(checked(9.81, 0.0, 3.0, false).magSuspect());  // 6-axis: no field to judge
}

TEST(SensorUnitsCheck, OtherUnitsAreSuspectedAndNamed) {
  const SensorUnitsCheck in_g = checked(1.0, 50.0, 0.5);
  EXPECT_TRUE(in_g.accelSuspect());
  EXPECT_NE(in_g.describe().find("the accelerometer's mean norm over the first 10 s is 1"), std::string::npos)
      << in_g.describe();
  EXPECT_NE(in_g.describe().find("(in g?)"), std::string::npos);
  const SensorUnitsCheck in_gauss = checked(9.81, 0.5, 0.5);
  EXPECT_TRUE(in_gauss.magSuspect());
  EXPECT_NE(in_gauss.describe().find("is 0.5, outside the 5-500 uT"), std::string::npos) << in_gauss.describe();
  EXPECT_TRUE(checked(9.81, 50000.0, 0.5).magSuspect());  // nT
  EXPECT_TRUE(checked(9.81, 50.0, 28.6).gyroSuspect());   // 0.5 rad/s read as °/s
  EXPECT_FALSE(checked(9.81, 50.0, 0.5).gyroSuspect());
  // Nothing is decided before the window is full.
  SensorUnitsCheck early;
  ImuSample s;
  s.accel_m_s2 = Vec3(0, 0, 1.0);
  early.add(s, 5.0);
  EXPECT_FALSE(early.decided());
  EXPECT_FALSE(early.accelSuspect());
}

}  // namespace
}  // namespace headingd::core
