// The calibration model (core/imu_calibration) and its TOML: round trip, error messages
// with file:line and key, and the correction itself.
#include <gtest/gtest.h>

#include <cmath>

#include "headingd/core/imu_calibration.hpp"
#include "headingd/core/imu_calibration_toml.hpp"

namespace headingd::calib_test {
namespace {

using core::Mat3;
using core::Vec3;

core::ImuCalibration example() {
  core::ImuCalibration c;
  c.gyro.bias_rad_s = Vec3(0.01, -0.02, 0.003);
  c.gyro.scale = Vec3(1.01, 0.99, 1.0);
  c.gyro.noise_sigma_rad_s = Vec3(0.04, 0.045, 0.044);
  c.accel.bias_m_s2 = Vec3(0.02, -0.01, 0.05);
  c.accel.scale = Vec3(1.002, 0.998, 1.001);
  c.mag.D << 1.3, 0.2, -0.1, 0.33, 0.58, -0.05, -0.4, 0.2, 0.72;
  c.mag.offset_uT = Vec3(38.1, -39.9, -2.4);
  c.mag.field_norm_uT = 51.88;
  c.mag.field_norm_source = core::FieldNormSource::kWmm;
  c.mag.field_norm_detail = "WMM-2025 at 59.33 N 18.07 E on 2026-06-01 \"quoted\"";
  c.mag.dip_rad = 1.272;
  c.provenance.method = "ellipsoid";
  c.provenance.source_file = "/tmp/x.csv";
  c.provenance.first_sample = 100;
  c.provenance.end_sample = 6001;
  c.provenance.coverage = 0.69;
  c.provenance.residual_rms_uT = 1.99;
  c.provenance.condition_number = 9.9;
  return c;
}

TEST(CalibrationFile, RoundTrip) {
  const core::ImuCalibration a = example();
  const core::ImuCalibration b = core::parseImuCalibration(core::formatImuCalibration(a), "calib.toml");
  EXPECT_EQ(b.mag.D, a.mag.D);  // 17 digits: exact
  EXPECT_EQ(b.mag.offset_uT, a.mag.offset_uT);
  EXPECT_EQ(b.gyro.bias_rad_s, a.gyro.bias_rad_s);
  EXPECT_EQ(b.gyro.scale, a.gyro.scale);
  EXPECT_EQ(*b.gyro.noise_sigma_rad_s, *a.gyro.noise_sigma_rad_s);
  EXPECT_EQ(b.accel.bias_m_s2, a.accel.bias_m_s2);
  EXPECT_EQ(b.accel.scale, a.accel.scale);
  EXPECT_EQ(b.mag.field_norm_uT, a.mag.field_norm_uT);
  EXPECT_EQ(b.mag.field_norm_source, a.mag.field_norm_source);
  EXPECT_EQ(b.mag.field_norm_detail, a.mag.field_norm_detail);
  EXPECT_NEAR(*b.mag.dip_rad, *a.mag.dip_rad, 1e-15);
  EXPECT_EQ(b.provenance.method, "ellipsoid");
  EXPECT_EQ(b.provenance.first_sample, 100);
  EXPECT_EQ(b.provenance.end_sample, 6001);
  EXPECT_EQ(*b.provenance.coverage, 0.69);
}

// Found by fuzzing (tests/fuzz/corpus/calibration_toml/escapes): a string holding a control
// character (read from an escape) was written back raw, which TOML does not allow.
TEST(CalibrationFile, StringsWithControlCharactersAreWrittenBackReadable) {
  const core::ImuCalibration a = core::parseImuCalibration(
      "[calibration]\nmethod = \"a\\u0001\\t\\u007F\\\"b\"\n[gyroscope]\nscale = [1, 1, 1]\n", "calib.toml");
  ASSERT_EQ(a.provenance.method, "a\x01\t\x7F\"b");
  const std::string written = core::formatImuCalibration(a);
  EXPECT_NE(written.find("method = \"a\\u0001\t\\u007F\\\"b\""), std::string::npos) << written;
  EXPECT_EQ(core::parseImuCalibration(written, "written.toml").provenance.method, a.provenance.method);
}

// An empty document is refused (ErrorsNameFileLineKeyAndExpectation); one that states the
// identity is the identity.
TEST(CalibrationFile, AStatedIdentityIsTheIdentity) {
  const core::ImuCalibration c = core::parseImuCalibration(
      "[magnetometer]\noffset_uT = [0, 0, 0]\n[gyroscope]\nbias_rad_s = [0, 0, 0]\n", "identity.toml");
  EXPECT_EQ(c.mag.D, Mat3::Identity());
  const core::ImuCorrection correction(c);
  core::ImuSample s;
  s.gyro_rad_s = Vec3(1, 2, 3);
  s.mag_uT = Vec3(4, 5, 6);
  const core::ImuSample out = correction.apply(s);
  EXPECT_EQ(out.gyro_rad_s, s.gyro_rad_s);
  EXPECT_EQ(out.mag_uT, s.mag_uT);
}

TEST(CalibrationFile, CorrectionInvertsTheModels) {
  const core::ImuCalibration c = example();
  const core::ImuCorrection correction(c);
  const Vec3 w(0.3, -0.2, 1.1), a(0.5, -0.3, -9.8), m(15.0, 2.0, 49.0);
  core::ImuSample s;
  s.gyro_rad_s = c.gyro.scale.cwiseProduct(w) + c.gyro.bias_rad_s;   // eq. 2.41
  s.accel_m_s2 = c.accel.scale.cwiseProduct(a) + c.accel.bias_m_s2;  // eq. 2.40
  s.mag_uT = c.mag.D * m + c.mag.offset_uT;                          // K&S eq. 8
  const core::ImuSample out = correction.apply(s);
  EXPECT_LT((out.gyro_rad_s - w).norm(), 1e-12);
  EXPECT_LT((out.accel_m_s2 - a).norm(), 1e-12);
  EXPECT_LT((out.mag_uT - m).norm(), 1e-12);
}

void expectError(const std::string& text, const std::string& fragment) {
  try {
    (void)core::parseImuCalibration(text, "calib.toml");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const core::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(CalibrationFile, ErrorsNameFileLineKeyAndExpectation) {
  expectError("[magnetometer]\nD = [[1, 0, 0], [0, 1, 0]]\n", "calib.toml:2: [magnetometer] D: expected a 3x3 matrix");
  expectError("[magnetometer]\nD = [[1, 0, 0], [0, 1, 0], [2, 0, 0]]\n",
              "calib.toml:2: [magnetometer] D: expected an invertible");
  expectError("[magnetometer]\noffset_uT = [1, 2]\n",
              "calib.toml:2: [magnetometer] offset_uT: expected an array of 3 numbers in uT");
  expectError("[magnetometer]\noffset_uT = [1, \"a\", 2]\n", "offset_uT: expected an array of 3 numbers");
  expectError("[magnetometer]\nfield_norm_source = \"guess\"\n",
              "calib.toml:2: [magnetometer] field_norm_source: expected \"wmm\"");
  expectError("\n[gyroscope]\nscale = [1, 0, 1]\n", "calib.toml:3: [gyroscope] scale: expected positive scale factors");
  expectError("[gyroscope]\nbias = [0, 0, 0]\n", "calib.toml:2: [gyroscope] bias: unknown key (expected one of");
  expectError("[magnetometre]\n", "calib.toml:1: unknown table or key 'magnetometre'");
  expectError("[calibration]\nsample_range = [5, 2]\n",
              "calib.toml:2: [calibration] sample_range: expected [first, end)");
  expectError("[magnetometer]\nD = \n", "calib.toml:2: TOML syntax error");
  expectError("magnetometer = 3\n", "calib.toml:1: 'magnetometer' must be a table");
  // Values no sensor's calibration has (another unit, another file) are refused, not applied.
  expectError("[gyroscope]\nscale = [1, 3, 1]\n",
              "calib.toml:2: [gyroscope] scale: expected scale factors within 0.5 .. 2");
  expectError("[gyroscope]\nbias_rad_s = [0, 0, 1.5]\n",
              "calib.toml:2: [gyroscope] bias_rad_s: expected each component within ±1.0 rad/s");
  expectError("[accelerometer]\nbias_m_s2 = [0, -12, 0]\n",
              "[accelerometer] bias_m_s2: expected each component within ±10.0");
  expectError("[magnetometer]\noffset_uT = [6000, 0, 0]\n",
              "[magnetometer] offset_uT: expected each component within ±5000.0 uT");
  // A file that lacks every correction is not taken for the identity (hardening round two).
  expectError("", "calib.toml: no correction in it: expected at least one of [magnetometer] D or offset_uT");
  expectError("[calibration]\nmethod = \"ml\"\n[quality]\ncoverage = 0.5\n", "calib.toml: no correction in it");
  EXPECT_NO_THROW((void)core::parseImuCalibration("[gyroscope]\nbias_rad_s = [0.01, 0, 0]\n", "calib.toml"));
}

TEST(CalibrationFile, SingularCorrectionIsRefused) {
  core::ImuCalibration c;
  c.mag.D = Mat3::Zero();
  EXPECT_THROW(core::ImuCorrection{c}, std::invalid_argument);
  c.mag.D = Mat3::Identity();
  c.gyro.scale = Vec3(1, 0, 1);
  EXPECT_THROW(core::ImuCorrection{c}, std::invalid_argument);
}

}  // namespace
}  // namespace headingd::calib_test
