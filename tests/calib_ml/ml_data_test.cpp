// The ML step's measurements (ml_data.hpp): decimation pre-integrates the gyro exactly and
// averages the accelerometer and magnetometer through the gyro's rotations; gaps are not
// integrated across.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "headingd/calib/ml/ml_data.hpp"
#include "headingd/calib/ml/ml_ekf.hpp"

namespace headingd::calib {
namespace {

using core::Vec3;

std::vector<core::ImuSample> turning(std::size_t n, std::int64_t gap_at = -1) {
  std::vector<core::ImuSample> out;
  std::int64_t t = 0;
  for (std::size_t k = 0; k < n; ++k) {
    core::ImuSample s;
    s.t_ns = t;
    const double x = 0.01 * static_cast<double>(k);
    s.gyro_rad_s = Vec3(std::sin(3.0 * x), 0.5 + std::cos(2.0 * x), -0.7 * x);
    s.accel_m_s2 = Vec3(0.1 * k, 0.0, -9.81);
    s.mag_uT = Vec3(20.0, 1.0 * k, 40.0);
    s.has_mag = true;
    out.push_back(s);
    t += (static_cast<std::int64_t>(k) == gap_at) ? 2'000'000'000 : 10'000'000;
  }
  return out;
}

// The attitude after all predictions, from the first sample on.
core::Quat integrate(const MlData& d) {
  MlEkf<double> ekf(MlModel<double>{}, 9.81);
  ekf.setAttitude(core::Quat::Identity(), 0.1);
  for (const MlSample& s : d.samples) ekf.predict(s.gyro_rad_s, s.dt_s, s.gyro_noise_dt2_s2);
  return ekf.attitude();
}

TEST(MlData, DecimationComposesTheGyroExactly) {
  const auto samples = turning(101);
  MlDataOptions o;
  const MlData full = prepareMlData(samples, o);
  o.decimation = 10;
  const MlData thin = prepareMlData(samples, o);
  ASSERT_EQ(full.samples.size(), 101u);
  ASSERT_EQ(thin.samples.size(), 11u);  // the first alone, then 10 groups of 10
  EXPECT_NEAR(thin.samples[1].dt_s, 0.1, 1e-12);
  EXPECT_NEAR(thin.samples[1].gyro_noise_dt2_s2, 10 * 0.01 * 0.01, 1e-15);
  Vec3 mean = Vec3::Zero();
  for (int k = 1; k <= 10; ++k) mean += full.samples[k].accel_m_s2 / 10.0;
  EXPECT_LT((thin.samples[1].accel_m_s2 - mean).norm(), 1e-12);
  EXPECT_EQ(thin.samples[1].accel_count, 10.0);
  EXPECT_EQ(thin.samples[1].mag_count, 10.0);
  EXPECT_NEAR(integrate(full).angularDistance(integrate(thin)), 0.0, 1e-12);
}

// A sensor turning at a constant rate reads a fixed NED vector: the group's mean reading is
// exactly M R_bn,end v with M its mean rotation (the model the decimated EKF update uses).
TEST(MlData, DecimatedMeanIsTheMeanRotationTimesTheLastReading) {
  const Vec3 rate(0.4, -1.1, 2.0);
  const Vec3 g_n(0.0, 0.0, 9.81);
  std::vector<core::ImuSample> samples;
  std::vector<core::Mat3> r_bn;
  for (int k = 0; k < 21; ++k) {
    const core::Quat q_nb(Eigen::AngleAxisd(rate.norm() * 0.01 * k, rate.normalized()));
    core::ImuSample s;
    s.t_ns = 10'000'000LL * k;
    s.gyro_rad_s = rate;
    s.accel_m_s2 = -(q_nb.conjugate() * g_n);
    s.mag_uT = q_nb.conjugate() * Vec3(20.0, 0.0, 45.0);
    s.has_mag = true;
    samples.push_back(s);
    r_bn.push_back(q_nb.conjugate().toRotationMatrix());
  }
  MlDataOptions o;
  o.field_norm_uT = 1.0;
  o.decimation = 5;
  const MlData thin = prepareMlData(samples, o);
  ASSERT_EQ(thin.samples.size(), 5u);
  for (std::size_t g = 1; g < 5; ++g) {
    const std::size_t end = 5 * g;
    const MlSample& s = thin.samples[g];
    EXPECT_LT((s.accel_m_s2 - s.accel_mean_rotation * (-(r_bn[end] * g_n))).norm(), 1e-9) << g;
    EXPECT_LT((s.mag_unit - s.mag_mean_rotation * (r_bn[end] * Vec3(20.0, 0.0, 45.0))).norm(), 1e-9) << g;
  }
}

TEST(MlData, DecimationDoesNotIntegrateAcrossAGap) {
  const auto samples = turning(50, 24);  // 2 s between samples 24 and 25
  MlDataOptions o;
  o.decimation = 10;
  const MlData thin = prepareMlData(samples, o);
  EXPECT_EQ(thin.time_gaps, 1u);
  // [0] [1..10] [11..20] [21..24] [25, no prediction] [26..35] [36..45] [46..49]
  ASSERT_EQ(thin.samples.size(), 8u);
  EXPECT_EQ(thin.samples[4].dt_s, 0.0);
  EXPECT_NEAR(thin.samples[3].dt_s, 0.04, 1e-12);
  EXPECT_EQ(thin.samples[3].accel_count, 4.0);
}

}  // namespace
}  // namespace headingd::calib
