// Algorithm 1 on simulated K&S runs (Table 2 distortions): the ML estimate recovers D, o, the
// dip and the gyro bias, and is closer than the initial estimate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/ml/ml_calibration.hpp"
#include "headingd/calib_montecarlo/ks_simulation.hpp"
#include "headingd/core/angles.hpp"

namespace headingd::calib {
namespace {

using core::kRadPerDeg;

MlCalibrationOptions optionsFor(const calib_montecarlo::KsRun& run) {
  MlCalibrationOptions o;
  o.initial.field_norm_uT = run.truth.field_norm_uT;
  o.initial.stationary_count = run.stationary_samples;
  o.initial.ellipsoid_min_coverage = 0.1;
  return o;
}

class MlRecovery : public ::testing::TestWithParam<int> {};

// Low noise (Table 2's σ ×0.01) so that the tolerances test the algorithm, not the noise.
TEST_P(MlRecovery, RecoversDistortionOffsetDipAndGyroBias) {
  const calib_montecarlo::KsRun run =
      calib_montecarlo::simulateKokSchonRun(calib_montecarlo::KsVariant::kShort, GetParam(), {0.01, false});
  int progress_calls = 0;
  const MlCalibrationResult r =
      calibrateMaximumLikelihood(run.samples, optionsFor(run), [&](const MlProgress&) { ++progress_calls; });
  const calib_montecarlo::KsTruth& t = run.truth;
  EXPECT_LT((r.D - t.mag_D).norm(), 0.01) << r.D << "\n" << t.mag_D;
  EXPECT_LT((r.offset_uT - t.mag_offset_uT).norm(), 0.2);
  EXPECT_NEAR(r.dip_rad, t.dip_rad, 0.05 * kRadPerDeg);
  EXPECT_LT((r.gyro_bias_rad_s - t.gyro_bias_rad_s).norm(), 0.02 * kRadPerDeg);
  // The ML estimate is closer to the truth than the initial one, and the cost went down.
  EXPECT_LT((r.D - t.mag_D).norm(), (r.initial.D - t.mag_D).norm());
  EXPECT_LT(r.cost_final, r.cost_initial);
  EXPECT_GT(progress_calls, 0);
  EXPECT_EQ(r.residuals_final.size(), run.samples.size());
  // Noise levels come back within a factor of two.
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::log(r.mag_sigma(i) / t.mag_sigma_uT(i)), 0.0, std::log(2.0)) << i;
  }
  const double h0 = calib_montecarlo::headingRmseRad(run, r.initial.D, r.initial.offset_uT);
  const double h1 = calib_montecarlo::headingRmseRad(run, r.D, r.offset_uT);
  EXPECT_LT(h1, h0);
  EXPECT_LT(h1, 0.2 * kRadPerDeg);
}

INSTANTIATE_TEST_SUITE_P(Seeds, MlRecovery, ::testing::Values(1, 2));

TEST(MlCalibration, TooLittleRotationIsAClearError) {
  calib_montecarlo::KsRun run =
      calib_montecarlo::simulateKokSchonRun(calib_montecarlo::KsVariant::kShort, 3, {0.01, false});
  run.samples.resize(run.stationary_samples + 5);  // the sensor hardly turned
  EXPECT_THROW(calibrateMaximumLikelihood(run.samples, optionsFor(run)), CalibrationError);
}

TEST(MlCalibration, StationarySegmentOutsideTheDataIsAClearError) {
  const calib_montecarlo::KsRun run =
      calib_montecarlo::simulateKokSchonRun(calib_montecarlo::KsVariant::kShort, 3, {0.01, false});
  MlCalibrationOptions o = optionsFor(run);
  o.initial.stationary_begin = run.samples.size();
  EXPECT_THROW(calibrateMaximumLikelihood(run.samples, o), CalibrationError);
}

}  // namespace
}  // namespace headingd::calib
