#include "headingd/daemon/loop/latency_histogram.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace headingd::daemon {

int LatencyHistogram::bucketOf(std::uint64_t v) {
  if (v < static_cast<std::uint64_t>(kSub)) return static_cast<int>(v);
  const int exponent = 63 - std::countl_zero(v);  // >= kSubBits
  const int shift = exponent - kSubBits;
  const int mantissa = static_cast<int>((v >> shift) & (kSub - 1));
  return kSub + shift * kSub + mantissa;
}

double LatencyHistogram::bucketMiddle(int index) {
  if (index < kSub) return index;
  const int shift = (index - kSub) / kSub;
  const int mantissa = (index - kSub) % kSub;
  const double width = std::ldexp(1.0, shift);
  return (kSub + mantissa) * width + 0.5 * (width - 1.0);
}

void LatencyHistogram::record(std::int64_t ns) {
  const std::int64_t v = std::max<std::int64_t>(ns, 0);
  ++buckets_[static_cast<std::size_t>(bucketOf(static_cast<std::uint64_t>(v)))];
  ++count_;
  max_ = std::max(max_, v);
  sum_ += v;
}

void LatencyHistogram::clear() {
  buckets_.fill(0);
  count_ = 0;
  max_ = 0;
  sum_ = 0;
}

double LatencyHistogram::percentile(double fraction) const {
  if (count_ == 0) return 0.0;
  const double clamped = std::clamp(fraction, 0.0, 1.0);
  // Rank of the value asked for, 1-based: the p50 of 1..100 is the 50th value.
  const auto rank =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(clamped * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (int i = 0; i < kBuckets; ++i) {
    seen += buckets_[static_cast<std::size_t>(i)];
    if (seen >= rank) return std::min(bucketMiddle(i), static_cast<double>(max_));
  }
  return static_cast<double>(max_);
}

}  // namespace headingd::daemon
