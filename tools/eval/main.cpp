// headingd-eval: BROAD's RMSE of an estimate file against a reference file.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "headingd/core/orientation_error.hpp"
#include "headingd/files/numeric_csv.hpp"

int main(int argc, char** argv) {
  using namespace headingd;
  CLI::App app{"Score estimates against a reference with BROAD's metric; prints one JSON object."};
  std::string estimates_path, reference_path;
  app.add_option("--estimates", estimates_path, "headingd-replay output (t,qw,qx,qy,qz,...; q maps sensor to NED)")
      ->required();
  app.add_option("--reference", reference_path,
                 "reference CSV with ref_w,ref_x,ref_y,ref_z (sensor to ENU) and moving, e.g. a BROAD trial")
      ->required();
  CLI11_PARSE(app, argc, argv);

  try {
    const auto est = files::readNumericCsv(estimates_path, {"qw", "qx", "qy", "qz"});
    const auto ref = files::readNumericCsv(reference_path, {"ref_w", "ref_x", "ref_y", "ref_z", "moving"});
    if (est.rows != ref.rows) {
      throw files::CsvError("estimates have " + std::to_string(est.rows) + " rows, reference " +
                             std::to_string(ref.rows) + ": rows are paired by index, so they must match");
    }
    core::RmseAccumulator rmse;
    std::size_t failures = 0;  // scored rows without a usable estimate count as 180° errors
    for (std::size_t i = 0; i < ref.rows; ++i) {
      const core::Quat q_ref(ref.column("ref_w")[i], ref.column("ref_x")[i], ref.column("ref_y")[i],
                             ref.column("ref_z")[i]);
      if (ref.column("moving")[i] != 1.0 || !q_ref.coeffs().allFinite()) continue;
      const core::Quat q_est(est.column("qw")[i], est.column("qx")[i], est.column("qy")[i], est.column("qz")[i]);
      if (!q_est.coeffs().allFinite() || q_est.norm() < 1e-6) {
        ++failures;
        rmse.add({std::numbers::pi, std::numbers::pi, std::numbers::pi});
        continue;
      }
      rmse.add(core::orientationError(q_est, q_ref));
    }
    const auto r = rmse.rmse();
    constexpr double kDeg = 180.0 / std::numbers::pi;
    std::printf(
        "{\"total_rmse_deg\":%.4f,\"heading_rmse_deg\":%.4f,\"inclination_rmse_deg\":%.4f,\"samples\":%zu,"
        "\"failed_samples\":%zu}\n",
        r.total_rad * kDeg, r.heading_rad * kDeg, r.inclination_rad * kDeg, rmse.count(), failures);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-eval: %s\n", e.what());
    return 1;
  }
  return 0;
}
