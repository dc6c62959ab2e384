// headingd-calib-montecarlo: Kok & Schön (2016) §8 reproduced. Per run: draw the sensor of
// Table 2, simulate 100 still + rotating samples, calibrate with Algorithm 1's initial
// estimate and with the ML refinement, and score both by the heading RMSE (Fig. 8).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/ml/ml_calibration.hpp"
#include "headingd/calib_montecarlo/ks_simulation.hpp"
#include "headingd/cli/parse_command_line.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/files/output_file.hpp"

namespace {

using namespace headingd;
using headingd::core::kDegPerRad;

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(q * static_cast<double>(v.size()), v.size() - 1))];
}

// Whether the calibration is told the dip (its sign, and its value for the ML step's second
// start), as headingd-calibrate is by the WMM at --lat/--lon/--date (the simulated place is
// Linköping, dip +72°).
bool g_place_known = true;
std::size_t g_decimation = 1;

calib::MlCalibrationOptions optionsFor(const calib_montecarlo::KsRun& run, double min_coverage) {
  calib::MlCalibrationOptions o;
  o.initial.field_norm_uT = run.truth.field_norm_uT;
  if (g_place_known) {
    o.initial.expected_dip_sign = calib::dipSignOf(run.truth.dip_rad);
    o.initial.expected_dip_rad = run.truth.dip_rad;
  }
  o.initial.stationary_begin = 0;
  o.initial.stationary_count = run.stationary_samples;
  o.initial.ellipsoid_min_coverage = min_coverage;
  o.decimation = g_decimation;
  return o;
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The ML calibration of `run`, with the seconds of step 2 (the refinement) alone.
calib::MlCalibrationResult calibrateTimed(const calib_montecarlo::KsRun& run, const calib::MlCalibrationOptions& o,
                                          double& ml_seconds) {
  calib::MlProblem problem = calib::prepareMaximumLikelihood(run.samples, o);
  const auto t0 = std::chrono::steady_clock::now();
  calib::MlCalibrationResult r = calib::refineMaximumLikelihood(std::move(problem), o);
  ml_seconds = secondsSince(t0);
  return r;
}

// Median seconds of `repeats` ML refinements of `run` with `method`.
double timeMl(const calib_montecarlo::KsRun& run, double min_coverage, calib::MlGradient method, int repeats,
              int& iterations) {
  std::vector<double> seconds;
  for (int i = 0; i < repeats; ++i) {
    calib::MlCalibrationOptions o = optionsFor(run, min_coverage);
    o.gradient = method;
    double s = 0.0;
    const calib::MlCalibrationResult r = calibrateTimed(run, o, s);
    seconds.push_back(s);
    iterations = r.iterations;
  }
  return median(seconds);
}

// Median seconds of one cost-and-gradient evaluation at θ̂0.
double timeGradient(const calib_montecarlo::KsRun& run, double min_coverage, calib::MlGradient method, int repeats) {
  const calib::MlCalibrationOptions o = optionsFor(run, min_coverage);
  const calib::MlProblem problem = calib::prepareMaximumLikelihood(run.samples, o);
  const calib::MlData& data = problem.data;
  const calib::MlParameters& theta = problem.theta_initial;
  std::vector<double> seconds;
  for (int i = 0; i < repeats; ++i) {
    double cost = 0.0;
    calib::MlParameters gradient{};
    const auto t0 = std::chrono::steady_clock::now();
    calib::evaluateMlCost(data, theta, method, cost, &gradient);
    seconds.push_back(secondsSince(t0));
  }
  return median(seconds);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Kok & Schon (2016) section 8 Monte Carlo study: heading RMSE after magnetometer calibration with "
      "the initial estimate (Algorithm 1 step 1) and with the maximum-likelihood estimate."};
  int runs = 150;
  std::string variant_name = "short";
  std::string out_path;
  std::uint64_t seed = 1;
  double min_coverage = 0.1;
  double noise_factor = 1.0;
  int speed_repeats = 0;
  double require_fraction = 0.0;
  bool quiet = false;
  std::string table_reading = "variance";
  app.add_option("--runs", runs, "number of Monte Carlo runs")->check(CLI::PositiveNumber);
  app.add_option("--variant", variant_name,
                 "short (100 still + 300 rotating samples, K&S), long (100 + 2900) or 5min (100 + 29900)")
      ->check(CLI::IsMember({"short", "long", "5min"}));
  app.add_option("--out", out_path, "CSV with one row per run");
  app.add_option("--seed", seed, "seed of the first run; run i uses seed + i");
  app.add_option("--min-coverage", min_coverage,
                 "ellipsoid fit's minimum sphere coverage (K&S's 3 s of rotation visit little of it)");
  app.add_option("--noise-factor", noise_factor, "multiplies every Table 2 noise sigma (1 = the paper)");
  app.add_option("--speed-repeats", speed_repeats,
                 "also time the ML step on the first run with each gradient (reverse, Jets, numeric), this many times");
  app.add_option("--require-ml-better", require_fraction,
                 "exit 1 unless ML beats the initial estimate in at least this fraction of runs");
  app.add_option("--table2-noise", table_reading,
                 "read Table 2's noise entries as variances (literally, Sigma) or as standard deviations")
      ->check(CLI::IsMember({"variance", "sigma"}));
  app.add_flag("--quiet", quiet, "no line per run");
  std::size_t decimation = 1;
  app.add_option("--decimation", decimation,
                 "ML step on every n-th sample, the gyro pre-integrated between (1: every sample)")
      ->check(CLI::PositiveNumber);
  std::string place = "known";
  app.add_option("--place", place,
                 "known: the calibration is told the simulated dip, its sign and value (as headingd-calibrate is by "
                 "the WMM at --lat/--lon/--date); unknown: it is not (eq. 27's best minimum, one ML start)")
      ->check(CLI::IsMember({"known", "unknown"}));
  app.footer(std::string(
                 "Exit codes: 0 done, 1 --require-ml-better not met, 2 bad arguments or --out cannot be written (it is "
                 "written at the end, through a temporary file renamed into place).") +
             "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;
  g_place_known = place == "known";
  g_decimation = decimation;

  const calib_montecarlo::KsVariant variant = calib_montecarlo::parseVariant(variant_name);
  const calib_montecarlo::KsNoiseScale noise{noise_factor, table_reading == "sigma"};
  // Collected here and written whole at the end, through a temporary file renamed into place.
  std::ostringstream csv;
  const bool write_csv = !out_path.empty();
  if (write_csv) {
    csv << "run,seed,heading_rmse_initial_deg,heading_rmse_ml_deg,ml_better,cost_initial,cost_final,iterations,"
           "ml_seconds,converged,D_error_initial,D_error_ml,offset_error_initial_uT,offset_error_ml_uT,"
           "dip_error_initial_deg,dip_error_ml_deg,gyro_bias_error_initial_deg_s,gyro_bias_error_ml_deg_s,error\n";
  }

  const auto study_start = std::chrono::steady_clock::now();
  std::vector<double> rmse_init, rmse_ml, ml_seconds;
  int ml_better = 0, failures = 0;
  for (int i = 0; i < runs; ++i) {
    const std::uint64_t run_seed = seed + static_cast<std::uint64_t>(i);
    const calib_montecarlo::KsRun run = calib_montecarlo::simulateKokSchonRun(variant, run_seed, noise);
    const calib_montecarlo::KsTruth& truth = run.truth;
    try {
      double seconds = 0.0;
      const calib::MlCalibrationResult r = calibrateTimed(run, optionsFor(run, min_coverage), seconds);
      const double e0 = calib_montecarlo::headingRmseRad(run, r.initial.D, r.initial.offset_uT) * kDegPerRad;
      const double e1 = calib_montecarlo::headingRmseRad(run, r.D, r.offset_uT) * kDegPerRad;
      rmse_init.push_back(e0);
      rmse_ml.push_back(e1);
      ml_seconds.push_back(seconds);
      if (e1 < e0) ++ml_better;
      if (!quiet) {
        std::printf(
            "run %3d seed %llu: heading RMSE initial %7.3f deg, ML %7.3f deg, %3d iterations, %d restarts, "
            "%d starts, %.2f s%s\n",
            i, static_cast<unsigned long long>(run_seed), e0, e1, r.iterations, r.restarts, r.starts, seconds,
            e1 < e0 ? "" : "  (ML not better)");
        std::fflush(stdout);  // a long study shows its progress when its output goes to a file
      }
      if (write_csv) {
        csv << i << ',' << run_seed << ',' << e0 << ',' << e1 << ',' << (e1 < e0 ? 1 : 0) << ',' << r.cost_initial
            << ',' << r.cost_final << ',' << r.iterations << ',' << seconds << ',' << (r.converged ? 1 : 0) << ','
            << (r.initial.D - truth.mag_D).norm() << ',' << (r.D - truth.mag_D).norm() << ','
            << (r.initial.offset_uT - truth.mag_offset_uT).norm() << ',' << (r.offset_uT - truth.mag_offset_uT).norm()
            << ',' << (r.initial.dip_rad - truth.dip_rad) * kDegPerRad << ','
            << (r.dip_rad - truth.dip_rad) * kDegPerRad << ','
            << (r.initial.gyro_bias_rad_s - truth.gyro_bias_rad_s).norm() * kDegPerRad << ','
            << (r.gyro_bias_rad_s - truth.gyro_bias_rad_s).norm() * kDegPerRad << ",\n";
      }
    } catch (const calib::CalibrationError& e) {
      ++failures;
      if (!quiet)
        std::printf("run %3d seed %llu: calibration failed: %s\n", i, static_cast<unsigned long long>(run_seed),
                    e.what());
      if (write_csv)
        csv << i << ',' << run_seed << ",nan,nan,0,nan,nan,0,nan,0,nan,nan,nan,nan,nan,nan,nan,nan,\"" << e.what()
            << "\"\n";
    }
  }

  if (write_csv) {
    try {
      files::writeWholeOutputFile(out_path, csv.str());
    } catch (const std::exception& e) {
      std::cerr << "headingd-calib-montecarlo: " << e.what() << "\n";
      return 2;
    }
  }

  const double fraction = static_cast<double>(ml_better) / static_cast<double>(runs);
  std::printf(
      "\nKok & Schon section 8 Monte Carlo, variant %s, %d runs (seeds %llu..%llu), Table 2 noise read as %s, x%.2f, "
      "place %s, ML decimation %zu\n",
      calib_montecarlo::variantName(variant), runs, static_cast<unsigned long long>(seed),
      static_cast<unsigned long long>(seed + runs - 1), table_reading.c_str(), noise_factor, place.c_str(), decimation);
  std::printf("  heading RMSE, initial estimate: median %.3f deg, 90th percentile %.3f deg, max %.3f deg\n",
              median(rmse_init), quantile(rmse_init, 0.9), quantile(rmse_init, 1.0));
  std::printf("  heading RMSE, ML estimate:      median %.3f deg, 90th percentile %.3f deg, max %.3f deg\n",
              median(rmse_ml), quantile(rmse_ml, 0.9), quantile(rmse_ml, 1.0));
  std::printf("  ML better than the initial estimate in %d of %d runs (%.1f %%); %d runs failed\n", ml_better, runs,
              100.0 * fraction, failures);
  std::printf("  ML step: median %.3f s per run; whole study %.1f s\n", median(ml_seconds), secondsSince(study_start));

  if (speed_repeats > 0) {
    const calib_montecarlo::KsRun run = calib_montecarlo::simulateKokSchonRun(variant, seed, noise);
    std::printf("\nSpeed on run 0 (%zu samples), median of %d:\n", run.samples.size(), speed_repeats);
    // Exact by reverse mode (the default), exact by Jets, and numerical; ratios to reverse mode.
    const double g_rev = timeGradient(run, min_coverage, calib::MlGradient::kAdjoint, speed_repeats);
    const double g_ad = timeGradient(run, min_coverage, calib::MlGradient::kAutomatic, speed_repeats);
    const double g_fw = timeGradient(run, min_coverage, calib::MlGradient::kNumericForward, speed_repeats);
    const double g_ce = timeGradient(run, min_coverage, calib::MlGradient::kNumericCentral, speed_repeats);
    std::printf(
        "  one cost + gradient: reverse mode %.5f s, automatic (Jets) %.5f s (x%.2f), numeric forward %.5f s "
        "(x%.2f), numeric central %.5f s (x%.2f)\n",
        g_rev, g_ad, g_ad / g_rev, g_fw, g_fw / g_rev, g_ce, g_ce / g_rev);
    int it_rev = 0, it_ad = 0, it_fw = 0, it_ce = 0;
    const double m_rev = timeMl(run, min_coverage, calib::MlGradient::kAdjoint, speed_repeats, it_rev);
    const double m_ad = timeMl(run, min_coverage, calib::MlGradient::kAutomatic, speed_repeats, it_ad);
    const double m_fw = timeMl(run, min_coverage, calib::MlGradient::kNumericForward, speed_repeats, it_fw);
    const double m_ce = timeMl(run, min_coverage, calib::MlGradient::kNumericCentral, speed_repeats, it_ce);
    std::printf(
        "  whole ML step: reverse mode %.3f s (%d iterations), automatic (Jets) %.3f s (%d it., x%.2f), "
        "numeric forward %.3f s (%d it., x%.2f), numeric central %.3f s (%d it., x%.2f)\n",
        m_rev, it_rev, m_ad, it_ad, m_ad / m_rev, m_fw, it_fw, m_fw / m_rev, m_ce, it_ce, m_ce / m_rev);
  }
  if (require_fraction > 0.0 && fraction < require_fraction) {
    std::printf("FAIL: ML better in %.1f %% of runs, required %.1f %%\n", 100.0 * fraction, 100.0 * require_fraction);
    return 1;
  }
  return 0;
}
