// --method ml: Kok & Schön (2016) Algorithm 1, maximum likelihood through the EKF predictor.
#include <algorithm>
#include <chrono>
#include <numbers>
#include <string>
#include <utility>

#include "headingd/calib/ml/ml_calibration.hpp"
#include "headingd/calibrate/method_support.hpp"
#include "headingd/calibrate/methods.hpp"
#include "headingd/calibrate/progress.hpp"
#include "headingd/core/angles.hpp"

namespace headingd::calibrate {
namespace {

using core::kRadPerDeg;

calib::MlGradient gradientNamed(const std::string& name) {
  return name == "jets"      ? calib::MlGradient::kAutomatic
         : name == "forward" ? calib::MlGradient::kNumericForward
         : name == "central" ? calib::MlGradient::kNumericCentral
                             : calib::MlGradient::kAdjoint;
}

}  // namespace

void calibrateMl(const Recording& rec, const MlSettings& ml, FieldNorm& field, core::ImuCalibration& cal,
                 ReportInput& report) {
  calib::MlCalibrationOptions o;
  takeFieldNormFromDataIfUnknown(field, rec.mags);
  o.initial.field_norm_uT = *field.norm_uT;
  applyPlace(o.initial, rec.dip_sign, field);
  o.decimation = std::max<std::size_t>(ml.decimation, 1);
  o.gradient = gradientNamed(ml.gradient);
  if (!rec.segments.empty()) {
    o.initial.stationary_begin = rec.segments.front().begin;
    o.initial.stationary_count = std::min<std::size_t>(rec.segments.front().size(), 500);
  }
  progress("maximum likelihood (Kok & Schon Algorithm 1) on %zu samples (every %zu. in the likelihood); dip sign %s",
           rec.samples.size(), o.decimation, calib::dipSignName(rec.dip_sign));
  calib::MlProblem problem = calib::prepareMaximumLikelihood(rec.samples, o);
  progress("initial estimate (step 1): dip %.2f deg, %d misalignment minima%s", problem.initial.dip_rad / kRadPerDeg,
           problem.initial.misalignment_minima,
           problem.initial.misalignment_sign_chosen ? ", the best one refused for its dip sign" : "");
  const auto ml_start = std::chrono::steady_clock::now();
  const auto r = calib::refineMaximumLikelihood(std::move(problem), o, [](const calib::MlProgress& p) {
    progress("  iteration %3d  cost %.6g  |gradient| %.3g%s", p.iteration, p.cost, p.gradient_max_norm,
             p.restart > 0 ? "  (restarted)" : "");
  });
  const double ml_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - ml_start).count();
  cal.mag.D = r.D;
  cal.mag.offset_uT = r.offset_uT;
  cal.mag.field_norm_uT = r.field_norm_uT;
  cal.mag.dip_rad = r.dip_rad;
  cal.mag.noise_sigma_uT = r.mag_sigma;
  cal.gyro.bias_rad_s = r.gyro_bias_rad_s;
  cal.gyro.noise_sigma_rad_s = r.gyro_sigma;
  cal.accel.noise_sigma_m_s2 = r.accel_sigma;
  report.coverage = calibratedCoverage(cal, rec.mags);
  cal.provenance.coverage = report.coverage;
  for (const auto& res : r.residuals_final) {
    if (res.has_mag) report.residuals.insert(report.residuals.end(), {res.mag.x(), res.mag.y(), res.mag.z()});
  }
  report.residual_kind = "EKF magnetometer innovations, normalised (x, y, z interleaved)";
  report.notes.push_back(
      describe("ML: %.0f iterations, %.2f s; cost from the initial estimate ", r.iterations, ml_seconds, "") +
      std::to_string(r.cost_initial) + " to " + std::to_string(r.cost_final) + " (" + r.termination + ")");
  if (r.starts > 1) {
    report.notes.push_back(std::string("ML: the first search ended at the dip's wall (") + r.termination_first_start +
                           "); a second started from the WMM's dip" +
                           (r.chosen_start == 1 ? " and was kept" : " and did no better"));
  }
  progress("ML: %d iterations, %d restarts, %d starts, %.2f s, %s", r.iterations, r.restarts, r.starts, ml_seconds,
           r.termination.c_str());
}

}  // namespace headingd::calibrate
