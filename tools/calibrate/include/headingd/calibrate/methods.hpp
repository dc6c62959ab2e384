#pragma once
// The calibration methods of headingd-calibrate (--method), each filling in the calibration
// and the report from the same prepared recording:
//   thesis     Henriksson (2013) §2.8: six static faces (accelerometer, magnetometer by
//              Newton's method), gyroscope bias at rest and scale from whole turns
//   ellipsoid  Kok & Schön (2016) Algorithm 1 step 1: ellipsoid fit (§6.1), then the
//              misalignment to the inertial axes and the dip (§6.2, eqs. 26-28)
//   ml         Kok & Schön Algorithm 1, maximum likelihood through the EKF predictor
// Each throws calib::CalibrationError (or another std::exception) when the data cannot give
// a calibration.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "headingd/calib/dip_sign.hpp"
#include "headingd/calib/static_segments.hpp"
#include "headingd/calibrate/report.hpp"
#include "headingd/core/imu_calibration.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::calibrate {

// The local field's magnitude and dip where they are known (--field-uT, or the WMM at
// --lat/--lon/--date), and where the magnitude came from, for the calibration file.
struct FieldNorm {
  std::optional<double> norm_uT;
  std::optional<double> dip_rad;
  core::FieldNormSource source = core::FieldNormSource::kData;
  std::string detail;
};

// What every method starts from.
struct Recording {
  std::span<const core::ImuSample> samples;
  double rate_hz = 0.0;
  std::vector<calib::StaticSegment> segments;
  std::vector<core::Vec3> mags;             // the finite magnetometer samples
  std::optional<core::Vec3> mag_sigma_raw;  // the field's noise in the longest static segment
  // The dip's sign known from the place: Kok & Schön's misalignment step has a mirror pair
  // of solutions that the data alone cannot tell apart (calib/dip_sign.hpp).
  calib::DipSign dip_sign = calib::DipSign::kUnknown;
};

// --ml-gradient and --ml-decimation.
struct MlSettings {
  std::string gradient = "reverse";
  std::size_t decimation = 1;
};

// Finds the static segments and the magnetometer samples, and takes the gyroscope's bias and
// noise and the accelerometer's noise at rest (common to all methods) into `cal`.
Recording prepareRecording(std::span<const core::ImuSample> samples, calib::DipSign dip_sign, core::ImuCalibration& cal,
                           ReportInput& report);

// The method's part. Without a known field norm, ellipsoid and ml take it from the data
// (D of unit determinant) and say so in `field`.
void calibrateThesis(const Recording& rec, const FieldNorm& field, core::ImuCalibration& cal, ReportInput& report);
void calibrateEllipsoid(const Recording& rec, FieldNorm& field, core::ImuCalibration& cal, ReportInput& report);
void calibrateMl(const Recording& rec, const MlSettings& ml, FieldNorm& field, core::ImuCalibration& cal,
                 ReportInput& report);

// After the method: where the field norm came from, and the dip and the field's noise where
// the method left them open.
void completeCalibration(const Recording& rec, const FieldNorm& field, core::ImuCalibration& cal);

}  // namespace headingd::calibrate
