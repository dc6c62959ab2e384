#pragma once
// The GPS epochs on their way from the rings into the estimator, held until they are due:
// a live or file epoch after the IMU samples up to its time (core::ImuThenGpsOrder, as
// headingd-replay does), a recording's epoch after as many IMU samples as it went in after in
// the live run (GpsRingEntry::after_imu_samples), so that a replay puts it back in the same
// place whatever the ticks. `Use` is called with each epoch as it is due, in that order.
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <vector>

#include "headingd/core/imu_then_gps_order.hpp"
#include "headingd/daemon/loop/ring_entries.hpp"

namespace headingd::daemon {

class GpsFeed {
 public:
  // Room for `ring_capacity` epochs (the GPS rings' sum) twice over: one tick's and the last.
  explicit GpsFeed(std::size_t ring_capacity) {
    timed_.reserve(2 * ring_capacity + 1);
    placed_.reserve(2 * ring_capacity + 1);
  }

  // An epoch from a ring. If the timed epochs fill their room (never expected: GPS is slow),
  // the oldest goes in now, counted in forcedOut().
  template <class Use>
  void add(const GpsRingEntry& e, Use&& use) {
    if (e.after_imu_samples >= 0) {
      placed_.push_back(e);  // in the recording's order, which is the live order
      return;
    }
    if (timed_.held() == timed_.capacity()) {
      timed_.releaseOldest(use);
      ++forced_out_;
    }
    timed_.pushGps(e);
  }

  // Several sources' epochs by time, ties by arrival.
  void sortHeld() {
    timed_.sortHeld([](const GpsRingEntry& a, const GpsRingEntry& b) {
      return std::tie(a.observation.t_ns, a.arrival_mono_ns, a.source_index) <
             std::tie(b.observation.t_ns, b.arrival_mono_ns, b.source_index);
    });
  }

  // The recording's epochs due after `imu_samples` IMU samples went in.
  template <class Use>
  void releasePlaced(std::uint64_t imu_samples, Use&& use) {
    while (next_placed_ < placed_.size() &&
           static_cast<std::uint64_t>(placed_[next_placed_].after_imu_samples) <= imu_samples) {
      use(placed_[next_placed_++]);
    }
    if (next_placed_ == placed_.size()) {
      placed_.clear();
      next_placed_ = 0;
    }
  }

  // After the IMU sample at `imu_t_ns`, the `imu_samples`-th: every epoch now due.
  template <class Use>
  void afterImu(std::int64_t imu_t_ns, std::uint64_t imu_samples, Use&& use) {
    timed_.afterImu(imu_t_ns, use);
    releasePlaced(imu_samples, use);
  }

  // Every timed epoch held, as it is: without IMU data an epoch would wait for ever.
  template <class Use>
  void releaseTimed(Use&& use) {
    timed_.releaseAll(use);
  }

  // Every recording epoch held (the last tick: the recording's last epoch may follow its last sample).
  template <class Use>
  void releaseAllPlaced(Use&& use) {
    while (next_placed_ < placed_.size()) use(placed_[next_placed_++]);
  }

  std::uint64_t forcedOut() const { return forced_out_; }

 private:
  core::ImuThenGpsOrder<GpsRingEntry> timed_;
  std::vector<GpsRingEntry> placed_;  // [next_placed_, end) are held
  std::size_t next_placed_ = 0;
  std::uint64_t forced_out_ = 0;
};

}  // namespace headingd::daemon
