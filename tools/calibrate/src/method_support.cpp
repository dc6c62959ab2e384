#include "headingd/calibrate/method_support.hpp"

#include <cmath>

#include "headingd/calib/ellipsoid_fit.hpp"
#include "headingd/calib/thesis_calibration.hpp"
#include "headingd/calibrate/progress.hpp"

namespace headingd::calibrate {

using core::Vec3;

Recording prepareRecording(std::span<const core::ImuSample> samples, calib::DipSign dip_sign, core::ImuCalibration& cal,
                           ReportInput& report) {
  Recording rec;
  rec.samples = samples;
  rec.dip_sign = dip_sign;
  rec.rate_hz = calib::sampleRateHz(samples);
  progress("%zu samples at %.1f Hz; finding static segments", samples.size(), rec.rate_hz);
  rec.segments = calib::findStaticSegments(samples, {}, rec.rate_hz);
  progress("%zu static segments", rec.segments.size());
  report.notes.push_back(std::to_string(rec.segments.size()) + " static segments found");
  if (!rec.segments.empty()) {
    const auto bias = calib::gyroBiasAtRest(rec.segments);
    const calib::StaticSegment* longest = &rec.segments[0];
    for (const auto& s : rec.segments) {
      if (s.size() > longest->size()) longest = &s;
    }
    cal.gyro.bias_rad_s = bias.bias_rad_s;
    cal.gyro.noise_sigma_rad_s = bias.noise_sigma_rad_s;
    cal.accel.noise_sigma_m_s2 = longest->accel_sigma;
    rec.mag_sigma_raw = longest->mag_sigma;
  }
  for (const auto& s : samples) {
    if (s.has_mag && s.mag_uT.allFinite()) rec.mags.push_back(s.mag_uT);
  }
  return rec;
}

void completeCalibration(const Recording& rec, const FieldNorm& field, core::ImuCalibration& cal) {
  cal.mag.field_norm_source = field.source;
  cal.mag.field_norm_detail = field.detail;
  if (!cal.mag.dip_rad && field.dip_rad) cal.mag.dip_rad = field.dip_rad;
  if (rec.mag_sigma_raw && !cal.mag.noise_sigma_uT) cal.mag.noise_sigma_uT = *rec.mag_sigma_raw;
}

void takeFieldNormFromDataIfUnknown(FieldNorm& field, std::span<const Vec3> mags) {
  if (field.norm_uT) return;
  const auto pre = calib::fitEllipsoid(mags, 1.0);
  field.norm_uT = std::cbrt(pre.D.determinant());
  field.detail = "scaled so that det D = 1 (no --field-uT or WMM place given)";
}

void applyPlace(calib::MlInitialOptions& o, calib::DipSign dip_sign, const FieldNorm& field) {
  o.expected_dip_sign = dip_sign;
  o.expected_dip_rad = field.dip_rad;
}

std::vector<double> radialResiduals(const core::ImuCalibration& cal, std::span<const Vec3> mags, double sigma_uT) {
  const core::ImuCorrection c(cal);
  std::vector<double> r;
  for (const Vec3& y : mags) r.push_back((c.magnetometer(y).norm() - cal.mag.field_norm_uT) / sigma_uT);
  return r;
}

double restSigmaCalibrated(const core::ImuCalibration& cal, const std::optional<Vec3>& mag_sigma_raw, double fallback) {
  if (!mag_sigma_raw || !(mag_sigma_raw->norm() > 0.0)) return fallback;
  return mag_sigma_raw->norm() / std::sqrt(3.0) / std::cbrt(std::abs(cal.mag.D.determinant()));
}

double calibratedCoverage(const core::ImuCalibration& cal, std::span<const Vec3> mags) {
  std::vector<Vec3> dirs;
  const core::ImuCorrection c(cal);
  for (const Vec3& y : mags) dirs.push_back(c.magnetometer(y));
  return calib::sphereCoverage(dirs);
}

}  // namespace headingd::calibrate
