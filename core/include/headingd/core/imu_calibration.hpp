#pragma once
// The calibration of one IMU and its application to each sample, before the estimator.
//
// Models (sensor readings on the left, the true quantities in the IMU's inertial axes on
// the right):
//   gyroscope      ω_g = K_g ω + b_g              (Henriksson 2013 eq. 2.41, K_g diagonal)
//   accelerometer  a_a = K_a a_p + b_a            (Henriksson eq. 2.40, K_a diagonal)
//   magnetometer   y_m = D m_b + o                (Kok & Schön 2016 eq. 8, D full 3×3)
// so the corrections are ω = K_g⁻¹(ω_g − b_g), a_p = K_a⁻¹(a_a − b_a), m_b = D⁻¹(y_m − o).
// D holds soft iron, scale, non-orthogonality and the magnetometer-to-inertial rotation;
// it is near identity for a clean sensor. Pure: the TOML file is imu_calibration_toml.hpp.
#include <cstdint>
#include <optional>
#include <string>

#include "headingd/core/imu_sample.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct GyroCalibration {
  Vec3 bias_rad_s = Vec3::Zero();
  Vec3 scale = Vec3::Ones();
  std::optional<Vec3> noise_sigma_rad_s;  // white noise per sample, informative
};

struct AccelCalibration {
  Vec3 bias_m_s2 = Vec3::Zero();
  Vec3 scale = Vec3::Ones();
  std::optional<Vec3> noise_sigma_m_s2;
};

// Where the field magnitude the magnetometer calibration was scaled to came from.
enum class FieldNormSource { kWmm, kArgument, kData };
const char* fieldNormSourceName(FieldNormSource s);  // "wmm", "argument", "data"

struct MagCalibration {
  Mat3 D = Mat3::Identity();
  Vec3 offset_uT = Vec3::Zero();
  double field_norm_uT = 0.0;  // |m_b| after calibration; 0 = not stated
  FieldNormSource field_norm_source = FieldNormSource::kData;
  std::string field_norm_detail;  // e.g. "WMM-2025 at 59.33 N 18.07 E on 2026-06-01"
  std::optional<double> dip_rad;  // inclination of the field, positive down
  std::optional<Vec3> noise_sigma_uT;
};

// What the calibration came from and how good it looked. Informative: nothing here
// changes the correction.
struct CalibrationProvenance {
  std::string method;  // "thesis", "ellipsoid", "ml"
  std::string source_file;
  std::int64_t first_sample = 0;  // rows of the source used, [first, end)
  std::int64_t end_sample = 0;
  std::string created;  // free text, e.g. tool and version
  std::optional<double> residual_rms_uT;
  std::optional<double> coverage;  // fraction of the sphere, 0..1
  std::optional<double> condition_number;
};

struct ImuCalibration {
  GyroCalibration gyro;
  AccelCalibration accel;
  MagCalibration mag;
  CalibrationProvenance provenance;
};

// Applies a calibration; the inverses are computed once. A calibration with a singular D
// or a zero scale is refused (std::invalid_argument) rather than turning samples into NaN.
class ImuCorrection {
 public:
  ImuCorrection() = default;  // identity
  explicit ImuCorrection(const ImuCalibration& c);
  ImuSample apply(const ImuSample& s) const;
  Vec3 magnetometer(const Vec3& y_uT) const { return d_inverse_ * (y_uT - mag_offset_uT_); }

 private:
  Vec3 gyro_bias_ = Vec3::Zero();
  Vec3 gyro_inverse_scale_ = Vec3::Ones();
  Vec3 accel_bias_ = Vec3::Zero();
  Vec3 accel_inverse_scale_ = Vec3::Ones();
  Mat3 d_inverse_ = Mat3::Identity();
  Vec3 mag_offset_uT_ = Vec3::Zero();
};

}  // namespace headingd::core
