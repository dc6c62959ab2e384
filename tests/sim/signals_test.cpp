// The ideal sensor signals describe the true motion: the gyro integrates to the true
// attitude, the accelerometer is specific force (+g up at rest, and the kinematic
// acceleration while moving), the magnetometer sees the WMM field, and the mount turns
// the sensor about body z.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/core/heading_definition.hpp"
#include "headingd/sim/imu_model.hpp"
#include "sim_test_support.hpp"

namespace headingd::sim_test {
namespace {

using core::kRadPerDeg;
using core::Quat;
using core::Vec3;

double angleBetween(const Quat& a, const Quat& b) { return a.angularDistance(b); }

TEST(RateBetween, InvertsTheGyroIncrement) {
  const Quat q0 = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).normalized();
  for (const Vec3& w : {Vec3(0.0, 0.0, 0.0), Vec3(1e-9, -2e-9, 0.0), Vec3(0.3, -1.2, 2.5), Vec3(-7.0, 3.0, 9.0)}) {
    const double dt = 0.01;
    const Quat q1 = q0 * core::gyroIncrement(w, dt);
    EXPECT_LT((sim::rateBetween(q0, q1, dt) - w).norm(), 1e-9) << w.transpose();
    // The sign of the quaternion does not matter.
    Quat q1_negated = q1;
    q1_negated.coeffs() = -q1.coeffs();
    EXPECT_LT((sim::rateBetween(q0, q1_negated, dt) - w).norm(), 1e-9);
  }
}

TEST(Gyro, IntegratingTheIdealGyroReproducesTheTrueAttitude) {
  for (const char* scenario : {"crawl", "run", "thesis-declination"}) {
    const sim::SimResult& r = run(config(scenario, 3, sim::ImuGrade::kIdeal));
    const double dt = 1.0 / r.config.imu_rate_hz;
    Quat q = r.imu.front().q_ns;
    double worst = 0.0;
    for (std::size_t k = 1; k < r.imu.size(); ++k) {
      q = (q * core::gyroIncrement(r.imu[k].gyro_rad_s, dt)).normalized();
      worst = std::max(worst, angleBetween(q, r.imu[k].q_ns));
    }
    EXPECT_LT(worst, 1e-8) << scenario << " over " << r.imu.size() << " samples";
  }
}

TEST(Gyro, RatesArePlausibleForAPerson) {
  const sim::SimResult& r = run(config("run", 3, sim::ImuGrade::kIdeal));
  double peak = 0.0;
  for (const sim::ImuRow& row : r.imu) peak = std::max(peak, row.gyro_rad_s.norm());
  EXPECT_GT(peak, 0.3);  // running does rotate the trunk
  EXPECT_LT(peak, 6.0);
}

TEST(Accel, AtRestReadsGravityUpInSensorAxes) {
  const sim::SimResult& r = run(pointConfig("static-disturbed", 3, sim::ImuGrade::kIdeal));
  for (std::size_t k = 0; k < r.imu.size(); k += 7) {
    const sim::ImuRow& row = r.imu[k];
    ASSERT_FALSE(row.moving);
    const Vec3 up_in_sensor = row.q_ns.conjugate() * Vec3(0.0, 0.0, -1.0);
    EXPECT_NEAR(row.accel_m_s2.norm(), sim::kGravity_m_s2, 1e-9);
    EXPECT_NEAR(row.accel_m_s2.dot(up_in_sensor), sim::kGravity_m_s2, 1e-9);
  }
}

TEST(Accel, LyingOnTheBackReadsGravityAlongBodyX) {
  // Crawl scenario, on the back (pitch 85°): the chest (x) points nearly up.
  const sim::SimResult& r = run(config("crawl", 3, sim::ImuGrade::kIdeal));
  const sim::ImuRow& row = r.imu[static_cast<std::size_t>(80.0 * r.config.imu_rate_hz)];
  ASSERT_EQ(r.trajectory.states[static_cast<std::size_t>(80.0 * r.config.imu_rate_hz)].activity,
            sim::Activity::kLyingBack);
  EXPECT_NEAR(row.accel_m_s2.x(), sim::kGravity_m_s2 * std::sin(85.0 * kRadPerDeg), 0.05);
}

TEST(Accel, WhileMovingItIsTheSecondDerivativeOfPosition) {
  // Rotate the ideal specific force back to NED, add gravity, integrate twice: the path
  // reproduces the true positions (the recurrence p+ = 2p - p- + a dt² is what the
  // trajectory's accelerations are the second differences of).
  const sim::SimResult& r = run(pointConfig("urban-walk", 3, sim::ImuGrade::kIdeal, 50.0));
  const double dt = 1.0 / r.config.imu_rate_hz;
  const auto& s = r.trajectory.states;
  for (const double start_s : {15.0, 75.0, 240.0}) {  // walking, running, walking
    const auto k0 = static_cast<std::size_t>(start_s * r.config.imu_rate_hz);
    Vec3 before = s[k0 - 1].position_ned_m, now = s[k0].position_ned_m;
    double peak_accel = 0.0;
    for (std::size_t k = k0; k < k0 + 500; ++k) {  // 10 s
      const Vec3 a = r.imu[k].q_ns * r.imu[k].accel_m_s2 + Vec3(0.0, 0.0, sim::kGravity_m_s2);
      peak_accel = std::max(peak_accel, a.norm());
      const Vec3 next = 2.0 * now - before + a * dt * dt;
      before = now;
      now = next;
    }
    EXPECT_LT((now - s[k0 + 500].position_ned_m).norm(), 1e-6) << "from t = " << start_s;
    EXPECT_GT(peak_accel, 1.0) << "gait accelerations are present at t = " << start_s;
  }
}

TEST(Sampling, IntervalMeanVectorsAreTheMeanOfThePointValuesAtTheIntervalsEnds) {
  // The default sensor reports the mean over (t_{k-1}, t_k] (trapezoid rule), as its gyro's
  // rate covers the same interval; the point-sampled one the value at t_k.
  const sim::SimResult& mean = run(config("urban-walk", 3, sim::ImuGrade::kIdeal, 50.0));
  const sim::SimResult& point = run(pointConfig("urban-walk", 3, sim::ImuGrade::kIdeal, 50.0));
  ASSERT_EQ(mean.imu.size(), point.imu.size());
  EXPECT_EQ(mean.imu[0].accel_m_s2, point.imu[0].accel_m_s2);  // no interval before the first row
  for (std::size_t k = 1; k < mean.imu.size(); k += 17) {
    EXPECT_LT((mean.imu[k].accel_m_s2 - 0.5 * (point.imu[k - 1].accel_m_s2 + point.imu[k].accel_m_s2)).norm(), 1e-9);
    EXPECT_LT((mean.imu[k].mag_uT - 0.5 * (point.imu[k - 1].mag_uT + point.imu[k].mag_uT)).norm(), 1e-9);
    EXPECT_EQ(mean.imu[k].gyro_rad_s, point.imu[k].gyro_rad_s);
  }
}

TEST(Mag, FieldStrengthIsTheWmmTotalIntensityOutdoors) {
  const sim::SimResult& r = run(pointConfig("thesis-declination", 3, sim::ImuGrade::kIdeal));
  const double f_uT = r.wmm.f_nT / 1000.0;
  EXPECT_NEAR(f_uT, 51.9, 1.0);  // Stockholm, 2026
  for (std::size_t k = 0; k < r.imu.size(); k += 13) EXPECT_NEAR(r.imu[k].mag_uT.norm(), f_uT, 1e-9);
}

TEST(Mag, AnomalyTurnsTheFieldEastAboutDown) {
  sim::SimConfig c = pointConfig("thesis-declination", 3, sim::ImuGrade::kIdeal, 20.0);
  c.decl_anomaly_deg = 2.5;
  const sim::SimResult& r = run(c);
  EXPECT_NEAR(r.declination_deg, r.wmm.declination_deg + 2.5, 1e-12);
  for (std::size_t k = 0; k < r.imu.size(); k += 97) {
    const Vec3 m_ned = r.imu[k].q_ns * r.imu[k].mag_uT;
    EXPECT_NEAR(std::atan2(m_ned.y(), m_ned.x()) / kRadPerDeg, r.declination_deg, 1e-7);
    EXPECT_NEAR(m_ned.norm(), r.wmm.f_nT / 1000.0, 1e-9);
    EXPECT_NEAR(m_ned.z(), r.wmm.z_nT / 1000.0, 1e-9);  // turning about down keeps the vertical part
  }
}

TEST(Mag, StaticDisturbedAddsTheConstantOffset) {
  const sim::SimResult& r = run(pointConfig("static-disturbed", 3, sim::ImuGrade::kIdeal, 20.0));
  const Vec3 earth = core::magneticFieldNed_uT(r.wmm);
  for (std::size_t k = 0; k < r.imu.size(); k += 31) {
    const Vec3 m_ned = r.imu[k].q_ns * r.imu[k].mag_uT;
    EXPECT_LT((m_ned - earth - Vec3(-3.0, 5.0, 4.0)).norm(), 1e-9);
  }
}

TEST(Mag, UrbanWalkIsDisturbedIndoorsAndAlmostCleanOutdoors) {
  const sim::SimResult& r = run(config("urban-walk", 3, sim::ImuGrade::kIdeal, 50.0));
  double indoor_sum = 0.0, outdoor_sum = 0.0;
  std::size_t indoor_n = 0, outdoor_n = 0;
  for (std::size_t k = 0; k < r.imu.size(); ++k) {
    const double d = r.disturbance_ned_uT[k].norm();
    if (r.trajectory.states[k].indoor) {
      indoor_sum += d;
      ++indoor_n;
    } else {
      outdoor_sum += d;
      ++outdoor_n;
    }
  }
  ASSERT_GT(indoor_n, 0u);
  EXPECT_GT(indoor_sum / indoor_n, 5.0);    // offsets of 8-12 µT plus the spatial field
  EXPECT_LT(outdoor_sum / outdoor_n, 2.0);  // only passing cars
}

TEST(Mount, SensorIsTheBodyTurnedAboutBodyZ) {
  sim::SimConfig c = config("thesis-declination", 3, sim::ImuGrade::kIdeal, 20.0);
  c.mount_yaw_deg = 30.0;
  const sim::SimResult& mounted = run(c);
  c.mount_yaw_deg = 0.0;
  const sim::SimResult& plain = run(c);
  const Quat q_bs(Eigen::AngleAxisd(30.0 * kRadPerDeg, Vec3::UnitZ()));
  for (std::size_t k = 0; k < mounted.imu.size(); k += 11) {
    const sim::TruthState& s = mounted.trajectory.states[k];
    EXPECT_LT(angleBetween(mounted.imu[k].q_ns, s.q_nb * q_bs), 1e-12);
    // Same motion, seen in turned axes: v_s = R_bsᵀ v_b.
    EXPECT_LT((mounted.imu[k].gyro_rad_s - q_bs.conjugate() * plain.imu[k].gyro_rad_s).norm(), 1e-9);
    EXPECT_LT((mounted.imu[k].accel_m_s2 - q_bs.conjugate() * plain.imu[k].accel_m_s2).norm(), 1e-9);
    EXPECT_LT((mounted.imu[k].mag_uT - q_bs.conjugate() * plain.imu[k].mag_uT).norm(), 1e-9);
    // Upright, the sensor's heading is the body's plus the mount yaw (up to the small tilt).
    const double sensor_heading = core::headingOf(mounted.imu[k].q_ns);
    EXPECT_NEAR(core::wrapAngle(sensor_heading - core::headingOf(s.q_nb)), 30.0 * kRadPerDeg, 0.5 * kRadPerDeg);
  }
}

TEST(Mount, PitchAndRollTurnTheSensorFurtherAsZyxEulerAngles) {
  sim::SimConfig c = config("thesis-declination", 3, sim::ImuGrade::kIdeal, 20.0);
  c.mount_yaw_deg = 30.0;
  c.mount_pitch_deg = 90.0;  // x up: a phone upright in a pocket
  c.mount_roll_deg = 180.0;
  const sim::SimResult& mounted = run(c);
  // Roll 180° turns y to -y, pitch 90° keeps it and takes x onto -z, yaw 30° turns -y about z.
  EXPECT_LT((mounted.q_bs * Vec3::UnitX() - Vec3(0.0, 0.0, -1.0)).norm(), 1e-12);
  EXPECT_LT((mounted.q_bs * Vec3::UnitY() - Vec3(0.5, -std::sqrt(0.75), 0.0)).norm(), 1e-12);
  // Standing upright at the start, the sensor's x axis points up.
  EXPECT_GT(-(mounted.imu[0].q_ns * Vec3::UnitX()).z(), 0.99);
  // Without pitch and roll, the mount is the yaw turn alone, bit for bit.
  c.mount_pitch_deg = 0.0;
  c.mount_roll_deg = 0.0;
  EXPECT_EQ(run(c).q_bs.coeffs(), core::headingRotation(30.0 * kRadPerDeg).coeffs());
}

TEST(ImuErrors, ConsumerGradeAddsNoiseOfTheConfiguredSize) {
  // Differences to the ideal run (same seed, so the same motion) at rest: white noise of the
  // drawn sigma around a constant offset.
  const sim::SimResult& ideal = run(config("static-disturbed", 5, sim::ImuGrade::kIdeal));
  const sim::SimResult& noisy = run(config("static-disturbed", 5, sim::ImuGrade::kConsumer));
  const std::size_t n = 2000;  // the first 20 s: drift is still small
  Vec3 mean = Vec3::Zero(), mean2 = Vec3::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 d = noisy.imu[k].gyro_rad_s - ideal.imu[k].gyro_rad_s;
    mean += d / n;
    mean2 += d.cwiseProduct(d) / n;
  }
  const Vec3 sigma = (mean2 - mean.cwiseProduct(mean)).cwiseSqrt();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(sigma(i), noisy.gyro.white_sigma(i), 0.1 * noisy.gyro.white_sigma(i));
    EXPECT_NEAR(mean(i), noisy.gyro.offset(i), 0.006);  // ±1°/s offset, plus bias drift and noise of the mean
    EXPECT_LE(std::abs(noisy.gyro.offset(i)), 1.0 * kRadPerDeg);
  }
  EXPECT_NEAR(noisy.gyro.white_sigma.x(), 0.00413 * std::sqrt(100.0), 1e-12);  // MAGYQ Table 2 ARW
}

TEST(ImuErrors, UncalibratedMagnetometerIsDistortedAsKokAndSchon) {
  const sim::SimResult& r = run(config("static-disturbed", 5, sim::ImuGrade::kUncalibrated, 20.0));
  const double f = core::magneticFieldNed_uT(r.wmm).norm();
  bool large = false;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(std::abs(r.mag.offset(i)), f);
    large = large || std::abs(r.mag.offset(i)) > 0.05 * f || std::abs(r.mag.distortion(i, i) - 1.0) > 0.05;
  }
  EXPECT_TRUE(large);
  EXPECT_GT(r.mag.distortion.determinant(), 0.0);
}

}  // namespace
}  // namespace headingd::sim_test
