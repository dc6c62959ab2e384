// Accuracy on real data: every BROAD trial of the set (../shared/data/broad's 14 when it is
// beside the checkout, else the repository's subset tests/data/broad) replayed through the
// estimator with default parameters and scored with BROAD's metric (headingd-eval's).
// Thresholds are our measured RMSE plus a margin of about 15 %, so a change that makes any
// trial clearly worse fails; the averages, undisturbed and disturbed, must stay at or below
// VQF's over the same trials (VQF 9D run on the same files and scored with the same metric;
// over all 14 that is 1.93 and 3.49 deg).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>

#include "headingd/core/angles.hpp"
#include "headingd/core/estimator.hpp"
#include "headingd/core/orientation_error.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "test_data.hpp"

namespace {

using namespace headingd;
using headingd::core::kDegPerRad;

struct Limits {
  double total_deg;
  double inclination_deg;
};

// Measured 2026-12-01 with the default EstimatorParams (still-block and in-motion
// gyro bias, R_k from the gravity measurement's residual, no back-tracking, interval-mean
// sample timing): total / inclination RMSE.
const std::map<std::string, Limits> kLimits = {
    {"01_undisturbed_slow_rotation_A", {1.98, 0.59}},              // 1.72 / 0.51
    {"03_undisturbed_slow_rotation_C", {2.11, 0.46}},              // 1.83 / 0.40
    {"05_undisturbed_slow_rotation_with_breaks_B", {0.99, 0.40}},  // 0.86 / 0.34
    {"07_undisturbed_fast_rotation_B", {1.89, 1.24}},              // 1.64 / 1.07
    {"09_undisturbed_fast_rotation_with_breaks_B", {1.40, 1.07}},  // 1.21 / 0.93
    {"11_undisturbed_slow_translation_B", {1.13, 0.61}},           // 0.98 / 0.53
    {"15_undisturbed_fast_translation_A", {2.49, 0.58}},           // 2.16 / 0.50
    {"21_undisturbed_fast_combined", {3.87, 1.58}},                // 3.36 / 1.37
    {"24_disturbed_tapping_A", {1.36, 0.69}},                      // 1.18 / 0.60
    {"26_disturbed_phone_vibration_A", {1.95, 0.63}},              // 1.69 / 0.54
    // 28 and 30 re-measured 2026-12-05 with the learned magnetometer delay (8.5 ms on these
    // trials instead of half of 3.5 ms): plain total 1.83 -> 2.18 and 1.52 -> 1.76 deg, fitted
    // 1.46 -> 1.25 and 1.38 -> 1.21 deg; the 14 trials' mean 1.85 -> 1.82 (fitted 1.36 -> 1.27).
    {"28_disturbed_stationary_magnet_A", {2.51, 1.28}},  // 2.18 / 1.11
    {"30_disturbed_stationary_magnet_C", {2.02, 1.14}},  // 1.76 / 1.00
    {"32_disturbed_attached_magnet_1cm", {1.95, 0.88}},  // 1.69 / 0.76
    {"34_disturbed_attached_magnet_3cm", {4.95, 0.89}},  // 4.30 / 0.77
};

// VQF 9D on each trial (run on the same files, scored with BROAD's metric), total RMSE: the
// averages are compared over the trials of the set used.
const std::map<std::string, double> kVqfTotalDeg = {
    {"01_undisturbed_slow_rotation_A", 1.99},
    {"03_undisturbed_slow_rotation_C", 1.93},
    {"05_undisturbed_slow_rotation_with_breaks_B", 0.99},
    {"07_undisturbed_fast_rotation_B", 1.75},
    {"09_undisturbed_fast_rotation_with_breaks_B", 1.49},
    {"11_undisturbed_slow_translation_B", 0.90},
    {"15_undisturbed_fast_translation_A", 2.31},
    {"21_undisturbed_fast_combined", 4.08},
    {"24_disturbed_tapping_A", 1.55},
    {"26_disturbed_phone_vibration_A", 1.75},
    {"28_disturbed_stationary_magnet_A", 4.04},
    {"30_disturbed_stationary_magnet_C", 2.57},
    {"32_disturbed_attached_magnet_1cm", 7.67},
    {"34_disturbed_attached_magnet_3cm", 3.35},
};

// Sums of our and VQF's total RMSE over a group of trials.
struct Average {
  double ours = 0.0, vqf = 0.0;
  int n = 0;
};

core::OrientationError replayAndScore(const std::string& path) {
  const auto samples = files::readImuCsv(path);
  const auto ref = files::readNumericCsv(path, {"ref_w", "ref_x", "ref_y", "ref_z", "moving"});
  core::Estimator estimator;
  core::RmseAccumulator rmse;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    estimator.process(samples[i]);
    const core::Quat q_ref(ref.column("ref_w")[i], ref.column("ref_x")[i], ref.column("ref_y")[i],
                           ref.column("ref_z")[i]);
    if (ref.column("moving")[i] != 1.0 || !q_ref.coeffs().allFinite()) continue;
    const auto& out = estimator.output();
    EXPECT_TRUE(out.valid && out.q_nb.coeffs().allFinite()) << path << " row " << i;
    rmse.add(core::orientationError(out.q_nb, q_ref));
  }
  EXPECT_GT(rmse.count(), 10000u) << path;
  return rmse.rmse();
}

TEST(BroadAccuracy, EveryTrialWithinItsMeasuredLimitAndAveragesBeatVqf) {
  const auto trials = test_data::all(test_data::kBroad);
  // Both groups must be there, or an average would go unchecked.
  ASSERT_GE(trials.size(), 2u) << "no BROAD trials in " << test_data::kBroad.dir;
  Average undisturbed, disturbed;
  for (const auto& path : trials) {
    const std::string file = path.filename().string();
    const std::string trial = file.substr(0, file.size() - std::string(".csv.gz").size());
    const auto e = replayAndScore(path.string());
    const double total = e.total_rad * kDegPerRad, inclination = e.inclination_rad * kDegPerRad;
    std::printf("%-45s total %5.2f  heading %5.2f  inclination %5.2f deg\n", trial.c_str(), total,
                e.heading_rad * kDegPerRad, inclination);
    const auto limit = kLimits.find(trial);
    const auto vqf = kVqfTotalDeg.find(trial);
    if (limit == kLimits.end() || vqf == kVqfTotalDeg.end()) {
      // A trial we have not measured yet: hold it to a generous bound rather than ignore it.
      EXPECT_LT(total, 10.0) << trial;
      continue;
    }
    EXPECT_LE(total, limit->second.total_deg) << trial;
    EXPECT_LE(inclination, limit->second.inclination_deg) << trial;
    Average& group = trial.find("undisturbed") != std::string::npos ? undisturbed : disturbed;
    group.ours += total;
    group.vqf += vqf->second;
    ++group.n;
  }
  for (const auto& [name, group] : {std::pair{"undisturbed", undisturbed}, std::pair{"disturbed", disturbed}}) {
    ASSERT_GT(group.n, 0) << "no " << name << " trial among the measured ones in " << test_data::kBroad.dir;
    std::printf("average %s total %.2f deg over %d trials (VQF %.2f)\n", name, group.ours / group.n, group.n,
                group.vqf / group.n);
    EXPECT_LE(group.ours / group.n, group.vqf / group.n) << name;
  }
}

}  // namespace
