#pragma once
// One single-producer single-consumer ring between a source thread and the estimator thread.
// The producer never blocks and never allocates: when the ring is full the sample is dropped
// and counted (a late estimator must not stall a driver; the drop shows on STATUS).
#include <algorithm>
#include <atomic>
#include <boost/lockfree/spsc_queue.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "headingd/daemon/loop/doorbell.hpp"

namespace headingd::daemon {

struct RingStats {
  std::size_t capacity = 0;
  std::size_t high_water = 0;  // most entries waiting at once
  std::uint64_t pushed = 0;
  std::uint64_t dropped = 0;
};

template <class Entry>
class SampleRing {
 public:
  SampleRing(std::string name, std::size_t capacity) : name_(std::move(name)), capacity_(capacity), queue_(capacity) {}
  SampleRing(const SampleRing&) = delete;
  SampleRing& operator=(const SampleRing&) = delete;

  const std::string& name() const { return name_; }
  // Rung after each push (null: none). Set before the producer starts.
  void setDoorbell(Doorbell* doorbell) { doorbell_ = doorbell; }
  std::size_t capacity() const { return capacity_; }

  // Producer thread only. False when the ring was full and the entry was dropped.
  bool push(const Entry& entry) noexcept {
    if (!queue_.push(entry)) {
      dropped_.store(dropped_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
      return false;
    }
    pushed_.store(pushed_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    // Only this thread writes high_water_, so a plain load-compare-store is enough.
    const std::size_t waiting = capacity_ - queue_.write_available();
    if (waiting > high_water_.load(std::memory_order_relaxed)) high_water_.store(waiting, std::memory_order_relaxed);
    if (doorbell_ != nullptr) doorbell_->ring();
    return true;
  }

  // Consumer thread only. Hands at most the entries present on entry to `consume`, so a fast
  // producer cannot keep the consumer here forever. Returns how many.
  template <class Consume>
  std::size_t drain(Consume&& consume) {
    const std::size_t available = queue_.read_available();
    // Only the producer adds between two drains, so what waits now is the most that waited
    // since the last drain.
    window_high_water_ = std::max(window_high_water_, available);
    std::size_t n = 0;
    for (; n < available; ++n) {
      const Entry* front = &queue_.front();
      consume(*front);
      queue_.pop();
    }
    return n;
  }

  // Consumer thread only: the most entries waiting at a drain since the last call (0 if none
  // since), then starts a new window. Unlike high_water (since start), it shows whether a
  // backlog is building now: STATUS's window_high_water.
  std::size_t takeWindowHighWater() noexcept { return std::exchange(window_high_water_, 0); }

  // Any thread: a snapshot of the counters (each exact, not taken at one instant together).
  RingStats stats() const {
    RingStats s;
    s.capacity = capacity_;
    s.high_water = high_water_.load(std::memory_order_relaxed);
    s.pushed = pushed_.load(std::memory_order_relaxed);
    s.dropped = dropped_.load(std::memory_order_relaxed);
    return s;
  }

 private:
  Doorbell* doorbell_ = nullptr;
  std::string name_;
  std::size_t capacity_;
  boost::lockfree::spsc_queue<Entry> queue_;
  std::atomic<std::uint64_t> pushed_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::size_t> high_water_{0};
  std::size_t window_high_water_ = 0;  // consumer's
};

}  // namespace headingd::daemon
