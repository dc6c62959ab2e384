#pragma once
// Bounds how often one kind of message is logged (per-sample and per-frame problems can come
// hundreds of times a second): at most `burst` messages per `interval`; the ones held back
// are counted and the count is handed to the next message that gets through.
#include <cstdint>

namespace headingd::daemon {

class RepeatLimiter {
 public:
  RepeatLimiter(int burst, double interval_s)
      : burst_(burst), interval_ns_(static_cast<std::int64_t>(interval_s * 1e9)) {}

  // True when this occurrence (at monotonic `now_ns`) may be logged; then *suppressed gets
  // how many were held back since the last one logged.
  bool allow(std::int64_t now_ns, std::uint64_t* suppressed) {
    if (!started_ || now_ns - window_start_ns_ >= interval_ns_) {
      started_ = true;
      window_start_ns_ = now_ns;
      in_window_ = 0;
    }
    if (in_window_ >= burst_) {
      ++suppressed_;
      return false;
    }
    ++in_window_;
    *suppressed = suppressed_;
    suppressed_ = 0;
    return true;
  }

 private:
  int burst_;
  std::int64_t interval_ns_;
  bool started_ = false;
  std::int64_t window_start_ns_ = 0;
  int in_window_ = 0;
  std::uint64_t suppressed_ = 0;
};

}  // namespace headingd::daemon
