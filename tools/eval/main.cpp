// headingd-eval: BROAD's RMSE of an estimate file against a reference file.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "headingd/cli/parse_command_line.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/core/orientation_error.hpp"
#include "headingd/files/csv_row_reader.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace {

// JSON has no nan or inf: a figure that does not exist is null.
std::string jsonNumber(double value) {
  if (!std::isfinite(value)) return "null";
  char text[48];
  std::snprintf(text, sizeof text, "%.4f", value);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace headingd;
  CLI::App app{
      "Score estimates against a reference with BROAD's metric; prints one JSON object. With no row to "
      "score (no reference row with moving = 1 and a finite quaternion) the RMSE figures are null and "
      "\"reason\" says why."};
  std::string estimates_path, reference_path;
  app.add_option("--estimates", estimates_path, "headingd-replay output (t,qw,qx,qy,qz,...; q maps sensor to NED)")
      ->required();
  app.add_option("--reference", reference_path,
                 "reference CSV with ref_w,ref_x,ref_y,ref_z (sensor to ENU) and moving, e.g. a BROAD trial")
      ->required();
  app.footer(
      std::string(
          "Exit codes: 0 scored (or nothing to score: see \"reason\"), 1 a file cannot be read, is malformed, or "
          "the two files' row counts differ, 2 bad arguments.") +
      "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;

  try {
    // Both files row by row, in step (rows are paired by index): memory stays flat whatever
    // their length.
    files::CsvRowReader est(estimates_path, {"qw", "qx", "qy", "qz"});
    files::CsvRowReader ref(reference_path, {"ref_w", "ref_x", "ref_y", "ref_z", "moving"});
    double e[4], r[5];
    core::RmseAccumulator rmse;
    std::size_t failures = 0;  // scored rows without a usable estimate count as 180° errors
    while (true) {
      const bool have_est = est.next(e);
      const bool have_ref = ref.next(r);
      if (have_est != have_ref) {  // one ran out first: count the other's rows for the message
        while (est.next(e)) {
        }
        while (ref.next(r)) {
        }
        throw files::CsvError("estimates have " + std::to_string(est.rows()) + " rows, reference " +
                              std::to_string(ref.rows()) + ": rows are paired by index, so they must match");
      }
      if (!have_est) break;
      const core::Quat q_ref(r[0], r[1], r[2], r[3]);
      if (r[4] != 1.0 || !q_ref.coeffs().allFinite()) continue;
      const core::Quat q_est(e[0], e[1], e[2], e[3]);
      if (!q_est.coeffs().allFinite() || q_est.norm() < 1e-6) {
        ++failures;
        rmse.add({std::numbers::pi, std::numbers::pi, std::numbers::pi});
        continue;
      }
      rmse.add(core::orientationError(q_est, q_ref));
    }
    const auto result = rmse.rmse();
    using headingd::core::kDegPerRad;
    const std::string reason =
        rmse.count() == 0 ? ",\"reason\":\"no row to score: no reference row has moving = 1 and a finite quaternion\""
                          : "";
    std::printf(
        "{\"total_rmse_deg\":%s,\"heading_rmse_deg\":%s,\"inclination_rmse_deg\":%s,\"samples\":%zu,"
        "\"failed_samples\":%zu%s}\n",
        jsonNumber(result.total_rad * kDegPerRad).c_str(), jsonNumber(result.heading_rad * kDegPerRad).c_str(),
        jsonNumber(result.inclination_rad * kDegPerRad).c_str(), rmse.count(), failures, reason.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-eval: %s\n", e.what());
    return 1;
  }
  return 0;
}
