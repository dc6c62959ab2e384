#pragma once
// The rings between the sources and the estimator thread, from the consumer's side: every
// source's IMU and GPS rings (the estimator thread is their one consumer), drained once a tick,
// the IMU samples in time order; their drops logged here (the producers must not log) and their
// state put on STATUS.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/system/repeat_limiter.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon {

class InputRings {
 public:
  // The rings are borrowed (owned by the daemon), the IMU rings first on STATUS.
  InputRings(std::vector<SampleRing<ImuRingEntry>*> imu, std::vector<SampleRing<GpsRingEntry>*> gps,
             RepeatLimiter drop_log);

  std::size_t imuCapacity() const;
  std::size_t gpsCapacity() const;
  std::size_t count() const { return imu_.size() + gps_.size(); }

  // Every IMU sample waiting into `batch` (cleared first), in time order; every GPS epoch to
  // `gps(entry)`, each ring's in its order.
  template <class Gps>
  void drain(std::vector<ImuRingEntry>& batch, Gps&& gps) {
    batch.clear();
    for (auto* ring : imu_) ring->drain([&](const ImuRingEntry& e) { batch.push_back(e); });
    for (auto* ring : gps_) ring->drain(gps);
    if (imu_.size() > 1) putInTimeOrder(batch);
  }

  // Logs (rate-limited) the samples the rings dropped since the last call.
  void logDrops(std::int64_t now_ns);
  // Capacity, high-water marks, pushes and drops of each ring (status_builder.hpp).
  void fillStatus(status_t& m);

 private:
  static void putInTimeOrder(std::vector<ImuRingEntry>& batch);

  std::vector<SampleRing<ImuRingEntry>*> imu_;
  std::vector<SampleRing<GpsRingEntry>*> gps_;
  std::vector<std::uint64_t> drops_seen_;  // IMU rings, then GPS rings
  RepeatLimiter drop_log_;
};

}  // namespace headingd::daemon
