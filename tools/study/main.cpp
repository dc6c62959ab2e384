// headingd-study: the estimator on BROAD trials and simulated motions, at any sample rate,
// scored as tables. Runs in memory, two jobs at a time.
//
//   headingd-study broad [--dir DIR] [--rate HZ ...] [--set key=value ...] [--config TOML]
//   headingd-study sim --scenario NAME --seeds 1-20 [--rate HZ ...] [--grade consumer] [--accel-lag-s S] [--set ...]
//   ... --trace FILE  (one run: per-sample diagnostics as CSV)
//   ... --qsf         (the quasi-static field periods and how still the field was in them)
//   ... --smooth      (headingd's offline smoother scored in place of the causal filter; with
//                      --anchors, beside VQF's offline and causal filters)
//   ... --anchors DIR (VQF and Fusion beside headingd: the drivers built by ../shared/anchors/build.sh;
//                      then also each filter's fitted heading over the first 25 s and after)
// The h<2s% column: the share of scored samples whose heading error is within twice the
// estimator's stated heading 1-sigma (plain errors on simulations, after the fitted alignment
// on recordings): docs/heading-sigma.md.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>

#include "headingd/cli/parse_command_line.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/core/mag_heading_observer.hpp"
#include "headingd/core/params_toml.hpp"
#include "headingd/core/two_filter_smoother.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/output_file.hpp"
#include "headingd/sim/simulation.hpp"
#include "headingd/study/anchors.hpp"
#include "headingd/study/quasi_static_score.hpp"
#include "headingd/study/reference_delay.hpp"
#include "headingd/study/resample.hpp"
#include "headingd/study/scoring.hpp"

namespace {

using namespace headingd;
using headingd::core::kDegPerRad;

core::EstimatorParams loadParams(const std::string& config, const std::vector<std::string>& sets) {
  std::string text = config.empty() ? std::string() : files::readMaybeGzipFile(config, files::kConfigFileLimit);
  if (!sets.empty()) {
    if (text.find("[estimator]") == std::string::npos) text += "\n[estimator]\n";
    for (const std::string& s : sets) text += s + "\n";  // later keys of a table are errors: --set replaces none
  }
  return text.empty() ? core::EstimatorParams{} : core::parseEstimatorParams(text, config.empty() ? "--set" : config);
}

template <typename Job>
void runParallel(std::size_t count, const Job& job) {
  std::atomic<std::size_t> next{0};
  const unsigned workers = std::max(1u, std::min(std::thread::hardware_concurrency(), 8u));
  std::vector<std::thread> threads;
  for (unsigned w = 0; w < workers; ++w) {
    threads.emplace_back([&] {
      for (std::size_t i = next++; i < count; i = next++) job(i);
    });
  }
  for (auto& t : threads) t.join();
}

std::vector<std::uint64_t> parseSeeds(const std::string& text) {
  std::vector<std::uint64_t> seeds;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    const auto dash = part.find('-');
    if (dash == std::string::npos) {
      seeds.push_back(std::stoull(part));
    } else {
      for (auto s = std::stoull(part.substr(0, dash)); s <= std::stoull(part.substr(dash + 1)); ++s) seeds.push_back(s);
    }
  }
  return seeds;
}

// The field's dip in a measurement through an attitude; NaN where it gives none (unknown
// reference, vertical field).
double dipDeg(const core::MagHeadingMeasurement& m) {
  return m.valid ? m.dip_rad * kDegPerRad : std::numeric_limits<double>::quiet_NaN();
}

void writeTrace(const std::string& path, const study::Recording& r, const core::EstimatorParams& params) {
  std::ostringstream out;  // written whole at the end, through a temporary file renamed into place
  out << "t,incl_err_deg,heading_err_deg,level,d_k,at_rest,bias_x,bias_y,bias_z,mag_disturbed,still_blocks,moving,"
         "roll_deg,pitch_deg,true_roll_deg,true_pitch_deg,mag_used,mag_restores,gravity_noise,heading_sigma_deg,"
         "mag_innovation_deg,mag_gain,rate_sigma_deg_s,heading_redefined,head_height,published_heading_err_deg,"
         "yaw_err_deg,vertical_rate_correction_mrad_s,mag_lag_ms,accel_lag_ms,accel_delay_estimate_ms,accel_delay_"
         "sigma_ms,"
         "tilt_sigma_deg,mag_norm_jump,mag_dip_jump,dip_deg,true_dip_deg,heading_prior_sigma_deg,mag_dip_deviation_deg,"
         "field_heading_error_deg,tilt_heading_error_deg,vertical_error_deg,shown_rate_error_mrad_s,"
         "shown_rate_error_sigma_mrad_s,true_rate_error_mrad_s,mag_quasi_static,qsf_mag_update,mau\n";
  std::vector<core::EstimatorOutput> outputs;
  std::vector<std::uint64_t> still_blocks, restores;
  std::vector<double> rate_sigmas, tilt_sigmas, prior_sigmas, dip_deviations, shown_rates, shown_rate_sigmas;
  std::vector<std::pair<double, double>> accel_delays;  // the regression's estimate and sigma
  const auto est = study::runEstimator(r, params, [&](std::size_t, const core::Estimator& e) {
    outputs.push_back(e.output());
    accel_delays.emplace_back(e.accelDelay().estimateS(), e.accelDelay().sigmaS());
    rate_sigmas.push_back(e.headingUncertainty().rateSigmaRadS());
    prior_sigmas.push_back(e.headingUncertainty().priorSigmaRad());
    shown_rates.push_back(e.headingUncertainty().shownRateRadS());
    shown_rate_sigmas.push_back(e.headingUncertainty().shownRateSigmaRadS());
    dip_deviations.push_back(e.magDisturbance().dipDeviation());
    // tilt_sigma_deg: the EKF's own 1-sigma of the tilt, √ of its covariance about north plus east.
    tilt_sigmas.push_back(std::sqrt(e.ekf().tiltCovariance().trace()));
    still_blocks.push_back(e.counters().bias_still_blocks);
    restores.push_back(e.counters().mag_heading_restores);
  });
  const auto errors = study::perSampleErrors(r, est);
  // mag_norm_jump, mag_dip_jump: which relative disturbance test fired. dip_deg, true_dip_deg:
  // the sample's raw field's dip through the published attitude and through the reference's
  // (the dip test's own is of the field turned forward by its lag, through the attitude
  // before the sample's updates), and mag_dip_deviation_deg the dip test's own |dip - its
  // low-pass| at the last field sample. heading_prior_sigma_deg: the heading sigma before the
  // innovations (heading_uncertainty.hpp); heading_sigma_deg is the published one.
  // field_heading_error_deg: the heading the sample's raw field gives through the reference's
  // attitude less the reference's heading (the field's own error: a building, a residual hard
  // iron, the noise). tilt_heading_error_deg: what the published tilt adds to that, tan(dip)
  // times the tilt's error about magnetic north (the innovation through the published attitude
  // less the one through the reference's, plus the estimate's turn about the vertical, which
  // the first difference holds too). vertical_error_deg: that turn (signed).
  // shown_rate_error_mrad_s and its sigma: what the heading sigma's filter that has seen the
  // innovations makes of the rate error about the vertical (heading_uncertainty.hpp);
  // true_rate_error_mrad_s: the rate error itself, the bias-corrected gyro about NED down and
  // the integral term's correction, less the reference's rate (from its attitude at the next
  // sample).
  char line[800];
  for (std::size_t i = 0; i < r.size(); ++i) {
    const auto& o = outputs[i];
    const auto e = core::eulerZyx(o.q_nb);
    const auto t = core::eulerZyx(r.truth_nb[i]);
    // The published heading (x-axis yaw, or lying down the head's) and the x-axis yaw against
    // the reference's x-axis yaw, plain (no alignment fitted).
    const auto wrapped_deg = [](double a) { return std::remainder(a, 2.0 * std::numbers::pi) * kDegPerRad; };
    const auto through_truth = core::measureMagHeading(r.truth_nb[i], r.samples[i].mag_uT, 0.0);
    const auto through_estimate = core::measureMagHeading(o.q_nb, r.samples[i].mag_uT, 0.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double field_error_deg = through_truth.valid ? wrapped_deg(through_truth.innovation_rad) : nan;
    // The estimate's turn from the reference about NED down (signed; the twist of q q_ref⁻¹).
    const core::Quat turn = o.q_nb * r.truth_nb[i].conjugate();
    const double vertical_error_rad = 2.0 * std::atan(turn.z() / turn.w());
    const core::Vec3 rate_error = r.samples[i].gyro_rad_s - o.gyro_bias_rad_s - study::referenceRate(r, i);
    const double true_rate_error =
        (r.truth_nb[i] * rate_error).z() + o.vertical_rate_correction_rad_s;  // turned in, too
    const double tilt_error_deg =
        through_truth.valid && through_estimate.valid
            ? wrapped_deg(through_estimate.innovation_rad - through_truth.innovation_rad + vertical_error_rad)
            : nan;
    std::snprintf(
        line, sizeof line,
        "%.4f,%.4f,%.4f,%d,%.4g,%d,%.5f,%.5f,%.5f,%d,%llu,%d,%.3f,%.3f,%.3f,%.3f,%d,%llu,%.3f,%.3f,%.4f,%.3g,%.4f,"
        "%d,%.4f,%.3f,%.3f,%.4f,%.2f,%.2f,%.2f,%.2f,%.4f,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,"
        "%d,%d,%d\n",
        1e-9 * static_cast<double>(r.samples[i].t_ns - r.samples[0].t_ns), errors[i].inclination_rad * kDegPerRad,
        errors[i].heading_rad * kDegPerRad, static_cast<int>(o.motion_level), o.accel_disturbance, o.at_rest ? 1 : 0,
        o.gyro_bias_rad_s.x(), o.gyro_bias_rad_s.y(), o.gyro_bias_rad_s.z(), o.mag_disturbed ? 1 : 0,
        static_cast<unsigned long long>(still_blocks[i]), r.moving[i] ? 1 : 0, e.roll_rad * kDegPerRad,
        e.pitch_rad * kDegPerRad, t.roll_rad * kDegPerRad, t.pitch_rad * kDegPerRad, o.mag_used ? 1 : 0,
        static_cast<unsigned long long>(restores[i]), o.gravity_noise_m_s2, o.heading_sigma_rad * kDegPerRad,
        o.mag_innovation_rad * kDegPerRad, o.mag_gain, rate_sigmas[i] * kDegPerRad, o.heading_redefined ? 1 : 0,
        o.head_height, wrapped_deg(o.heading_rad - t.yaw_rad), wrapped_deg(o.yaw_rad - t.yaw_rad),
        1e3 * o.vertical_rate_correction_rad_s, 1e3 * o.mag_lag_s, 1e3 * o.accel_lag_s, 1e3 * accel_delays[i].first,
        1e3 * accel_delays[i].second, tilt_sigmas[i] * kDegPerRad, o.mag_disturbance.norm_jump ? 1 : 0,
        o.mag_disturbance.dip_jump ? 1 : 0, dipDeg(through_estimate), dipDeg(through_truth),
        prior_sigmas[i] * kDegPerRad, dip_deviations[i] * kDegPerRad, field_error_deg, tilt_error_deg,
        vertical_error_rad * kDegPerRad, 1e3 * shown_rates[i], 1e3 * shown_rate_sigmas[i], 1e3 * true_rate_error,
        o.mag_quasi_static ? 1 : 0, o.qsf_mag_update_applied ? 1 : 0, o.mau_applied ? 1 : 0);
    out << line;
  }
  files::writeWholeOutputFile(path, out.str());
}

struct Row {
  std::string name;
  double rate_hz = 0.0;
  study::RunScore score;
  study::EpisodeScore episode;
  // Share of heading errors within 2 stated sigmas: plain errors on simulations (the truth is
  // in the estimator's magnetic frame), after the fitted alignment on recordings.
  double heading_2sigma = 0.0;
  std::vector<study::RunScore> anchors;        // one per --anchors filter, in findAnchors' order
  study::ReferenceDelays delays;               // with --reference-delays
  double learned_mag_lag_s = 0.0;              // the estimator's, median over the second half
  study::QuasiStaticScore mag_qsf, accel_qsf;  // with --qsf
  core::EstimatorCounters counters;            // at the end of the run
  double minutes = 0.0;                        // of samples
};

double medianOfSecondHalf(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto first = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  const auto middle = first + (v.end() - first) / 2;
  std::nth_element(first, middle, v.end());
  return *middle;
}

void printReferenceDelays(const std::vector<Row>& rows) {
  std::printf(
      "\ndelays against the reference (ms; reference_delay.hpp): the field's that makes it steadiest in "
      "the earth frame (its spread there, and at 0 ms, uT), the gyro's, and what headingd learned and applied "
      "(mag_lag, median of the second half)\n");
  std::printf("%-46s %7s | %6s %13s | %6s | %8s\n", "run", "Hz", "field", "spread (0 ms)", "gyro", "headingd");
  for (const Row& row : rows) {
    if (!row.delays.valid) {
      std::printf("%-46s %7.1f | too few samples with a reference\n", row.name.c_str(), row.rate_hz);
      continue;
    }
    std::printf("%-46s %7.1f | %6.0f %5.2f (%5.2f) | %6.0f | %8.1f\n", row.name.c_str(), row.rate_hz,
                1e3 * row.delays.mag_s, row.delays.mag_spread_uT, row.delays.mag_spread_at_zero_uT,
                1e3 * row.delays.gyro_s, 1e3 * row.learned_mag_lag_s);
  }
}

// How often the updates from the field's direction fired (issue 29), where one is on.
void printFieldUpdates(const std::vector<Row>& rows) {
  std::printf(
      "\nfield updates per minute (quasi_static_field_update.hpp, magnetic_attitude_update.hpp, "
      "rotated_field_update.hpp): QSF applied / rejected by the gate, MAU applied / rejected by the gate / "
      "not verified by the magnetic frame, MARU and AGU applied / rejected by the gate\n");
  std::printf("%-46s %7s | %8s %8s | %8s %8s %8s | %8s %8s | %8s %8s\n", "run", "Hz", "qsf", "qsf.rej", "mau",
              "mau.rej", "mau.unv", "maru", "maru.rej", "agu", "agu.rej");
  for (const Row& row : rows) {
    const auto& c = row.counters;
    const auto perMinute = [&](std::uint64_t n) { return static_cast<double>(n) / row.minutes; };
    std::printf("%-46s %7.1f | %8.1f %8.1f | %8.1f %8.1f %8.1f | %8.1f %8.1f | %8.1f %8.1f\n", row.name.c_str(),
                row.rate_hz, perMinute(c.qsf_mag_updates), perMinute(c.qsf_mag_updates_rejected),
                perMinute(c.mau_updates), perMinute(c.mau_updates_rejected), perMinute(c.mau_updates_unverified),
                perMinute(c.maru_updates), perMinute(c.maru_updates_rejected), perMinute(c.agu_updates),
                perMinute(c.agu_updates_rejected));
  }
}

void printQuasiStatic(const std::vector<Row>& rows) {
  std::printf(
      "\nquasi-static periods (quasi_static_field.hpp; --qsf): share of the samples, periods, their mean "
      "length (s), and the vector's distance from the period's start through the reference attitude, "
      "median / 95th percentile (field uT, specific force m/s^2)\n");
  std::printf("%-46s %7s | %6s %5s %6s %6s %6s | %6s %5s %6s %6s %6s\n", "run", "Hz", "mag%", "per", "len", "med",
              "p95", "acc%", "per", "len", "med", "p95");
  for (const Row& row : rows) {
    const auto& m = row.mag_qsf;
    const auto& a = row.accel_qsf;
    std::printf("%-46s %7.1f | %6.1f %5zu %6.1f %6.2f %6.2f | %6.1f %5zu %6.1f %6.3f %6.3f\n", row.name.c_str(),
                row.rate_hz, 100.0 * m.share, m.periods, m.mean_period_s, m.median_drift, m.p95_drift, 100.0 * a.share,
                a.periods, a.mean_period_s, a.median_drift, a.p95_drift);
  }
}

// The fitted heading apart for the opening of each run and the rest (study::kOpeningS): how
// fast each filter finds the heading from its start.
void printOpenings(const std::vector<Row>& rows, const std::vector<double>& rates,
                   const std::vector<std::string>& names) {
  std::printf("\nfitted heading (deg): per filter the first %.0f s of the scored samples | after\n", study::kOpeningS);
  std::printf("%-46s %7s", "run", "Hz");
  for (const auto& n : names) std::printf(" | %-13s", n.c_str());
  std::printf("\n");
  for (std::size_t ri = 0; ri < rates.size(); ++ri) {
    std::vector<std::array<double, 2>> sums(names.size(), {0, 0});
    std::vector<std::array<std::size_t, 2>> counts(names.size(), {0, 0});
    for (std::size_t job = ri; job < rows.size(); job += rates.size()) {
      const Row& row = rows[job];
      std::printf("%-46s %7.1f", row.name.c_str(), row.rate_hz);
      for (std::size_t f = 0; f < names.size(); ++f) {
        const study::RunScore& s = f == 0 ? row.score : row.anchors[f - 1];
        const std::array<double, 2> v = {s.aligned_opening_rmse.heading_rad * kDegPerRad,
                                         s.aligned_after_opening_rmse.heading_rad * kDegPerRad};
        std::printf(" | %6.2f %6.2f", v[0], v[1]);
        for (int k = 0; k < 2; ++k) {
          if (std::isnan(v[k])) continue;  // a run shorter than its opening
          sums[f][k] += v[k];
          ++counts[f][k];
        }
      }
      std::printf("\n");
    }
    std::printf("OPENING-MEAN %-33s %7.1f", "", rates[ri]);
    for (std::size_t f = 0; f < names.size(); ++f) {
      std::printf(" | %6.2f %6.2f", sums[f][0] / static_cast<double>(counts[f][0]),
                  sums[f][1] / static_cast<double>(counts[f][1]));
    }
    std::printf("\n");
  }
}

// One filter's figures in the side-by-side table: plain total, then fitted total / heading /
// inclination (constant earth and body rotations fitted for each filter alone).
void printSideBySide(const std::vector<Row>& rows, const std::vector<double>& rates,
                     const std::vector<study::AnchorFilter>& anchors) {
  std::vector<std::string> names = {"headingd"};
  for (const auto& a : anchors) names.push_back(a.name);
  std::printf("\nside by side (deg): per filter plain total | fitted total / heading / inclination\n");
  std::printf("%-46s %7s", "run", "Hz");
  for (const auto& n : names) std::printf(" | %-27s", n.c_str());
  std::printf("\n");
  for (std::size_t ri = 0; ri < rates.size(); ++ri) {
    std::vector<std::array<double, 4>> sums(names.size(), {0, 0, 0, 0});
    std::size_t n = 0;
    for (std::size_t job = ri; job < rows.size(); job += rates.size(), ++n) {
      const Row& row = rows[job];
      std::printf("%-46s %7.1f", row.name.c_str(), row.rate_hz);
      for (std::size_t f = 0; f < names.size(); ++f) {
        const study::RunScore& s = f == 0 ? row.score : row.anchors[f - 1];
        const std::array<double, 4> v = {s.rmse.total_rad * kDegPerRad, s.aligned_rmse.total_rad * kDegPerRad,
                                         s.aligned_rmse.heading_rad * kDegPerRad,
                                         s.aligned_rmse.inclination_rad * kDegPerRad};
        std::printf(" | %6.2f %6.2f/%6.2f/%6.2f", v[0], v[1], v[2], v[3]);
        for (int k = 0; k < 4; ++k) sums[f][k] += v[k];
      }
      std::printf("\n");
    }
    std::printf("SIDE-MEAN %-36s %7.1f", "", rates[ri]);
    for (const auto& s : sums) std::printf(" | %6.2f %6.2f/%6.2f/%6.2f", s[0] / n, s[1] / n, s[2] / n, s[3] / n);
    std::printf("\n");
  }
  printOpenings(rows, rates, names);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The estimator on BROAD trials and simulated motions at any sample rate, scored."};
  app.require_subcommand(1);
  std::string config, trace, anchors_dir;
  std::vector<std::string> sets;
  std::vector<double> rates;
  bool quasi_static = false, smooth = false;
  auto common = [&](CLI::App* c) {
    c->add_flag("--smooth", smooth,
                "score headingd's offline smoother (core/two_filter_smoother.hpp) in place of its causal filter; "
                "with --anchors, VQF's offline and causal filters beside it");
    c->add_flag("--qsf", quasi_static,
                "also print the quasi-static field and specific force periods the estimator found, and how still "
                "each vector was in them through the reference attitude");
    c->add_option("--config", config, "TOML with an [estimator] table");
    c->add_option("--set", sets, "an [estimator] key = value, e.g. --set 'gyro_noise_rad_s = 0.03' (repeatable)");
    c->add_option("--rate", rates, "resample to these rates in Hz (repeatable; none: the recording's own)");
    c->add_option("--trace", trace, "write per-sample diagnostics of the first run to this CSV");
    c->add_option("--anchors", anchors_dir,
                  "folder of the comparator drivers (anchor_vqf, anchor_fusion; ../shared/anchors/build.sh "
                  "OUT builds them in OUT/bin): VQF and Fusion run on the same samples and are scored the same way");
  };
  auto* broad = app.add_subcommand("broad", "BROAD trials: BROAD's metric, the aligned metric, worst inclination");
  std::string dir = HEADINGD_STUDY_BROAD_DIR, only;
  broad->add_option("--dir", dir, "folder of NN_name.csv.gz trials")->capture_default_str();
  broad->add_option("--only", only, "trials whose name contains this");
  bool centred = false, reference_delays = false;
  std::vector<double> reference_field;
  broad
      ->add_option("--reference-field", reference_field,
                   "the field where it was recorded, strength (uT) and dip (deg), given to the estimator as the "
                   "daemon gives the WMM's with a GPS fix or a configured place (e.g. BROAD's lab: 42.5 69.5)")
      ->expected(2);
  broad->add_flag("--reference-delays", reference_delays,
                  "also measure how late the magnetometer and the gyro are against the reference attitude, and "
                  "print them beside the magnetometer delay headingd learned");
  broad->add_flag("--centred", centred,
                  "resample accelerometer and magnetometer centred on each sample time (default: the interval "
                  "that ends at it, as an integrate-and-dump sensor)");
  common(broad);
  auto* simulate = app.add_subcommand("sim", "simulator scenarios over seeds: scores and tilt of the motion episode");
  std::string scenario, seeds_text = "1-10", grade = "consumer", cof = HEADINGD_STUDY_DEFAULT_COF;
  double settle_s = 5.0;
  simulate->add_option("--scenario", scenario, "headingd-sim scenario")->required();
  simulate->add_option("--seeds", seeds_text, "e.g. 1-20 or 1,5,9")->capture_default_str();
  simulate->add_option("--grade", grade, "IMU grade: consumer, mems, uncalibrated, phone, ideal")
      ->capture_default_str();
  simulate->add_option("--settle", settle_s, "seconds after the motion from which the recovery is scored")
      ->capture_default_str();
  simulate->add_option("--cof", cof, "WMM coefficients")->capture_default_str();
  std::optional<double> accel_lag_s;
  simulate->add_option("--accel-lag-s", accel_lag_s,
                       "the accelerometer this late against the gyro (s), instead of the grade's (headingd-sim)");
  double initial_error_deg = 0.0;
  simulate->add_option("--initial-error-deg", initial_error_deg,
                       "turn the first sample's accelerometer and magnetometer by this angle (about an axis drawn "
                       "from the seed): the estimator starts that far off");
  bool wmm_reference = false;
  simulate->add_flag("--wmm-reference", wmm_reference,
                     "give the estimator the WMM's field at the simulated place, as the daemon does once GPS has a "
                     "fix (enables the reference strength and dip tests, and MAU)");
  common(simulate);
  app.footer(
      std::string("Exit codes: 0 done, 1 an input cannot be read or a trace cannot be written, 2 bad arguments.") +
      "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;

  try {
    const core::EstimatorParams params = loadParams(config, sets);
    std::vector<study::AnchorFilter> anchors;
    if (!anchors_dir.empty()) {
      anchors = study::findAnchors(anchors_dir, smooth);
      if (anchors.empty()) throw std::runtime_error("no anchor_vqf or anchor_fusion in " + anchors_dir);
      std::printf("anchors: %zu comparator filters from %s, run on the same samples\n", anchors.size(),
                  anchors_dir.c_str());
    }
    if (rates.empty()) rates.push_back(0.0);
    std::vector<std::string> paths;    // BROAD trials, or
    std::vector<std::uint64_t> seeds;  // simulator seeds
    if (*broad) {
      for (const auto& e : std::filesystem::directory_iterator(dir)) {
        const std::string f = e.path().filename().string();
        if (f.ends_with(".csv.gz") && (only.empty() || f.find(only) != std::string::npos)) paths.push_back(e.path());
      }
      std::sort(paths.begin(), paths.end());
    } else {
      seeds = parseSeeds(seeds_text);
      (void)sim::makeScenario(scenario);  // an unknown name fails here, once
    }
    std::optional<core::WorldMagneticModel> wmm;
    if (*simulate) wmm.emplace(core::parseWmmCoefficients(files::readMaybeGzipFile(cof, files::kWmmFileLimit), cof));
    const std::size_t sources = *broad ? paths.size() : seeds.size();
    // Simulations are run at the asked rate directly; recordings are resampled.
    std::vector<Row> rows(sources * rates.size());
    std::mutex trace_mutex;
    runParallel(rows.size(), [&](std::size_t job) {
      const std::size_t source = job / rates.size();
      const double rate = rates[job % rates.size()];
      study::Recording r;
      if (*simulate) {
        sim::SimConfig c;
        c.scenario = scenario;
        c.seed = seeds[source];
        c.imu_grade = sim::parseImuGrade(grade);
        if (rate > 0.0) c.imu_rate_hz = rate;
        c.accel_lag_s = accel_lag_s;
        r = study::fromSimulation(sim::simulate(c, *wmm), scenario + " seed " + std::to_string(c.seed));
        if (initial_error_deg != 0.0) study::startOffBy(r, initial_error_deg / kDegPerRad, c.seed);
        if (!wmm_reference) r.reference_field_uT = 0.0;
      } else {
        r = study::readBroadTrial(paths[source]);
        if (rate > 0.0) {
          r = study::resample(r, rate, centred ? study::VectorWindow::kCentred : study::VectorWindow::kTrailing);
        }
        if (reference_field.size() == 2) {
          r.reference_field_uT = reference_field[0];
          r.reference_inclination_rad = reference_field[1] / kDegPerRad;
        }
      }
      std::vector<double> sigmas, mag_lags;
      std::vector<bool> mag_qsf(r.size(), false), accel_qsf(r.size(), false);
      std::vector<core::Vec3> mag_used, accel_used;  // with --qsf: each vector turned by its lag
      sigmas.reserve(r.size());
      core::EstimatorCounters counters;
      auto est = study::runEstimator(r, params, [&](std::size_t i, const core::Estimator& e) {
        if (i + 1 == r.size()) counters = e.counters();
        sigmas.push_back(e.output().heading_sigma_rad);
        mag_lags.push_back(e.output().mag_lag_s);
        const core::EstimatorOutput& o = e.output();
        mag_qsf[i] = o.mag_quasi_static;
        accel_qsf[i] = o.accel_quasi_static;
        if (quasi_static) {
          const core::Vec3 rate = r.samples[i].gyro_rad_s - o.gyro_bias_rad_s;
          mag_used.push_back(core::turnedBySmallAngle(r.samples[i].mag_uT, -o.mag_lag_s * rate));
          accel_used.push_back(core::turnedBySmallAngle(r.samples[i].accel_m_s2, -o.accel_lag_s * rate));
        }
      });
      if (smooth) {
        const std::vector<core::AttitudeEstimate> smoothed = core::smoothAttitudes(r.samples, params);
        for (std::size_t i = 0; i < r.size(); ++i) {
          constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
          est[i] = smoothed[i].valid ? smoothed[i].q_nb : core::Quat(kNan, kNan, kNan, kNan);
          sigmas[i] = std::sqrt(smoothed[i].covariance_ned(2, 2));
        }
      }
      const double coverage = study::headingCoverage(r, *simulate ? est : study::alignedEstimates(r, est), sigmas, 2.0);
      rows[job] = {
          r.name,
          r.rate_hz,
          study::score(r, est),
          study::scoreEpisode(r, est, settle_s, 1.0 / kDegPerRad),
          coverage,
          {},
          {},
          0.0,
          {},
          {},
          counters,
          r.size() > 1 ? 1e-9 * static_cast<double>(r.samples.back().t_ns - r.samples.front().t_ns) / 60.0 : 0.0};
      for (const auto& a : anchors) rows[job].anchors.push_back(study::score(r, study::runAnchor(a, r)));
      if (quasi_static) {
        rows[job].mag_qsf = study::scoreQuasiStatic(r, mag_qsf, mag_used);
        rows[job].accel_qsf = study::scoreQuasiStatic(r, accel_qsf, accel_used);
      }
      if (reference_delays) {
        rows[job].delays = study::measureReferenceDelays(r);
        rows[job].learned_mag_lag_s = medianOfSecondHalf(std::move(mag_lags));
      }
      if (job == 0 && !trace.empty()) {
        const std::lock_guard lock(trace_mutex);
        writeTrace(trace, r, params);
      }
    });

    std::printf("%-46s %7s | %6s %6s %6s | %6s %6s %6s | %7s | %7s %7s %7s %7s | %6s\n", "run", "Hz", "tot", "head",
                "incl", "a.tot", "a.head", "a.incl", "maxincl", "ep.incl", "ep.max", "after", "settle", "h<2s%");
    for (std::size_t ri = 0; ri < rates.size(); ++ri) {
      double sum_tot = 0, sum_incl = 0, sum_atot = 0, worst_max = 0, worst_after = 0, worst_settle = 0;
      double sum_coverage = 0;
      std::size_t n = 0;
      for (std::size_t job = ri; job < rows.size(); job += rates.size()) {
        const Row& row = rows[job];
        const auto& s = row.score;
        const auto& e = row.episode;
        std::printf("%-46s %7.1f | %6.2f %6.2f %6.2f | %6.2f %6.2f %6.2f | %7.2f | %7.2f %7.2f %7.2f %7.1f | %6.1f\n",
                    row.name.c_str(), row.rate_hz, s.rmse.total_rad * kDegPerRad, s.rmse.heading_rad * kDegPerRad,
                    s.rmse.inclination_rad * kDegPerRad, s.aligned_rmse.total_rad * kDegPerRad,
                    s.aligned_rmse.heading_rad * kDegPerRad, s.aligned_rmse.inclination_rad * kDegPerRad,
                    s.max_inclination_rad * kDegPerRad, e.inclination_rmse_rad * kDegPerRad,
                    e.max_inclination_rad * kDegPerRad, e.max_inclination_after_rad * kDegPerRad, e.settle_time_s,
                    100.0 * row.heading_2sigma);
        sum_coverage += row.heading_2sigma;
        sum_tot += s.rmse.total_rad * kDegPerRad;
        sum_incl += s.rmse.inclination_rad * kDegPerRad;
        sum_atot += s.aligned_rmse.total_rad * kDegPerRad;
        worst_max = std::max(worst_max, e.max_inclination_rad * kDegPerRad);
        worst_after = std::max(worst_after, e.max_inclination_after_rad * kDegPerRad);
        worst_settle = std::max(worst_settle, e.settle_time_s);
        ++n;
      }
      std::printf("MEAN %-41s %7.1f | %6.2f %6s %6.2f | %6.2f %6s %6s | %7s | %7s %7.2f %7.2f %7.1f | %6.1f  (worst)\n",
                  "", rates[ri], sum_tot / n, "", sum_incl / n, sum_atot / n, "", "", "", "", worst_max, worst_after,
                  worst_settle, 100.0 * sum_coverage / n);
    }
    if (!anchors.empty()) printSideBySide(rows, rates, anchors);
    if (reference_delays) printReferenceDelays(rows);
    if (quasi_static) printQuasiStatic(rows);
    if (params.qsf_mag_update_noise_uT > 0.0 || params.mau_noise_uT > 0.0 || params.maru_baseline_s > 0.0 ||
        params.agu_baseline_s > 0.0) {
      printFieldUpdates(rows);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-study: %s\n", e.what());
    return 1;
  }
  return 0;
}
