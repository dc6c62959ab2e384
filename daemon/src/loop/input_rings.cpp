#include "headingd/daemon/loop/input_rings.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <tuple>

#include "headingd/daemon/loop/status_builder.hpp"

namespace headingd::daemon {
namespace {

template <class Entry>
std::size_t totalCapacity(const std::vector<SampleRing<Entry>*>& rings) {
  std::size_t capacity = 0;
  for (const auto* r : rings) capacity += r->capacity();
  return capacity;
}

// Sensor time, ties by arrival, then by source.
bool imuByTime(const ImuRingEntry& a, const ImuRingEntry& b) {
  return std::tie(a.sample.t_ns, a.arrival_mono_ns, a.source_index) <
         std::tie(b.sample.t_ns, b.arrival_mono_ns, b.source_index);
}

}  // namespace

InputRings::InputRings(std::vector<SampleRing<ImuRingEntry>*> imu, std::vector<SampleRing<GpsRingEntry>*> gps,
                       RepeatLimiter drop_log)
    : imu_(std::move(imu)), gps_(std::move(gps)), drops_seen_(imu_.size() + gps_.size(), 0), drop_log_(drop_log) {}

std::size_t InputRings::imuCapacity() const { return totalCapacity(imu_); }
std::size_t InputRings::gpsCapacity() const { return totalCapacity(gps_); }

void InputRings::putInTimeOrder(std::vector<ImuRingEntry>& batch) {
  // One source's samples stay in the order it pushed them (the sample gate judges a time that
  // goes back), so the order never depends on where a tick cut the stream: a recording of one
  // IMU replays in the same order whatever the ticks. Several sources are merged by sensor
  // time (std::sort: no temporary buffer, unlike stable_sort).
  if (!std::is_sorted(batch.begin(), batch.end(), imuByTime)) std::sort(batch.begin(), batch.end(), imuByTime);
}

void InputRings::logDrops(std::int64_t now_ns) {
  std::size_t i = 0;
  const auto check = [&](const auto& ring) {
    const RingStats s = ring.stats();
    if (s.dropped != drops_seen_[i]) {
      std::uint64_t suppressed = 0;
      if (drop_log_.allow(now_ns, &suppressed)) {
        spdlog::warn("ring {} full: {} sample(s) dropped ({} in total; {} such messages suppressed)", ring.name(),
                     s.dropped - drops_seen_[i], s.dropped, suppressed);
      }
      drops_seen_[i] = s.dropped;
    }
    ++i;
  };
  for (const auto* ring : imu_) check(*ring);
  for (const auto* ring : gps_) check(*ring);
}

void InputRings::fillStatus(status_t& m) { fillRingStatus(m, imu_, gps_); }

}  // namespace headingd::daemon
