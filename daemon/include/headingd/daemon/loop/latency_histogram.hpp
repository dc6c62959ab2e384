#pragma once
// Distribution of a duration (ns) with a fixed array of log-linear buckets: recording never
// allocates (the estimator thread records several values per tick), and percentiles come
// out within about 3 % (16 buckets per power of two).
#include <array>
#include <cstdint>

namespace headingd::daemon {

class LatencyHistogram {
 public:
  void record(std::int64_t ns);  // negative values count as 0
  void clear();

  std::uint64_t count() const { return count_; }
  std::int64_t max() const { return max_; }
  double mean() const { return count_ ? static_cast<double>(sum_) / static_cast<double>(count_) : 0.0; }
  // Value below which `fraction` (0..1) of the recorded values lie: the middle of the bucket
  // holding that rank. 0 when nothing was recorded.
  double percentile(double fraction) const;

 private:
  static constexpr int kSubBits = 4;
  static constexpr int kSub = 1 << kSubBits;
  static constexpr int kBuckets = kSub + (63 - kSubBits) * kSub;
  static int bucketOf(std::uint64_t v);
  static double bucketMiddle(int index);

  std::array<std::uint64_t, kBuckets> buckets_{};
  std::uint64_t count_ = 0;
  std::int64_t max_ = 0;
  std::int64_t sum_ = 0;
};

}  // namespace headingd::daemon
