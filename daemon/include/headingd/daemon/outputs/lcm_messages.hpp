#pragma once
// Filling the LCM messages (daemon/lcm/*.lcm) from the estimator's values. Pure functions on
// reused message objects: after the first call their strings have capacity, so later calls
// do not allocate.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/attitude_t.hpp"
#include "headingd/core/gps_observation.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/imu_sample.hpp"
#include "headingd/core/sample_gate.hpp"
#include "headingd/gps_t.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/imu_t.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon {

// Freshness of a published estimate (heading_t.VALIDITY_*).
enum class Validity : std::int8_t { kNone = 0, kFresh = 1, kStale = 2 };

struct PublishTimes {
  std::int64_t utime_us = 0;         // CLOCK_REALTIME at publish
  std::int64_t sample_utime_us = 0;  // newest sample, sensor time axis
  std::int64_t sample_age_us = 0;
};

void fillHeading(headingd::heading_t& m, const core::HeadingOutput& h, Validity validity, const PublishTimes& t);
void fillAttitude(headingd::attitude_t& m, const core::HeadingOutput& h, const core::Mat4& q_covariance,
                  Validity validity, const PublishTimes& t);
void fillImu(headingd::imu_t& m, const core::ImuSample& s, core::SampleVerdict verdict, const std::string& source,
             std::int64_t utime_us);
void fillGps(headingd::gps_t& m, const core::GpsObservation& g, const std::string& source, std::int64_t utime_us);
// STATUS counter `i`, appended the first time; its name string is reused while it is unchanged
// (every STATUS but the first allocates nothing).
void setStatusCounter(std::vector<headingd::counter_t>& counters, std::size_t i, std::string_view name,
                      std::uint64_t value);
// Counters after those `m` holds: `for_each(add)` calls add(name, value) for each, in order.
template <class ForEach>
void appendStatusCounters(headingd::status_t& m, ForEach&& for_each) {
  auto i = static_cast<std::size_t>(m.num_counters);
  for_each([&](std::string_view name, std::uint64_t value) { setStatusCounter(m.counters, i++, name, value); });
  m.num_counters = static_cast<std::int32_t>(i);
}

}  // namespace headingd::daemon
