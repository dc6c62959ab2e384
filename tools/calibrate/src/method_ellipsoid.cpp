// --method ellipsoid: Kok & Schön (2016) Algorithm 1 step 1.
#include <Eigen/Geometry>
#include <algorithm>
#include <numbers>
#include <string>

#include "headingd/calib/ellipsoid_fit.hpp"
#include "headingd/calibrate/method_support.hpp"
#include "headingd/calibrate/methods.hpp"
#include "headingd/calibrate/progress.hpp"
#include "headingd/core/angles.hpp"

namespace headingd::calibrate {
namespace {

using core::kRadPerDeg;

}  // namespace

void calibrateEllipsoid(const Recording& rec, FieldNorm& field, core::ImuCalibration& cal, ReportInput& report) {
  // The fit alone gives D only up to a rotation (K&S eq. 25); the misalignment step
  // (§6.2) turns it onto the inertial axes with the vertical from the gyro and
  // accelerometer, so that headings from D⁻¹(y - o) are right, not just |m_b|.
  calib::MlInitialOptions o;
  o.ellipsoid_min_coverage = calib::EllipsoidFitOptions{}.min_coverage;
  applyPlace(o, rec.dip_sign, field);
  takeFieldNormFromDataIfUnknown(field, rec.mags);
  o.field_norm_uT = *field.norm_uT;
  if (!rec.segments.empty()) {
    o.stationary_begin = rec.segments.front().begin;
    o.stationary_count = std::min<std::size_t>(rec.segments.front().size(), 500);
  } else {
    // No rest found: the noise floors of MlInitialOptions carry the inclination EKF.
    o.stationary_count = std::min<std::size_t>(rec.samples.size(), 100);
    report.notes.push_back("no static segment: gyro bias 0 assumed for the misalignment step");
  }
  progress(
      "ellipsoid fit of %zu magnetometer samples and misalignment to the inertial axes (Kok & Schon "
      "sec. 6.1-6.2)",
      rec.mags.size());
  const calib::MlInitialEstimate init = calib::estimateInitialParameters(rec.samples, o);
  cal.mag.D = init.D;
  cal.mag.offset_uT = init.offset_uT;
  cal.mag.field_norm_uT = *field.norm_uT;
  cal.mag.dip_rad = init.dip_rad;
  cal.provenance.residual_rms_uT = init.ellipsoid_residual_rms_uT;
  cal.provenance.coverage = init.ellipsoid_coverage;
  cal.provenance.condition_number = init.ellipsoid_condition_number;
  report.coverage = init.ellipsoid_coverage;
  report.condition_number = init.ellipsoid_condition_number;
  const Eigen::AngleAxisd misalignment(init.misalignment);
  progress("coverage %.0f %%, residual %.2f uT rms, condition %.0f; misalignment %.2f deg, dip %.2f deg",
           100 * init.ellipsoid_coverage, init.ellipsoid_residual_rms_uT, init.ellipsoid_condition_number,
           misalignment.angle() / kRadPerDeg, init.dip_rad / kRadPerDeg);
  report.notes.push_back(describe("misalignment to the inertial axes %.2f deg (K&S eq. 27, rms residual %.4f)",
                                  misalignment.angle() / kRadPerDeg, init.misalignment_rms, ""));
  if (init.misalignment_sign_chosen) {
    report.notes.push_back(std::string("misalignment: the best minimum of eq. 27 had the dip sign the place rules "
                                       "out; the best of sign ") +
                           calib::dipSignName(rec.dip_sign) + " was taken");
  }
  const double fit_residual = init.ellipsoid_residual_rms_uT;
  report.residuals = radialResiduals(cal, rec.mags, restSigmaCalibrated(cal, rec.mag_sigma_raw, fit_residual));
  report.residual_kind = "(|m_b| - F) / sigma, sigma the magnetometer noise at rest";
}

}  // namespace headingd::calibrate
