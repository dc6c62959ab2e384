// Henriksson §2.8 routines and the static-segment detector on the simulator's six-position
// recording, against the errors the simulator drew.
#include "headingd/calib/thesis_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "calib_test_support.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/sim/rng.hpp"

namespace headingd::calib_test {
namespace {

using core::kRadPerDeg;
using core::Mat3;
using core::Vec3;

TEST(StaticSegments, FindsTheSixFacesAndTheRests) {
  const sim::SimResult& r = simulated("calib-six-position", 1, sim::ImuGrade::kConsumer);
  const auto samples = samplesOf(r);
  const auto segments = calib::findStaticSegments(samples);
  // Six faces + level + three rests after the turns (the first rest is the level pose).
  EXPECT_EQ(segments.size(), 10u);
  // The segments are still in the truth, up to the last creep of a move (the truth's
  // moving flag is a 2°/s threshold on the smooth scripted motion).
  for (const auto& s : segments) {
    std::size_t moving = 0;
    for (std::size_t i = s.begin; i < s.end; ++i) moving += r.imu[i].moving ? 1 : 0;
    EXPECT_LE(moving, 10u) << "segment at " << s.begin;
    EXPECT_GE(s.size(), 450u);  // 10 s faces and 5 s rests at 100 Hz, less the edges
  }
}

TEST(StaticSegments, NoneInContinuousRotationAndNoCrashOnNaN) {
  std::vector<core::ImuSample> samples(1000);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    samples[i].t_ns = static_cast<std::int64_t>(i) * 10'000'000;
    const double a = 0.02 * static_cast<double>(i);
    samples[i].gyro_rad_s = Vec3(1.0 + 0.3 * std::sin(a), 0.2, -0.5);
    samples[i].accel_m_s2 = Vec3(9.81 * std::sin(a), 0.0, -9.81 * std::cos(a));
  }
  EXPECT_TRUE(calib::findStaticSegments(samples).empty());
  for (auto& s : samples) s = core::ImuSample{s.t_ns, Vec3(0.001, 0, 0), Vec3(0, 0, -9.81), Vec3(20, 0, 45), true};
  samples[500].accel_m_s2.x() = std::nan("");
  const auto segments = calib::findStaticSegments(samples);
  ASSERT_EQ(segments.size(), 2u);  // split by the bad sample
  EXPECT_LE(segments[0].end, 500u);
  EXPECT_GT(segments[1].begin, 500u);
}

TEST(ThesisCalibration, AccelerometerSixPosition) {
  const sim::SimResult& r = simulated("calib-six-position", 2, sim::ImuGrade::kConsumer);
  const auto samples = samplesOf(r);
  const auto segments = calib::findStaticSegments(samples);
  const auto faces = calib::findSixFaces(segments);
  const auto acc = calib::calibrateAccelSixPosition(segments, faces, sim::kGravity_m_s2);
  // Truth: diagonal of D (the skew and rotation terms, ±0.2°, are outside eq. 2.40's model)
  // and the offset plus the drifting bias (MAGYQ's Gauss-Markov, < 1.5 mg).
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(acc.scale(i), r.accel.distortion(i, i), 1e-3) << i;
    EXPECT_NEAR(acc.bias_m_s2(i), r.accel.offset(i), 0.01) << i;
  }
}

TEST(ThesisCalibration, GyroscopeBiasAndScale) {
  const sim::SimResult& r = simulated("calib-six-position", 3, sim::ImuGrade::kConsumer);
  const auto samples = samplesOf(r);
  const auto segments = calib::findStaticSegments(samples);
  const auto bias = calib::gyroBiasAtRest(segments);
  for (int i = 0; i < 3; ++i) {
    // Offset up to 1°/s plus a bias drifting by ~0.07°/s (MAGYQ): within 0.15°/s.
    EXPECT_NEAR(bias.bias_rad_s(i), r.gyro.offset(i), 0.15 * kRadPerDeg) << i;
    EXPECT_NEAR(bias.noise_sigma_rad_s(i), r.gyro.white_sigma(i), 0.2 * r.gyro.white_sigma(i)) << i;
  }
  const auto scale = calib::gyroScaleFromTurns(samples, segments, bias.bias_rad_s, 100.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(scale.turns_used[static_cast<std::size_t>(i)], 2) << i;
    EXPECT_NEAR(scale.scale(i), r.gyro.distortion(i, i), 1.5e-3) << i;
  }
}

TEST(ThesisCalibration, MagnetometerNewtonRecoversAnUpperTriangularModel) {
  // The model of eq. 2.45 exactly: the simulator's motion and field, a magnetometer with
  // 20 % scale differences, cross terms and a 50 % offset on z (Henriksson §6.1 saw both).
  const sim::SimResult& r = simulated("calib-six-position", 4, sim::ImuGrade::kConsumer);
  Mat3 beta;
  beta << 1.1, 0.05, -0.08, 0.0, 0.92, 0.04, 0.0, 0.0, 1.0;
  const Vec3 offset(6.0, -9.0, 26.0);
  auto samples = samplesOf(r);
  sim::Rng rng(99);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Vec3 m_b = r.imu[i].q_ns.conjugate() * r.field_ned_uT[i];
    samples[i].mag_uT = beta * m_b + offset + 0.5 * rng.gaussian3();
  }
  const auto segments = calib::findStaticSegments(samples);
  const auto faces = calib::findSixFaces(segments);
  const double norm = fieldNorm(r), dip = r.wmm.inclination_deg * kRadPerDeg;
  for (const std::optional<double> given_dip : {std::optional<double>(dip), std::optional<double>()}) {
    const auto mag = calib::calibrateMagSixPosition(segments, faces, norm, given_dip);
    const Mat3 alpha_true = beta.inverse();
    EXPECT_LT((mag.alpha - alpha_true).cwiseAbs().maxCoeff(), 0.01) << mag.alpha;
    EXPECT_LT((mag.bias_uT - offset).norm(), 0.5);
    EXPECT_NEAR(mag.dip_rad, dip, 0.3 * kRadPerDeg);
    EXPECT_LT(mag.residual_rms_uT, 0.5);
  }
}

TEST(ThesisCalibration, MissingFacesAreNamed) {
  const sim::SimResult& r = simulated("calib-rotation-long", 1, sim::ImuGrade::kConsumer);
  const auto samples = samplesOf(r);
  const auto segments = calib::findStaticSegments(samples);
  try {
    (void)calib::findSixFaces(segments);
    FAIL() << "expected CalibrationError";
  } catch (const calib::CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("z up"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace headingd::calib_test
