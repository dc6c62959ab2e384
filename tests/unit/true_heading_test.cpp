// The pieces of the true-heading pipeline: noise floor, mounting yaw from the
// gait, declination from course minus heading (Henriksson eqs. 5.1-5.2), fusion of sources.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/core/declination_estimator.hpp"
#include "headingd/core/gait_mount_yaw.hpp"
#include "headingd/core/noise_floor.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

TEST(NoiseFloor, IsTheQuietestSecondOfTheLastMinute) {
  NoiseFloor floor(1.0);
  EXPECT_EQ(floor.threshold(3.0, 0.5, 10.0), 0.5);                         // warm-up: the configured minimum
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
    gait.update(Vec3::Zero(), q_sensor.conjugate() * specific_force_n, dt);  // not turning
  }
}

TEST(GaitMountYaw, RecoversTheMountingYawFromSteps) {
  for (const double mount_deg : {-40.0, -3.0, 0.0, 3.0, 25.0}) {
    GaitMountYawEstimator gait;
    EXPECT_FALSE(gait.hasEstimate());
    walk(gait, mount_deg * kRadPerDeg, 1.2, 60.0);
    ASSERT_TRUE(gait.hasEstimate());
    EXPECT_NEAR(gait.mountYawRad() / kRadPerDeg, mount_deg, 0.2) << mount_deg;
    // Batch means over 10 s blocks: every block of this noise-free walk gives the same axis.
    EXPECT_LT(gait.sigmaRad() / kRadPerDeg, 0.5);
  }
}

TEST(GaitMountYaw, DoesNotDependOnTheWalkingDirection) {
  GaitMountYawEstimator gait;
  for (const double heading_deg : {0.0, 90.0, 180.0, 270.0})
    walk(gait, 5.0 * kRadPerDeg, heading_deg * kRadPerDeg, 10.0);
  EXPECT_NEAR(gait.mountYawRad() / kRadPerDeg, 5.0, 0.2);
}

// A trunk that is pitched forward and yaws ±3° at half the step rate while it walks, the
// gyro reporting every rotation: the estimate uses no attitude estimate, only the gyro frame
// and the window's mean specific force, so neither the tilt nor the yawing may move it.
TEST(GaitMountYaw, TiltedYawingTrunkGivesTheMountingYaw) {
  for (const double mount_deg : {0.0, 3.0, -7.0}) {
    GaitMountYawEstimator gait;
    const Quat mount(Eigen::AngleAxisd(mount_deg * kRadPerDeg, Vec3::UnitZ()));
    const double dt = 0.01, step_hz = 1.9, path_heading = 0.7;
    // Step phase of a cadence that wanders by ±3 % (a fixed cadence would put every 4 s
    // window at one of five step phases, and the windows' leftovers would not average out).
    const auto step_phase = [&](double t) {
      constexpr double kWander = 2.0 * std::numbers::pi * 0.05;
      return 2.0 * std::numbers::pi * step_hz * (t - 0.03 * (std::cos(kWander * t) - 1.0) / kWander);
    };
    const auto sensor_at = [&](double t) {
      const double phase = step_phase(t);
      const double yaw = path_heading + 3.0 * kRadPerDeg * std::cos(0.5 * phase);
      const double pitch = (-8.0 + 1.5 * std::sin(phase)) * kRadPerDeg, roll = 2.0 * kRadPerDeg * std::sin(0.5 * phase);
      return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                  Eigen::AngleAxisd(roll, Vec3::UnitX())) *
             mount;
    };
    for (double t = dt; t < 60.0; t += dt) {
      const Quat q_previous = sensor_at(t - dt), q = sensor_at(t);
      const Eigen::AngleAxisd turn(q_previous.conjugate() * q);  // sensor axes
      const Vec3 gyro = turn.angle() / dt * turn.axis();
      const double phase = step_phase(t);
      const Vec3 accel_path(1.7 * std::sin(phase), 0.9 * std::sin(0.5 * phase), 2.8 * std::cos(phase));
      const Vec3 specific_force_n = headingRotation(path_heading) * accel_path - Vec3(0.0, 0.0, 9.81);
      gait.update(gyro, q.conjugate() * specific_force_n, dt);
    }
    ASSERT_TRUE(gait.hasEstimate());
    // The mounting yaw seen on the horizontal plane (what turns the heading): a turn μ about
    // a body axis pitched by 8° appears as atan(tan μ / cos 8°) there.
    const double horizontal_deg =
        std::atan2(std::sin(mount_deg * kRadPerDeg), std::cos(mount_deg * kRadPerDeg) * std::cos(8.0 * kRadPerDeg)) /
        kRadPerDeg;
    EXPECT_NEAR(gait.mountYawRad() / kRadPerDeg, horizontal_deg, 0.05) << mount_deg;
  }
}

TEST(GaitMountYaw, RestartDropsTheOpenWindowOnly) {
  GaitMountYawEstimator gait;
  walk(gait, 4.0 * kRadPerDeg, 0.0, 30.0);
  const double before = gait.mountYawRad(), seconds = gait.walkingSeconds();
  gait.restart();
  walk(gait, 40.0 * kRadPerDeg, 0.0, 3.0);  // shorter than a window: never counts
  gait.restart();
  EXPECT_DOUBLE_EQ(gait.walkingSeconds(), seconds);
  EXPECT_DOUBLE_EQ(gait.mountYawRad(), before);
}

TEST(CourseMinusHeading, AveragesOverDirectionsEq51) {
  CourseMinusHeading estimator(30.0 * kRadPerDeg, 10);
  AngleEstimate e;
  EXPECT_FALSE(estimator.estimate(&e));
  test::Random rng(7);
  // Declination minus mounting yaw of 6°, with a direction-dependent error of ±2° that
  // eq. 5.1's mean over the four directions cancels.
  const double directions[] = {0.0, 90.0, 180.0, -90.0};
  const double direction_error[] = {2.0, -2.0, 2.0, -2.0};
  for (int d = 0; d < 4; ++d) {
    for (int j = 0; j < (d + 1) * 20; ++j) {  // unequal numbers of epochs per direction
      const double course = directions[d] * kRadPerDeg + rng.normal(0.03);
      estimator.add(course, course - (6.0 + direction_error[d]) * kRadPerDeg + rng.normal(0.02), j > 0);
    }
  }
  ASSERT_TRUE(estimator.estimate(&e));
  EXPECT_EQ(estimator.directions(), 4);
  EXPECT_NEAR(e.value_rad / kRadPerDeg, 6.0, 0.4);  // 1.15° noise per epoch, ≥ 20 epochs per direction
  EXPECT_GT(e.sigma_rad, 0.0);
}

// Course noise correlated from epoch to epoch (a receiver's velocity error, first-order
// Gauss-Markov with φ = 0.6): n epochs are worth n(1-φ)/(1+φ) independent ones, and the
// standard error says so; epochs that do not follow each other are taken as independent.
TEST(CourseMinusHeading, StandardErrorCountsCorrelatedEpochs) {
  const double sigma = 3.0 * kRadPerDeg, phi = 0.6;
  const int epochs = 400;
  test::Random rng(11);
  CourseMinusHeading correlated(30.0 * kRadPerDeg, 10), separate(30.0 * kRadPerDeg, 10);
  double error = rng.normal(sigma);
  for (int j = 0; j < epochs; ++j) {
    error = phi * error + std::sqrt(1.0 - phi * phi) * rng.normal(sigma);
    correlated.add(0.5 + error, 0.5 - 0.1, j > 0);
    separate.add(0.5 + error, 0.5 - 0.1, false);
  }
  AngleEstimate c, s;
  ASSERT_TRUE(correlated.estimate(&c));
  ASSERT_TRUE(separate.estimate(&s));
  const double independent = sigma / std::sqrt(static_cast<double>(epochs));
  EXPECT_NEAR(s.sigma_rad / independent, 1.0, 0.15);
  EXPECT_NEAR(c.sigma_rad / independent, std::sqrt((1.0 + phi) / (1.0 - phi)), 0.4);  // 2.0 ± sampling
  EXPECT_NEAR(c.value_rad, 0.1, 3.0 * c.sigma_rad);
}

TEST(FuseAngles, InverseVarianceAcrossPlusMinus180) {
  const AngleEstimate two[] = {{179.0 * kRadPerDeg, 1.0 * kRadPerDeg}, {-179.0 * kRadPerDeg, 1.0 * kRadPerDeg}};
  const AngleEstimate fused = fuseAngles(two);
  EXPECT_NEAR(std::abs(fused.value_rad) / kRadPerDeg, 180.0, 1e-9);
  EXPECT_NEAR(fused.sigma_rad / kRadPerDeg, 1.0 / std::sqrt(2.0), 1e-9);
  const AngleEstimate unequal[] = {{10.0 * kRadPerDeg, 1.0 * kRadPerDeg}, {20.0 * kRadPerDeg, 3.0 * kRadPerDeg}};
  const AngleEstimate weighted = fuseAngles(unequal);
  EXPECT_NEAR(weighted.value_rad / kRadPerDeg, 11.0, 1e-9);  // weights 9:1
  EXPECT_TRUE(std::isinf(fuseAngles({}).sigma_rad));
}

}  // namespace
}  // namespace headingd::core
