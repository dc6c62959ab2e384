#pragma once
// The wait before the next attempt of a GPS reader that reopens or reconnects (the serial
// port, gpsd's socket): the initial delay after a loss, doubled after each failed attempt up to
// a maximum, back to the initial one once an attempt succeeds. Shared by the serial and the
// gpsd readers, so that both retry alike.
#include <algorithm>
#include <chrono>
#include <cstdint>

namespace headingd::nmea {

class ReconnectDelay {
 public:
  ReconnectDelay(double initial_s, double max_s) : initial_(toNs(initial_s)), max_(toNs(max_s)), next_(initial_) {}

  // The wait before the next attempt; the one after it is twice as long (up to the maximum).
  std::chrono::nanoseconds afterFailure() {
    const std::chrono::nanoseconds wait = next_;
    next_ = std::min(next_ * 2, max_);
    return wait;
  }
  // An attempt succeeded, or the link was lost after working: start again from the initial wait.
  std::chrono::nanoseconds reset() { return next_ = initial_; }

 private:
  static std::chrono::nanoseconds toNs(double seconds) {
    return std::chrono::nanoseconds(static_cast<std::int64_t>(seconds * 1e9));
  }
  std::chrono::nanoseconds initial_, max_, next_;
};

}  // namespace headingd::nmea
