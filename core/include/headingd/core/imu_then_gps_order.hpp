#pragma once
// The order in which the estimator sees IMU samples and GPS epochs: each IMU sample, then
// every GPS epoch stamped at or before that sample's time, oldest first. An epoch thus waits
// until the attitude has been propagated to its time (the course it brings is compared with
// the heading of the same moment), and an epoch of the same time as a sample goes in after it.
// headingd-replay and the daemon's estimator loop both feed HeadingPipeline in this order, so
// a replay and a live run of the same data see the same sequence of calls.
//
// Pure: it holds epochs and says which are due; the caller does the processing (so it can
// publish or count what goes in). No allocation while the held epochs fit what reserve() set.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "headingd/core/gps_observation.hpp"

namespace headingd::core {

// The time an epoch is ordered by (IMU time axis). Another epoch type (one carrying where it
// came from, say) provides its own overload in its namespace.
inline std::int64_t sensorTimeNs(const GpsObservation& g) { return g.t_ns; }

template <class Epoch>
class ImuThenGpsOrder {
 public:
  void reserve(std::size_t epochs) { epochs_.reserve(epochs); }
  std::size_t capacity() const { return epochs_.capacity(); }
  // Epochs pushed and not yet handed out.
  std::size_t held() const { return epochs_.size() - next_; }

  // Holds an epoch until an IMU sample at or after its time. Push in time order, or call
  // sortHeld() before the next sample.
  void pushGps(const Epoch& epoch) {
    dropHandedOut();
    epochs_.push_back(epoch);
  }

  // After an IMU sample went in: hands `use` every held epoch up to the sample's time.
  // Stops at the first later epoch, so held epochs keep the order they have.
  template <class Use>
  void afterImu(std::int64_t imu_t_ns, Use&& use) {
    while (next_ < epochs_.size() && sensorTimeNs(epochs_[next_]) <= imu_t_ns) use(epochs_[next_++]);
  }

  // Hands out every held epoch whatever its time (no IMU sample will come to release it).
  template <class Use>
  void releaseAll(Use&& use) {
    while (next_ < epochs_.size()) use(epochs_[next_++]);
  }

  // Hands out the oldest held epoch (to make room when the holder is full).
  template <class Use>
  void releaseOldest(Use&& use) {
    if (next_ < epochs_.size()) use(epochs_[next_++]);
  }

  // Puts the held epochs in the order `less` gives (std::sort: no temporary buffer).
  template <class Less>
  void sortHeld(Less less) {
    const auto first = epochs_.begin() + static_cast<std::ptrdiff_t>(next_);
    if (!std::is_sorted(first, epochs_.end(), less)) std::sort(first, epochs_.end(), less);
  }

 private:
  void dropHandedOut() {
    if (next_ == 0) return;
    epochs_.erase(epochs_.begin(), epochs_.begin() + static_cast<std::ptrdiff_t>(next_));
    next_ = 0;
  }

  std::vector<Epoch> epochs_;  // [next_, end) are held
  std::size_t next_ = 0;
};

}  // namespace headingd::core
