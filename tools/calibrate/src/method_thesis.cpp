// --method thesis: Henriksson (2013) §2.8.
#include <string>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/thesis_calibration.hpp"
#include "headingd/calibrate/method_support.hpp"
#include "headingd/calibrate/methods.hpp"
#include "headingd/calibrate/progress.hpp"

namespace headingd::calibrate {

void calibrateThesis(const Recording& rec, const FieldNorm& field, core::ImuCalibration& cal, ReportInput& report) {
  if (!field.norm_uT)
    throw calib::CalibrationError("thesis: the field norm is needed: give --field-uT or --lat/--lon/--date");
  const auto faces = calib::findSixFaces(rec.segments);
  progress("six faces found; accelerometer (eq. 2.40), gyroscope (eq. 2.41), magnetometer (Newton, eq. 2.47)");
  const auto acc = calib::calibrateAccelSixPosition(rec.segments, faces, 9.81);
  cal.accel.scale = acc.scale;
  cal.accel.bias_m_s2 = acc.bias_m_s2;
  const auto gs = calib::gyroScaleFromTurns(rec.samples, rec.segments, cal.gyro.bias_rad_s, rec.rate_hz);
  cal.gyro.scale = gs.scale;
  report.notes.push_back("gyroscope scale from whole turns about x, y, z: " + std::to_string(gs.turns_used[0]) + ", " +
                         std::to_string(gs.turns_used[1]) + ", " + std::to_string(gs.turns_used[2]) +
                         " (0: left at 1)");
  const auto mag = calib::calibrateMagSixPosition(rec.segments, faces, *field.norm_uT, field.dip_rad);
  cal.mag.D = mag.alpha.inverse();
  cal.mag.offset_uT = mag.bias_uT;
  cal.mag.field_norm_uT = *field.norm_uT;
  cal.mag.dip_rad = mag.dip_rad;
  cal.provenance.residual_rms_uT = mag.residual_rms_uT;
  report.coverage = calibratedCoverage(cal, rec.mags);
  cal.provenance.coverage = report.coverage;
  progress("Newton: %d iterations, residual %.3f uT rms", mag.iterations, mag.residual_rms_uT);
  report.residuals = radialResiduals(cal, rec.mags, restSigmaCalibrated(cal, rec.mag_sigma_raw, 1.0));
  report.residual_kind = "(|m_b| - F) / sigma over the whole recording, sigma the noise at rest";
}

}  // namespace headingd::calibrate
