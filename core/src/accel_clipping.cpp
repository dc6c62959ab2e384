#include "headingd/core/accel_clipping.hpp"

#include <cmath>
#include <limits>

namespace headingd::core {

namespace {

constexpr double kLowestLimit_m_s2 = 1.5 * 9.80665;  // the first bin's lower edge
constexpr double kBinRatio = 1.02;                   // each bin 2 % wider than the last
constexpr double kForgetTimeConstantS = 60.0;
constexpr double kLearnEveryS = 1.0;
constexpr double kTopBinMinSamples = 3.0;   // the candidate limit: the highest bin with these
constexpr int kPileBins = 3;                // the pile: the bins up to the candidate (6 %) ...
constexpr double kPileMinSamples = 20.0;    // ... holding at least these ...
constexpr double kPileOverShoulder = 3.0;   // ... more than this many times the bins below ...
constexpr double kPileMinFlatShare = 0.15;  // ... and this share of them flat:
constexpr double kFlatTolerance = 0.005;    // within this fraction of one value ...
constexpr double kFlatMinS = 0.02;          // ... for this long

double binLowerEdge(int bin) { return kLowestLimit_m_s2 * std::pow(kBinRatio, bin); }

}  // namespace

AccelClipDetector::AccelClipDetector() { clip_from_.fill(std::numeric_limits<double>::infinity()); }

Vec3 AccelClipDetector::update(const Vec3& accel_m_s2, double dt_s) {
  Vec3 clipped = Vec3::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    const double reading = accel_m_s2(axis);
    const double magnitude = std::abs(reading);
    // Below the lowest limit (the common case) there is nothing to count, and a flat run
    // that counts starts at or above it. Non-finite readings are the sample gate's to count.
    if (!(magnitude >= kLowestLimit_m_s2) || !std::isfinite(magnitude)) {
      run_s_(axis) = -1.0;  // no run
      continue;
    }
    if (run_s_(axis) >= 0.0 && std::abs(reading - run_value_(axis)) <= kFlatTolerance * magnitude) {
      run_s_(axis) += dt_s;
    } else {
      run_value_(axis) = reading;
      run_s_(axis) = 0.0;
    }
    const bool negative = reading < 0.0;
    const int bin = static_cast<int>(std::log(magnitude / kLowestLimit_m_s2) / std::log(kBinRatio));
    if (bin < kBins) {
      counts_[slot(axis, negative)][bin] += 1.0;
      if (run_s_(axis) >= kFlatMinS) flat_counts_[slot(axis, negative)][bin] += 1.0;
    }
    if (magnitude >= clip_from_[slot(axis, negative)]) clipped(axis) = negative ? -1.0 : 1.0;
  }
  since_learn_s_ += dt_s;
  if (since_learn_s_ >= kLearnEveryS) learn();
  return clipped;
}

void AccelClipDetector::learn() {
  const double keep = std::exp(-since_learn_s_ / kForgetTimeConstantS);
  since_learn_s_ = 0.0;
  for (int s = 0; s < 6; ++s) {
    std::array<double, kBins>& counts = counts_[s];
    for (double& c : counts) c *= keep;
    for (double& c : flat_counts_[s]) c *= keep;
    clip_from_[s] = std::numeric_limits<double>::infinity();
    int top = kBins - 1;
    while (top >= 0 && counts[top] < kTopBinMinSamples) --top;
    // The pile and the bins below it must lie above the lowest limit, or the comparison
    // would be with bins that were never counted.
    const int pile_from = top - kPileBins + 1;
    const int shoulder_from = pile_from - kPileBins;
    if (shoulder_from < 0) continue;
    double pile = 0.0, flat = 0.0, shoulder = 0.0;
    for (int b = pile_from; b <= top; ++b) {
      pile += counts[b];
      flat += flat_counts_[s][b];
    }
    for (int b = shoulder_from; b < pile_from; ++b) shoulder += counts[b];
    if (pile >= kPileMinSamples && pile > kPileOverShoulder * shoulder && flat >= kPileMinFlatShare * pile) {
      clip_from_[s] = binLowerEdge(pile_from);
    }
  }
}

}  // namespace headingd::core
