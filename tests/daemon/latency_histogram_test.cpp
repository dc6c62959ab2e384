#include <gtest/gtest.h>

#include "headingd/daemon/loop/latency_histogram.hpp"

namespace headingd::daemon {
namespace {

TEST(LatencyHistogram, PercentilesWithinBucketResolution) {
  LatencyHistogram h;
  for (int i = 1; i <= 1000; ++i) h.record(i * 1000);  // 1 µs .. 1 ms
  EXPECT_EQ(h.count(), 1000u);
  EXPECT_EQ(h.max(), 1'000'000);
  EXPECT_NEAR(h.percentile(0.5), 500'000, 500'000 * 0.035);
  EXPECT_NEAR(h.percentile(0.99), 990'000, 990'000 * 0.035);
  EXPECT_LE(h.percentile(1.0), 1'000'000);
  EXPECT_NEAR(h.mean(), 500'500, 1);
}

TEST(LatencyHistogram, SmallNegativeAndEmpty) {
  LatencyHistogram h;
  EXPECT_EQ(h.percentile(0.5), 0.0);
  h.record(-5);  // a clock read before the deadline counts as 0
  h.record(3);
  EXPECT_EQ(h.percentile(0.5), 0.0);
  EXPECT_EQ(h.percentile(1.0), 3.0);
  h.clear();
  EXPECT_EQ(h.count(), 0u);
}

}  // namespace
}  // namespace headingd::daemon
