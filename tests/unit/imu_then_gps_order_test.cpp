// The order IMU samples and GPS epochs reach the estimator in: each IMU sample, then the
// GPS epochs at or before its time; and the list of the estimator's counters.
#include "headingd/core/imu_then_gps_order.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "headingd/core/estimator.hpp"

namespace headingd::core {
namespace {

GpsObservation epochAt(std::int64_t t_ns) {
  GpsObservation g;
  g.t_ns = t_ns;
  return g;
}

// Feeds IMU sample times and returns the sequence: "i<t>" for a sample, "g<t>" for an epoch.
std::vector<std::string> feed(ImuThenGpsOrder<GpsObservation>& order, const std::vector<std::int64_t>& imu_t) {
  std::vector<std::string> seen;
  for (const std::int64_t t : imu_t) {
    seen.push_back("i" + std::to_string(t));
    order.afterImu(t, [&](const GpsObservation& g) { seen.push_back("g" + std::to_string(g.t_ns)); });
  }
  return seen;
}

TEST(ImuThenGpsOrder, EpochGoesAfterTheFirstSampleAtOrAfterItsTime) {
  ImuThenGpsOrder<GpsObservation> order;
  for (const std::int64_t t : {5, 10, 11, 30}) order.pushGps(epochAt(t));
  EXPECT_EQ(feed(order, {0, 10, 20}), (std::vector<std::string>{"i0", "i10", "g5", "g10", "i20", "g11"}));
  EXPECT_EQ(order.held(), 1u);  // the epoch at 30 waits for a sample at 30 or later
  std::vector<std::int64_t> rest;
  order.releaseAll([&](const GpsObservation& g) { rest.push_back(g.t_ns); });
  EXPECT_EQ(rest, (std::vector<std::int64_t>{30}));
  EXPECT_EQ(order.held(), 0u);
}

TEST(ImuThenGpsOrder, EpochsBeforeTheFirstSampleWaitForIt) {
  ImuThenGpsOrder<GpsObservation> order;
  order.pushGps(epochAt(1));
  order.pushGps(epochAt(2));
  EXPECT_EQ(feed(order, {3}), (std::vector<std::string>{"i3", "g1", "g2"}));
}

TEST(ImuThenGpsOrder, HeldEpochsKeepTheirOrderUntilSorted) {
  ImuThenGpsOrder<GpsObservation> order;
  order.pushGps(epochAt(20));
  order.pushGps(epochAt(10));
  // Unsorted, the later epoch at the front holds the earlier one back.
  EXPECT_EQ(feed(order, {15}), (std::vector<std::string>{"i15"}));
  order.sortHeld([](const GpsObservation& a, const GpsObservation& b) { return a.t_ns < b.t_ns; });
  EXPECT_EQ(feed(order, {16}), (std::vector<std::string>{"i16", "g10"}));
}

TEST(ImuThenGpsOrder, ReleaseOldestMakesRoomWithoutGrowing) {
  ImuThenGpsOrder<GpsObservation> order;
  order.reserve(2);
  const std::size_t capacity = order.capacity();
  std::vector<std::int64_t> forced;
  for (std::int64_t t = 1; t <= 5; ++t) {
    if (order.held() == order.capacity()) {
      order.releaseOldest([&](const GpsObservation& g) { forced.push_back(g.t_ns); });
    }
    order.pushGps(epochAt(t));
  }
  EXPECT_EQ(order.capacity(), capacity);
  EXPECT_EQ(forced.size(), 5u - capacity);
  EXPECT_EQ(forced.front(), 1);
  EXPECT_EQ(order.held(), capacity);
}

TEST(ImuThenGpsOrder, EpochsHandedOutAreNotHandedOutAgain) {
  ImuThenGpsOrder<GpsObservation> order;
  order.pushGps(epochAt(1));
  EXPECT_EQ(feed(order, {1}), (std::vector<std::string>{"i1", "g1"}));
  order.pushGps(epochAt(2));  // drops the handed-out epoch
  EXPECT_EQ(feed(order, {2, 3}), (std::vector<std::string>{"i2", "g2", "i3"}));
}

// A counter added to EstimatorCounters goes into forEachCounter too (and into this test).
static_assert(sizeof(EstimatorCounters) == 28 * sizeof(std::uint64_t));

TEST(EstimatorCounters, ForEachCounterListsEveryCounterOnce) {
  EstimatorCounters c;
  std::uint64_t v = 1;
  // Distinct values, so that each field shows up under exactly one name.
  for (std::uint64_t* f : {&c.samples.accepted,
                           &c.samples.gaps,
                           &c.samples.clock_jumps,
                           &c.samples.duplicate_time,
                           &c.samples.backwards_time,
                           &c.samples.non_finite,
                           &c.samples.non_finite_mag,
                           &c.samples.out_of_range,
                           &c.samples.out_of_range_mag,
                           &c.bias_still_blocks,
                           &c.mag_no_heading,
                           &c.mag_disturbed,
                           &c.mag_heading_restores,
                           &c.state_recoveries,
                           &c.accel_clipped,
                           &c.qsf_mag_periods,
                           &c.qsf_mag_ms,
                           &c.qsf_accel_periods,
                           &c.qsf_accel_ms,
                           &c.qsf_mag_updates,
                           &c.qsf_mag_updates_rejected,
                           &c.mau_updates,
                           &c.mau_updates_rejected,
                           &c.mau_updates_unverified,
                           &c.maru_updates,
                           &c.maru_updates_rejected,
                           &c.agu_updates,
                           &c.agu_updates_rejected}) {
    *f = v++;
  }
  std::vector<std::pair<std::string, std::uint64_t>> list;
  forEachCounter(c, [&](const char* name, std::uint64_t value) { list.emplace_back(name, value); });
  ASSERT_EQ(list.size(), 28u);
  for (std::size_t i = 0; i < list.size(); ++i) EXPECT_EQ(list[i].second, i + 1) << list[i].first;
  EXPECT_EQ(list.front().first, "accepted");
  EXPECT_EQ(list[8].first, "out_of_range_mag");
  EXPECT_EQ(list[14].first, "accel_clipped");
  EXPECT_EQ(list.back().first, "agu_updates_rejected");
}

}  // namespace
}  // namespace headingd::core
