#include "headingd/study/quasi_static_score.hpp"

#include <algorithm>
#include <limits>

namespace headingd::study {
namespace {

// The vector through the reference attitude is compared in means over blocks this long, so that
// the sensor's white noise hardly shows.
constexpr double kBlockS = 0.25;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto k = static_cast<std::ptrdiff_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

}  // namespace

QuasiStaticScore scoreQuasiStatic(const Recording& r, const std::vector<bool>& flags,
                                  const std::vector<core::Vec3>& vectors_sensor) {
  QuasiStaticScore score;
  std::vector<double> drifts;
  std::size_t with_reference = 0, flagged = 0;
  double period_seconds = 0.0;
  const auto seconds = [&](std::size_t i) { return 1e-9 * static_cast<double>(r.samples[i].t_ns); };
  const auto vectorAt = [&](std::size_t i) { return core::Vec3(r.truth_nb[i] * vectors_sensor[i]); };
  std::size_t i = 0;
  while (i < r.size()) {
    if (hasTruth(r.truth_nb[i])) ++with_reference;
    if (!flags[i]) {
      ++i;
      continue;
    }
    // A period: the flagged samples from i on.
    std::size_t end = i;
    while (end < r.size() && flags[end]) ++end;
    // Means over consecutive blocks of the period; the first is the reference. The last, shorter
    // block is left out (its mean keeps more of the noise).
    std::vector<core::Vec3> blocks;
    core::Vec3 sum = core::Vec3::Zero();
    std::size_t n = 0, with_truth = 0;
    double block_start_s = seconds(i);
    for (std::size_t k = i; k < end; ++k) {
      if (seconds(k) - block_start_s >= kBlockS) {
        if (n > 0) blocks.push_back(sum / static_cast<double>(n));
        sum.setZero();
        n = 0;
        block_start_s = seconds(k);
      }
      if (!hasTruth(r.truth_nb[k])) continue;
      sum += vectorAt(k);
      ++n;
      ++with_truth;
    }
    if (with_truth > 0) {
      ++score.periods;
      flagged += with_truth;
      period_seconds += seconds(end - 1) - seconds(i);
      for (std::size_t b = 1; b < blocks.size(); ++b) drifts.push_back((blocks[b] - blocks.front()).norm());
    }
    // Samples of the period after the first are counted here, the first above.
    for (std::size_t k = i + 1; k < end; ++k) with_reference += hasTruth(r.truth_nb[k]) ? 1 : 0;
    i = end;
  }
  score.share = with_reference > 0 ? static_cast<double>(flagged) / static_cast<double>(with_reference) : 0.0;
  score.mean_period_s = score.periods > 0 ? period_seconds / static_cast<double>(score.periods) : 0.0;
  score.median_drift = percentile(drifts, 0.5);
  score.p95_drift = percentile(drifts, 0.95);
  return score;
}

}  // namespace headingd::study
