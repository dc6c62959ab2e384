// The pieces of the true-heading pipeline (issue 4): noise floor, mounting yaw from the
// gait, declination from course minus heading (Henriksson eqs. 5.1-5.2), fusion of sources.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "headingd/core/declination_estimator.hpp"
#include "headingd/core/gait_mount_yaw.hpp"
#include "headingd/core/noise_floor.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

constexpr double kRad = std::numbers::pi / 180.0;

TEST(NoiseFloor, IsTheQuietestSecondOfTheLastMinute) {
  NoiseFloor floor(1.0);
  EXPECT_EQ(floor.threshold(3.0, 0.5, 10.0), 0.5);  // warm-up: the configured minimum
  for (int i = 0; i < 1000; ++i) floor.update(i < 500 ? 0.2 : 1.0, 0.01);  // quiet, then noisy
  EXPECT_DOUBLE_EQ(floor.value(), 0.2);
  EXPECT_NEAR(floor.threshold(3.0, 0.1, 10.0), 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(floor.threshold(3.0, 1.0, 10.0), 1.0);  // never below the minimum
  EXPECT_DOUBLE_EQ(floor.threshold(3.0, 0.1, 0.3), 0.3);   // nor above the maximum
  for (int i = 0; i < 7000; ++i) floor.update(1.0, 0.01);  // the quiet part leaves the window
  EXPECT_DOUBLE_EQ(floor.value(), 1.0);
}

// Walking in body axes: forward-backward acceleration at the step rate, sideways sway at
// half of it (smaller), vertical bounce; the IMU is turned by mount_yaw about body down.
void walk(GaitMountYawEstimator& gait, double mount_yaw_rad, double heading_rad, double seconds) {
  const Quat q_body = headingRotation(heading_rad);
  const Quat q_sensor = q_body * Quat(Eigen::AngleAxisd(mount_yaw_rad, Vec3::UnitZ()));
  const double dt = 0.01, step_hz = 1.9;
  for (double t = 0.0; t < seconds; t += dt) {
    const double phase = 2.0 * std::numbers::pi * step_hz * t;
    const Vec3 accel_body(1.5 * std::sin(phase), 0.6 * std::sin(0.5 * phase), 2.0 * std::cos(phase));
    const Vec3 specific_force_n = q_body * accel_body - Vec3(0.0, 0.0, 9.81);
    gait.update(q_sensor, q_sensor.conjugate() * specific_force_n, dt, 9.81);
  }
}

TEST(GaitMountYaw, RecoversTheMountingYawFromSteps) {
  for (const double mount_deg : {-40.0, -3.0, 0.0, 3.0, 25.0}) {
    GaitMountYawEstimator gait;
    EXPECT_FALSE(gait.hasEstimate());
    walk(gait, mount_deg * kRad, 1.2, 60.0);
    ASSERT_TRUE(gait.hasEstimate());
    EXPECT_NEAR(gait.mountYawRad() / kRad, mount_deg, 0.2) << mount_deg;
    // Batch means over 10 s blocks: every block of this noise-free walk gives the same axis.
    EXPECT_LT(gait.sigmaRad() / kRad, 0.5);
  }
}

TEST(GaitMountYaw, DoesNotDependOnTheWalkingDirection) {
  GaitMountYawEstimator gait;
  for (const double heading_deg : {0.0, 90.0, 180.0, 270.0}) walk(gait, 5.0 * kRad, heading_deg * kRad, 10.0);
  EXPECT_NEAR(gait.mountYawRad() / kRad, 5.0, 0.2);
}

TEST(CourseMinusHeading, AveragesOverDirectionsEq51) {
  CourseMinusHeading estimator(30.0 * kRad, 10);
  AngleEstimate e;
  EXPECT_FALSE(estimator.estimate(&e));
  test::Random rng(7);
  // Declination minus mounting yaw of 6°, with a direction-dependent error of ±2° that
  // eq. 5.1's mean over the four directions cancels.
  const double directions[] = {0.0, 90.0, 180.0, -90.0};
  const double direction_error[] = {2.0, -2.0, 2.0, -2.0};
  for (int d = 0; d < 4; ++d) {
    for (int j = 0; j < (d + 1) * 20; ++j) {  // unequal numbers of epochs per direction
      const double course = directions[d] * kRad + rng.normal(0.03);
      estimator.add(course, course - (6.0 + direction_error[d]) * kRad + rng.normal(0.02));
    }
  }
  ASSERT_TRUE(estimator.estimate(&e));
  EXPECT_EQ(estimator.directions(), 4);
  EXPECT_NEAR(e.value_rad / kRad, 6.0, 0.4);  // 1.15° noise per epoch, ≥ 20 epochs per direction
  EXPECT_GT(e.sigma_rad, 0.0);
}

TEST(FuseAngles, InverseVarianceAcrossPlusMinus180) {
  const AngleEstimate two[] = {{179.0 * kRad, 1.0 * kRad}, {-179.0 * kRad, 1.0 * kRad}};
  const AngleEstimate fused = fuseAngles(two);
  EXPECT_NEAR(std::abs(fused.value_rad) / kRad, 180.0, 1e-9);
  EXPECT_NEAR(fused.sigma_rad / kRad, 1.0 / std::sqrt(2.0), 1e-9);
  const AngleEstimate unequal[] = {{10.0 * kRad, 1.0 * kRad}, {20.0 * kRad, 3.0 * kRad}};
  const AngleEstimate weighted = fuseAngles(unequal);
  EXPECT_NEAR(weighted.value_rad / kRad, 11.0, 1e-9);  // weights 9:1
  EXPECT_TRUE(std::isinf(fuseAngles({}).sigma_rad));
}

}  // namespace
}  // namespace headingd::core
