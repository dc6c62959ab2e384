#pragma once
// The wait before the next attempt of a driver that reopens or reconnects (the serial port,
// gpsd's socket, the CAN socket): the initial delay after a loss, doubled after each failed
// attempt up to a maximum, back to the initial one once an attempt succeeds. Shared, so that
// every driver retries alike.
#include <algorithm>
#include <chrono>

#include "headingd/live/clocks.hpp"

namespace headingd::live {

class ReconnectDelay {
 public:
  ReconnectDelay(std::chrono::nanoseconds initial, std::chrono::nanoseconds max)
      : initial_(initial), max_(max), next_(initial) {}
  ReconnectDelay(double initial_s, double max_s) : ReconnectDelay(secondsToNs(initial_s), secondsToNs(max_s)) {}

  // The wait before the next attempt; the one after it is twice as long (up to the maximum).
  std::chrono::nanoseconds afterFailure() {
    const std::chrono::nanoseconds wait = next_;
    next_ = std::min(next_ * 2, max_);
    return wait;
  }
  // An attempt succeeded, or the link was lost after working: start again from the initial wait.
  std::chrono::nanoseconds reset() { return next_ = initial_; }

 private:
  std::chrono::nanoseconds initial_, max_, next_;
};

}  // namespace headingd::live
