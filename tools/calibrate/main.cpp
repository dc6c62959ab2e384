// headingd-calibrate: IMU calibration from a recording (BROAD CSV), written as the TOML that
// headingd-replay --calib and the daemon apply. Methods:
//   thesis     Henriksson (2013) §2.8: six static faces (accelerometer, magnetometer by
//              Newton's method), gyroscope bias at rest and scale from whole turns
//   ellipsoid  Kok & Schön (2016) Algorithm 1 step 1: ellipsoid fit (§6.1), then the
//              misalignment to the inertial axes and the dip (§6.2, eqs. 26-28)
//   ml         Kok & Schön Algorithm 1, maximum likelihood through the EKF predictor
// Exit codes: 0 written, 1 file error, 2 bad arguments, 3 the data cannot give a calibration.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

#include "headingd/calib/dip_sign.hpp"
#include "headingd/calib/ellipsoid_fit.hpp"
#include "headingd/calib/ml_calibration.hpp"
#include "headingd/calib/static_segments.hpp"
#include "headingd/calib/thesis_calibration.hpp"
#include "headingd/calibrate/report.hpp"
#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/core/wmm.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace {

using namespace headingd;
using core::Vec3;
constexpr double kDeg = std::numbers::pi / 180.0;

const auto g_start = std::chrono::steady_clock::now();

// Progress on the terminal (stderr), with the time since start.
template <typename... Args>
void progress(const char* fmt, Args... args) {
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - g_start).count();
  std::fprintf(stderr, "[%6.2f s] ", t);
  std::fprintf(stderr, fmt, args...);
  std::fputc('\n', stderr);
}
// Text without arguments, printed as it is (Debian's -Werror=format-security rejects a
// non-literal format without arguments).
void progress(const char* text) { progress("%s", text); }

struct FieldNorm {
  std::optional<double> norm_uT;
  std::optional<double> dip_rad;
  core::FieldNormSource source = core::FieldNormSource::kData;
  std::string detail;
};

std::string describe(const char* fmt, double a, double b, const std::string& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c.c_str());
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Calibrate the IMU from a recording and write the calibration TOML that headingd-replay --calib "
               "applies (y_m = D m_b + o for the magnetometer, gyro bias/scale, accelerometer scale/bias)."};
  std::string imu_csv, method = "ellipsoid", out, report_dir, date, wmm_path = HEADINGD_WMM_DEFAULT_COF;
  std::optional<double> field_uT, lat, lon;
  std::size_t first = 0, end = 0;
  app.add_option("--imu-csv", imu_csv, "IMU CSV (BROAD columns; plain or gzip)")->required();
  app.add_option("--method", method, "thesis | ellipsoid | ml")->capture_default_str();
  app.add_option("--out", out, "calibration TOML to write")->required();
  app.add_option("--report", report_dir, "directory for an HTML report with plots");
  app.add_option("--field-uT", field_uT, "local field magnitude in uT (instead of the WMM)");
  app.add_option("--lat", lat, "latitude in degrees, for the WMM field");
  app.add_option("--lon", lon, "longitude in degrees, for the WMM field");
  app.add_option("--date", date, "date YYYY-MM-DD, for the WMM field");
  app.add_option("--wmm", wmm_path, "WMM coefficient file (NOAA COF)")->capture_default_str();
  std::size_t ml_decimation = 1;
  std::string ml_gradient = "reverse";
  app.add_option("--ml-gradient", ml_gradient,
                 "ml: how the likelihood's gradient is computed: reverse (exact, reverse mode; the fastest), jets "
                 "(exact, Ceres forward-mode Jets), forward or central (numerical differences); for comparisons")
      ->check(CLI::IsMember({"reverse", "jets", "forward", "central"}))
      ->capture_default_str();
  app.add_option("--ml-decimation", ml_decimation,
                 "ml: the likelihood on every n-th sample, the gyro pre-integrated between (for minutes of data)")
      ->capture_default_str();
  std::string hemisphere;
  app.add_option("--hemisphere", hemisphere,
                 "north | south: the magnetic hemisphere, for the sign of the dip when no --lat/--lon/--date is given "
                 "(ellipsoid and ml; it picks between the mirror solutions of the misalignment step)");
  app.add_option("--first-sample", first, "first row used (0-based)");
  app.add_option("--end-sample", end, "one past the last row used (default: all)");
  app.footer("Without --field-uT or --lat/--lon/--date the field norm is taken from the data (D scaled to unit "
             "determinant) and the file says so. Exit codes: 0 written, 1 file error, 2 bad arguments, 3 the data "
             "cannot give a calibration (the message says why).");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the help or the message
    return code == 0 ? 0 : 2;      // exit code 2 for every bad argument, as the footer says
  }
  if (method != "thesis" && method != "ellipsoid" && method != "ml") {
    std::fprintf(stderr, "headingd-calibrate: --method must be thesis, ellipsoid or ml (got '%s')\n", method.c_str());
    return 2;
  }
  const bool wmm_requested = lat || lon || !date.empty();
  if (wmm_requested && (!lat || !lon || date.empty())) {
    std::fprintf(stderr, "headingd-calibrate: the WMM needs all of --lat, --lon and --date\n");
    return 2;
  }
  if (field_uT && (!(*field_uT > 0.0) || *field_uT > 1000.0)) {
    std::fprintf(stderr, "headingd-calibrate: --field-uT must be within 0 .. 1000\n");
    return 2;
  }

  if (!hemisphere.empty() && hemisphere != "north" && hemisphere != "south") {
    std::fprintf(stderr, "headingd-calibrate: --hemisphere must be north or south (got '%s')\n", hemisphere.c_str());
    return 2;
  }
  if (!hemisphere.empty() && wmm_requested) {
    std::fprintf(stderr, "headingd-calibrate: give --hemisphere or --lat/--lon/--date, not both\n");
    return 2;
  }

  FieldNorm field;
  std::vector<core::ImuSample> all;
  try {
    if (field_uT) {
      field.norm_uT = *field_uT;
      field.source = core::FieldNormSource::kArgument;
      field.detail = describe("--field-uT %.3f", *field_uT, 0.0, "");
    } else if (wmm_requested) {
      int y = 0, m = 0, d = 0;
      if (std::sscanf(date.c_str(), "%d-%d-%d", &y, &m, &d) != 3) {
        std::fprintf(stderr, "headingd-calibrate: --date: expected YYYY-MM-DD, got '%s'\n", date.c_str());
        return 2;
      }
      const core::WorldMagneticModel wmm(core::parseWmmCoefficients(files::readMaybeGzipFile(wmm_path), wmm_path));
      const auto e = wmm.field({*lat, *lon, 0.0}, core::decimalYear(y, m, d));
      field.norm_uT = e.f_nT / 1000.0;
      field.dip_rad = e.inclination_deg * kDeg;
      field.source = core::FieldNormSource::kWmm;
      field.detail = wmm.modelName() + describe(" at %.4f N %.4f E on %s", *lat, *lon, date);
    }
    progress("reading %s", imu_csv.c_str());
    all = files::readImuCsv(imu_csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return 1;
  }
  if (end == 0 || end > all.size()) end = all.size();
  if (first >= end) {
    std::fprintf(stderr, "headingd-calibrate: no rows in [%zu, %zu)\n", first, end);
    return 2;
  }
  const std::span<const core::ImuSample> samples(all.data() + first, end - first);

  // The dip's sign (and value) known from the place: Kok & Schön's misalignment step has a
  // mirror pair of solutions that the data alone cannot tell apart (calib/dip_sign.hpp).
  calib::DipSign dip_sign = calib::DipSign::kUnknown;
  if (field.dip_rad) {
    dip_sign = calib::dipSignOf(*field.dip_rad);
  } else if (!hemisphere.empty()) {
    dip_sign = hemisphere == "north" ? calib::DipSign::kDown : calib::DipSign::kUp;
  }
  const auto withPlace = [&](calib::MlInitialOptions& o) {
    o.expected_dip_sign = dip_sign;
    o.expected_dip_rad = field.dip_rad;
  };

  core::ImuCalibration cal;
  cal.provenance.method = method;
  cal.provenance.source_file = imu_csv;
  cal.provenance.first_sample = static_cast<std::int64_t>(first);
  cal.provenance.end_sample = static_cast<std::int64_t>(end);
  cal.provenance.created = "headingd-calibrate";
  calibrate::ReportInput report;
  report.method = method;
  report.source_file = imu_csv;
  try {
    const double rate = calib::sampleRateHz(samples);
    progress("%zu samples at %.1f Hz; finding static segments", samples.size(), rate);
    const auto segments = calib::findStaticSegments(samples, {}, rate);
    progress("%zu static segments", segments.size());
    report.notes.push_back(std::to_string(segments.size()) + " static segments found");
    std::optional<Vec3> mag_sigma_raw;
    if (!segments.empty()) {
      const auto bias = calib::gyroBiasAtRest(segments);
      const calib::StaticSegment* longest = &segments[0];
      for (const auto& s : segments) {
        if (s.size() > longest->size()) longest = &s;
      }
      cal.gyro.bias_rad_s = bias.bias_rad_s;
      cal.gyro.noise_sigma_rad_s = bias.noise_sigma_rad_s;
      cal.accel.noise_sigma_m_s2 = longest->accel_sigma;
      mag_sigma_raw = longest->mag_sigma;
    }
    std::vector<Vec3> mags;
    std::vector<double> mag_t;
    for (const auto& s : samples) {
      if (s.has_mag && s.mag_uT.allFinite()) {
        mags.push_back(s.mag_uT);
        mag_t.push_back(static_cast<double>(s.t_ns - samples.front().t_ns) * 1e-9);
      }
    }
    // Radial residuals (|m_b| − F)/σ for the report, σ the noise at rest carried through D⁻¹.
    const auto radialResiduals = [&](double sigma_uT) {
      const core::ImuCorrection c(cal);
      std::vector<double> r;
      for (const Vec3& y : mags) r.push_back((c.magnetometer(y).norm() - cal.mag.field_norm_uT) / sigma_uT);
      return r;
    };
    const auto restSigmaCalibrated = [&](double fallback) {
      if (!mag_sigma_raw || !(mag_sigma_raw->norm() > 0.0)) return fallback;
      return mag_sigma_raw->norm() / std::sqrt(3.0) / std::cbrt(std::abs(cal.mag.D.determinant()));
    };

    if (method == "ellipsoid") {
      // The fit alone gives D only up to a rotation (K&S eq. 25); the misalignment step
      // (§6.2) turns it onto the inertial axes with the vertical from the gyro and
      // accelerometer, so that headings from D⁻¹(y - o) are right, not just |m_b|.
      calib::MlInitialOptions o;
      o.ellipsoid_min_coverage = calib::EllipsoidFitOptions{}.min_coverage;
      withPlace(o);
      if (!field.norm_uT) {  // from the data: D of unit determinant
        const auto pre = calib::fitEllipsoid(mags, 1.0);
        field.norm_uT = std::cbrt(pre.D.determinant());
        field.detail = "scaled so that det D = 1 (no --field-uT or WMM place given)";
      }
      o.field_norm_uT = *field.norm_uT;
      if (!segments.empty()) {
        o.stationary_begin = segments.front().begin;
        o.stationary_count = std::min<std::size_t>(segments.front().size(), 500);
      } else {
        // No rest found: the noise floors of MlInitialOptions carry the inclination EKF.
        o.stationary_count = std::min<std::size_t>(samples.size(), 100);
        report.notes.push_back("no static segment: gyro bias 0 assumed for the misalignment step");
      }
      progress("ellipsoid fit of %zu magnetometer samples and misalignment to the inertial axes (Kok & Schon "
               "sec. 6.1-6.2)", mags.size());
      const calib::MlInitialEstimate init = calib::estimateInitialParameters(samples, o);
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
               misalignment.angle() / kDeg, init.dip_rad / kDeg);
      report.notes.push_back(describe("misalignment to the inertial axes %.2f deg (K&S eq. 27, rms residual %.4f)",
                                      misalignment.angle() / kDeg, init.misalignment_rms, ""));
      if (init.misalignment_sign_chosen) {
        report.notes.push_back(std::string("misalignment: the best minimum of eq. 27 had the dip sign the place rules "
                                           "out; the best of sign ") + calib::dipSignName(dip_sign) + " was taken");
      }
      const double fit_residual = init.ellipsoid_residual_rms_uT;
      report.residuals = radialResiduals(restSigmaCalibrated(fit_residual));
      report.residual_kind = "(|m_b| - F) / sigma, sigma the magnetometer noise at rest";
    } else if (method == "thesis") {
      if (!field.norm_uT) throw calib::CalibrationError("thesis: the field norm is needed: give --field-uT or --lat/--lon/--date");
      const auto faces = calib::findSixFaces(segments);
      progress("six faces found; accelerometer (eq. 2.40), gyroscope (eq. 2.41), magnetometer (Newton, eq. 2.47)");
      const auto acc = calib::calibrateAccelSixPosition(segments, faces, 9.81);
      cal.accel.scale = acc.scale;
      cal.accel.bias_m_s2 = acc.bias_m_s2;
      const auto gs = calib::gyroScaleFromTurns(samples, segments, cal.gyro.bias_rad_s, rate);
      cal.gyro.scale = gs.scale;
      report.notes.push_back("gyroscope scale from whole turns about x, y, z: " + std::to_string(gs.turns_used[0]) +
                             ", " + std::to_string(gs.turns_used[1]) + ", " + std::to_string(gs.turns_used[2]) +
                             " (0: left at 1)");
      const auto mag = calib::calibrateMagSixPosition(segments, faces, *field.norm_uT, field.dip_rad);
      cal.mag.D = mag.alpha.inverse();
      cal.mag.offset_uT = mag.bias_uT;
      cal.mag.field_norm_uT = *field.norm_uT;
      cal.mag.dip_rad = mag.dip_rad;
      cal.provenance.residual_rms_uT = mag.residual_rms_uT;
      std::vector<Vec3> dirs;
      const core::ImuCorrection c(cal);
      for (const Vec3& y : mags) dirs.push_back(c.magnetometer(y));
      report.coverage = calib::sphereCoverage(dirs);
      cal.provenance.coverage = report.coverage;
      progress("Newton: %d iterations, residual %.3f uT rms", mag.iterations, mag.residual_rms_uT);
      report.residuals = radialResiduals(restSigmaCalibrated(1.0));
      report.residual_kind = "(|m_b| - F) / sigma over the whole recording, sigma the noise at rest";
    } else {
      calib::MlCalibrationOptions o;
      if (!field.norm_uT) {
        const auto pre = calib::fitEllipsoid(mags, 1.0);
        field.norm_uT = std::cbrt(pre.D.determinant());
        field.detail = "scaled so that det D = 1 (no --field-uT or WMM place given)";
      }
      o.initial.field_norm_uT = *field.norm_uT;
      withPlace(o.initial);
      o.decimation = std::max<std::size_t>(ml_decimation, 1);
      o.gradient = ml_gradient == "jets"      ? calib::MlGradient::kAutomatic
                   : ml_gradient == "forward" ? calib::MlGradient::kNumericForward
                   : ml_gradient == "central" ? calib::MlGradient::kNumericCentral
                                              : calib::MlGradient::kAdjoint;
      if (!segments.empty()) {
        o.initial.stationary_begin = segments.front().begin;
        o.initial.stationary_count = std::min<std::size_t>(segments.front().size(), 500);
      }
      progress("maximum likelihood (Kok & Schon Algorithm 1) on %zu samples (every %zu. in the likelihood); dip sign %s",
               samples.size(), o.decimation, calib::dipSignName(dip_sign));
      calib::MlProblem problem = calib::prepareMaximumLikelihood(samples, o);
      progress("initial estimate (step 1): dip %.2f deg, %d misalignment minima%s", problem.initial.dip_rad / kDeg,
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
      std::vector<Vec3> dirs;
      const core::ImuCorrection c(cal);
      for (const Vec3& y : mags) dirs.push_back(c.magnetometer(y));
      report.coverage = calib::sphereCoverage(dirs);
      cal.provenance.coverage = report.coverage;
      for (const auto& res : r.residuals_final) {
        if (res.has_mag) report.residuals.insert(report.residuals.end(), {res.mag.x(), res.mag.y(), res.mag.z()});
      }
      report.residual_kind = "EKF magnetometer innovations, normalised (x, y, z interleaved)";
      report.notes.push_back(describe("ML: %.0f iterations, %.2f s; cost from the initial estimate ", r.iterations,
                                      ml_seconds, "") +
                             std::to_string(r.cost_initial) + " to " + std::to_string(r.cost_final) + " (" +
                             r.termination + ")");
      if (r.starts > 1) {
        report.notes.push_back(std::string("ML: the first search ended at the dip's wall (") + r.termination_first_start +
                               "); a second started from the WMM's dip" +
                               (r.chosen_start == 1 ? " and was kept" : " and did no better"));
      }
      progress("ML: %d iterations, %d restarts, %d starts, %.2f s, %s", r.iterations, r.restarts, r.starts, ml_seconds,
               r.termination.c_str());
    }
    cal.mag.field_norm_source = field.source;
    cal.mag.field_norm_detail = field.detail;
    if (!cal.mag.dip_rad && field.dip_rad) cal.mag.dip_rad = field.dip_rad;
    if (mag_sigma_raw && !cal.mag.noise_sigma_uT) cal.mag.noise_sigma_uT = *mag_sigma_raw;
  } catch (const calib::CalibrationError& e) {
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return 3;
  }

  try {
    {
      std::ofstream f(out, std::ios::binary | std::ios::trunc);
      f << core::formatImuCalibration(cal);
      f.flush();
      if (!f) throw std::runtime_error(out + ": cannot write");
    }
    progress("wrote %s", out.c_str());
    if (!report_dir.empty()) {
      report.calibration = cal;
      for (const auto& s : samples) {
        if (s.has_mag && s.mag_uT.allFinite()) {
          report.mag_raw_uT.push_back(s.mag_uT);
          report.t_s.push_back(static_cast<double>(s.t_ns - samples.front().t_ns) * 1e-9);
        }
      }
      report.condition_number = cal.provenance.condition_number.value_or(0.0);
      calibrate::writeReport(report_dir, report);
      const auto v = calibrate::judge(report);
      progress("report in %s/index.html: %s", report_dir.c_str(), v.overall.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return 1;
  }
  return 0;
}
