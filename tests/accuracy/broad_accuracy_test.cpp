// Accuracy on real data: every BROAD trial in ../shared/data/broad replayed through the
// estimator with default parameters and scored with BROAD's metric (headingd-eval's).
// Thresholds are our measured RMSE plus a margin of about 15 %, so a change that makes any
// trial clearly worse fails; the averages must stay at or below VQF's (ANCHORS.md).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>

#include "headingd/core/estimator.hpp"
#include "headingd/core/orientation_error.hpp"
#include "headingd/replay/imu_csv.hpp"
#include "headingd/replay/numeric_csv.hpp"

namespace {

using namespace headingd;
constexpr double kDeg = 180.0 / std::numbers::pi;

struct Limits {
  double total_deg;
  double inclination_deg;
};

// Measured 2026-12-01 with the default EstimatorParams (issue 17: still-block and in-motion
// gyro bias, R_k from the gravity measurement's residual, no back-tracking, interval-mean
// sample timing): total / inclination RMSE.
const std::map<std::string, Limits> kLimits = {
    {"01_undisturbed_slow_rotation_A", {1.98, 0.59}},   // 1.72 / 0.51
    {"03_undisturbed_slow_rotation_C", {2.11, 0.46}},   // 1.83 / 0.40
    {"05_undisturbed_slow_rotation_with_breaks_B", {0.99, 0.40}}, // 0.86 / 0.34
    {"07_undisturbed_fast_rotation_B", {1.89, 1.24}},   // 1.64 / 1.07
    {"09_undisturbed_fast_rotation_with_breaks_B", {1.40, 1.07}}, // 1.21 / 0.93
    {"11_undisturbed_slow_translation_B", {1.13, 0.61}}, // 0.98 / 0.53
    {"15_undisturbed_fast_translation_A", {2.49, 0.58}}, // 2.16 / 0.50
    {"21_undisturbed_fast_combined", {3.87, 1.58}},     // 3.36 / 1.37
    {"24_disturbed_tapping_A", {1.36, 0.69}},           // 1.18 / 0.60
    {"26_disturbed_phone_vibration_A", {1.95, 0.63}},   // 1.69 / 0.54
    {"28_disturbed_stationary_magnet_A", {2.14, 1.28}}, // 1.86 / 1.11
    {"30_disturbed_stationary_magnet_C", {1.75, 1.14}}, // 1.52 / 0.99
    {"32_disturbed_attached_magnet_1cm", {1.95, 0.88}}, // 1.69 / 0.76
    {"34_disturbed_attached_magnet_3cm", {4.95, 0.89}}, // 4.30 / 0.77
};

// VQF 9D on the same trials (../shared/data/broad/ANCHORS.md), total RMSE.
constexpr double kVqfUndisturbedTotalDeg = 1.93;
constexpr double kVqfDisturbedTotalDeg = 3.49;

core::OrientationError replayAndScore(const std::string& path) {
  const auto samples = replay::readImuCsv(path);
  const auto ref = replay::readNumericCsv(path, {"ref_w", "ref_x", "ref_y", "ref_z", "moving"});
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

std::filesystem::path broadDir() { return std::filesystem::path(HEADINGD_SHARED_DIR) / "data" / "broad"; }

TEST(BroadAccuracy, EveryTrialWithinItsMeasuredLimitAndAveragesBeatVqf) {
  ASSERT_TRUE(std::filesystem::is_directory(broadDir()))
      << broadDir() << " is missing: the accuracy test needs ../shared beside the checkout "
      << "(or -DHEADINGD_SHARED_DIR=...)";
  double sum_undisturbed = 0.0, sum_disturbed = 0.0;
  int n_undisturbed = 0, n_disturbed = 0, seen = 0;
  for (const auto& entry : std::filesystem::directory_iterator(broadDir())) {
    const std::string file = entry.path().filename().string();
    if (!file.ends_with(".csv.gz")) continue;
    const std::string trial = file.substr(0, file.size() - std::string(".csv.gz").size());
    const auto e = replayAndScore(entry.path().string());
    const double total = e.total_rad * kDeg, inclination = e.inclination_rad * kDeg;
    std::printf("%-45s total %5.2f  heading %5.2f  inclination %5.2f deg\n", trial.c_str(), total,
                e.heading_rad * kDeg, inclination);
    ++seen;
    if (trial.find("undisturbed") != std::string::npos) {
      sum_undisturbed += total;
      ++n_undisturbed;
    } else {
      sum_disturbed += total;
      ++n_disturbed;
    }
    const auto limit = kLimits.find(trial);
    if (limit == kLimits.end()) {
      // A trial we have not measured yet: hold it to a generous bound rather than ignore it.
      EXPECT_LT(total, 10.0) << trial;
      continue;
    }
    EXPECT_LE(total, limit->second.total_deg) << trial;
    EXPECT_LE(inclination, limit->second.inclination_deg) << trial;
  }
  ASSERT_GT(seen, 0) << "no *.csv.gz trials in " << broadDir();
  if (n_undisturbed > 0) {
    const double average = sum_undisturbed / n_undisturbed;
    std::printf("average undisturbed total %.2f deg (VQF %.2f)\n", average, kVqfUndisturbedTotalDeg);
    EXPECT_LE(average, kVqfUndisturbedTotalDeg);
  }
  if (n_disturbed > 0) {
    const double average = sum_disturbed / n_disturbed;
    std::printf("average disturbed total %.2f deg (VQF %.2f)\n", average, kVqfDisturbedTotalDeg);
    EXPECT_LE(average, kVqfDisturbedTotalDeg);
  }
}

}  // namespace
