// headingd-calibrate: IMU calibration from a recording (BROAD CSV), written as the TOML that
// headingd-replay --calib and the daemon apply. The methods (--method thesis, ellipsoid, ml)
// are described in headingd/calibrate/methods.hpp.
// Exit codes: 0 written, 1 file error, 2 bad arguments, 3 the data cannot give a calibration.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "headingd/calib/dip_sign.hpp"
#include "headingd/calibrate/methods.hpp"
#include "headingd/calibrate/progress.hpp"
#include "headingd/calibrate/report.hpp"
#include "headingd/cli/parse_command_line.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/core/wmm.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/output_file.hpp"

namespace {

using namespace headingd;
using calibrate::describe;
using calibrate::progress;
using headingd::core::kRadPerDeg;

// Exit codes.
constexpr int kWritten = 0;
constexpr int kFileError = 1;
constexpr int kBadArguments = 2;
constexpr int kNoCalibration = 3;

struct Arguments {
  std::string imu_csv, method = "ellipsoid", out, report_dir, date, wmm_path = HEADINGD_WMM_DEFAULT_COF;
  std::optional<double> field_uT, lat, lon;
  std::size_t first = 0, end = 0;
  calibrate::MlSettings ml;
  std::string hemisphere;

  bool wmmRequested() const { return lat || lon || !date.empty(); }
};

// Parses the command line into `a`; returns the exit code when the tool must stop here
// (help printed, or a bad argument), nothing when it goes on.
std::optional<int> parseArguments(int argc, char** argv, Arguments& a) {
  CLI::App app{
      "Calibrate the IMU from a recording and write the calibration TOML that headingd-replay --calib "
      "applies (y_m = D m_b + o for the magnetometer, gyro bias/scale, accelerometer scale/bias)."};
  app.add_option("--imu-csv", a.imu_csv, "IMU CSV (BROAD columns; plain or gzip)")->required();
  app.add_option("--method", a.method, "thesis | ellipsoid | ml")->capture_default_str();
  app.add_option("--out", a.out, "calibration TOML to write")->required();
  app.add_option("--report", a.report_dir, "directory for an HTML report with plots");
  app.add_option("--field-uT", a.field_uT, "local field magnitude in uT (instead of the WMM)");
  app.add_option("--lat", a.lat, "latitude in degrees, for the WMM field");
  app.add_option("--lon", a.lon, "longitude in degrees, for the WMM field");
  app.add_option("--date", a.date, "date YYYY-MM-DD, for the WMM field");
  app.add_option("--wmm", a.wmm_path, "WMM coefficient file (NOAA COF)")->capture_default_str();
  app.add_option("--ml-gradient", a.ml.gradient,
                 "ml: how the likelihood's gradient is computed: reverse (exact, reverse mode; the fastest), jets "
                 "(exact, Ceres forward-mode Jets), forward or central (numerical differences); for comparisons")
      ->check(CLI::IsMember({"reverse", "jets", "forward", "central"}))
      ->capture_default_str();
  app.add_option("--ml-decimation", a.ml.decimation,
                 "ml: the likelihood on every n-th sample, the gyro pre-integrated between (for minutes of data)")
      ->capture_default_str();
  app.add_option("--hemisphere", a.hemisphere,
                 "north | south: the magnetic hemisphere, for the sign of the dip when no --lat/--lon/--date is given "
                 "(ellipsoid and ml; it picks between the mirror solutions of the misalignment step)");
  app.add_option("--first-sample", a.first, "first row used (0-based)");
  app.add_option("--end-sample", a.end, "one past the last row used (default: all)");
  app.footer(
      std::string(
          "Without --field-uT or --lat/--lon/--date the field norm is taken from the data (D scaled to unit "
          "determinant) and the file says so. Exit codes: 0 written, 1 file error, 2 bad arguments, 3 the data "
          "cannot give a calibration (the message says why). An --out that is the same file as an input is refused "
          "(2).") +
      "\n" + headingd::cli::kFileRules);
  return cli::parseCommandLine(app, argc, argv);  // exit code 2 for every bad argument, as the footer says
}

// The checks across options that CLI11 does not make; false (after a message) for bad ones.
bool argumentsConsistent(const Arguments& a) {
  if (a.method != "thesis" && a.method != "ellipsoid" && a.method != "ml") {
    std::fprintf(stderr, "headingd-calibrate: --method must be thesis, ellipsoid or ml (got '%s')\n", a.method.c_str());
    return false;
  }
  if (a.wmmRequested() && (!a.lat || !a.lon || a.date.empty())) {
    std::fprintf(stderr, "headingd-calibrate: the WMM needs all of --lat, --lon and --date\n");
    return false;
  }
  if (a.field_uT && (!(*a.field_uT > 0.0) || *a.field_uT > 1000.0)) {
    std::fprintf(stderr, "headingd-calibrate: --field-uT must be within 0 .. 1000\n");
    return false;
  }
  if (!a.hemisphere.empty() && a.hemisphere != "north" && a.hemisphere != "south") {
    std::fprintf(stderr, "headingd-calibrate: --hemisphere must be north or south (got '%s')\n", a.hemisphere.c_str());
    return false;
  }
  if (!a.hemisphere.empty() && a.wmmRequested()) {
    std::fprintf(stderr, "headingd-calibrate: give --hemisphere or --lat/--lon/--date, not both\n");
    return false;
  }
  return true;
}

// The field from --field-uT or the WMM at --lat/--lon/--date, if either is given. Returns
// false (after a message) for a malformed --date; throws for a WMM file that cannot be read.
bool fieldFromArguments(const Arguments& a, calibrate::FieldNorm& field) {
  if (a.field_uT) {
    field.norm_uT = *a.field_uT;
    field.source = core::FieldNormSource::kArgument;
    field.detail = describe("--field-uT %.3f", *a.field_uT, 0.0, "");
  } else if (a.wmmRequested()) {
    int y = 0, m = 0, d = 0;
    if (std::sscanf(a.date.c_str(), "%d-%d-%d", &y, &m, &d) != 3) {
      std::fprintf(stderr, "headingd-calibrate: --date: expected YYYY-MM-DD, got '%s'\n", a.date.c_str());
      return false;
    }
    const core::WorldMagneticModel wmm(
        core::parseWmmCoefficients(files::readMaybeGzipFile(a.wmm_path, files::kWmmFileLimit), a.wmm_path));
    const auto e = wmm.field({*a.lat, *a.lon, 0.0}, core::decimalYear(y, m, d));
    field.norm_uT = e.f_nT / 1000.0;
    field.dip_rad = e.inclination_deg * kRadPerDeg;
    field.source = core::FieldNormSource::kWmm;
    field.detail = wmm.modelName() + describe(" at %.4f N %.4f E on %s", *a.lat, *a.lon, a.date);
  }
  return true;
}

// The dip's sign known from the place (the WMM's dip) or from --hemisphere.
calib::DipSign dipSignFrom(const Arguments& a, const calibrate::FieldNorm& field) {
  if (field.dip_rad) return calib::dipSignOf(*field.dip_rad);
  if (!a.hemisphere.empty()) return a.hemisphere == "north" ? calib::DipSign::kDown : calib::DipSign::kUp;
  return calib::DipSign::kUnknown;
}

// Runs the chosen method on the samples; throws when the data cannot give a calibration.
void runMethod(const Arguments& a, std::span<const core::ImuSample> samples, calibrate::FieldNorm& field,
               core::ImuCalibration& cal, calibrate::ReportInput& report) {
  const calibrate::Recording rec = calibrate::prepareRecording(samples, dipSignFrom(a, field), cal, report);
  if (a.method == "ellipsoid") {
    calibrate::calibrateEllipsoid(rec, field, cal, report);
  } else if (a.method == "thesis") {
    calibrate::calibrateThesis(rec, field, cal, report);
  } else {
    calibrate::calibrateMl(rec, a.ml, field, cal, report);
  }
  calibrate::completeCalibration(rec, field, cal);
}

// Writes the calibration TOML and, with --report, the HTML report; throws on a write error.
void writeOutputs(const Arguments& a, std::span<const core::ImuSample> samples, const core::ImuCalibration& cal,
                  calibrate::ReportInput& report) {
  files::writeWholeOutputFile(a.out, core::formatImuCalibration(cal));
  progress("wrote %s", a.out.c_str());
  if (a.report_dir.empty()) return;
  report.calibration = cal;
  for (const auto& s : samples) {
    if (s.has_mag && s.mag_uT.allFinite()) {
      report.mag_raw_uT.push_back(s.mag_uT);
      report.t_s.push_back(static_cast<double>(s.t_ns - samples.front().t_ns) * 1e-9);
    }
  }
  report.condition_number = cal.provenance.condition_number.value_or(0.0);
  calibrate::writeReport(a.report_dir, report);
  const auto v = calibrate::judge(report);
  progress("report in %s/index.html: %s", a.report_dir.c_str(), v.overall.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Arguments a;
  if (const auto code = parseArguments(argc, argv, a)) return *code;
  if (!argumentsConsistent(a)) return kBadArguments;

  try {
    files::refuseOutputOverInputs({"--out", a.out}, {{"--imu-csv", a.imu_csv}, {"--wmm", a.wmm_path}});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return kBadArguments;
  }

  calibrate::FieldNorm field;
  std::vector<core::ImuSample> all;
  try {
    if (!fieldFromArguments(a, field)) return kBadArguments;
    progress("reading %s", a.imu_csv.c_str());
    // All rows in memory: the fit takes a window [first, end) and every method goes over it
    // more than once. readImuCsv parses in place (files::ImuCsvReader), so only the samples
    // themselves are held.
    all = files::readImuCsv(a.imu_csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return kFileError;
  }
  const std::size_t end = a.end == 0 || a.end > all.size() ? all.size() : a.end;
  if (a.first >= end) {
    std::fprintf(stderr, "headingd-calibrate: no rows in [%zu, %zu)\n", a.first, end);
    return kBadArguments;
  }
  const std::span<const core::ImuSample> samples(all.data() + a.first, end - a.first);

  core::ImuCalibration cal;
  cal.provenance.method = a.method;
  cal.provenance.source_file = a.imu_csv;
  cal.provenance.first_sample = static_cast<std::int64_t>(a.first);
  cal.provenance.end_sample = static_cast<std::int64_t>(end);
  cal.provenance.created = "headingd-calibrate";
  calibrate::ReportInput report;
  report.method = a.method;
  report.source_file = a.imu_csv;
  try {
    runMethod(a, samples, field, cal, report);
  } catch (const std::exception& e) {  // calib::CalibrationError or another failure of the data
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return kNoCalibration;
  }

  try {
    writeOutputs(a, samples, cal, report);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-calibrate: %s\n", e.what());
    return kFileError;
  }
  return kWritten;
}
