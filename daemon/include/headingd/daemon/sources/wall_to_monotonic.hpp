#pragma once
// Puts a CLOCK_REALTIME timestamp (a CAN frame's kernel receive time) on CLOCK_MONOTONIC,
// across steps of the wall clock (date -s, an NTP step, a GPS-disciplined clock setting
// itself): the kernel stamped the frame before the daemon reads the clocks, so a step in
// between would move the frame by the whole step, an hour ahead of or behind its neighbours,
// which the estimator's sample gate then rejects (backwards_time) or takes as a clock jump.
//
// It keeps the offset realtime - monotonic of the regime before the last step beside the
// current one, and of the two mappings takes the latest that is not after now: a frame
// cannot have arrived in the future, and the other regime's mapping is off by the whole step.
// A step is an offset change of more than kStepNs between two frames (NTP's slewing changes
// it by at most 0.5 ms a second). The offset is only learnt from clock readings taken close
// together (readClocks): a thread preempted between its two clock reads (milliseconds under
// load or emulation) would otherwise look like a step. Allocation-free, one thread.
#include <cstdint>

namespace headingd::daemon {

// Both clocks now: realtime read between two monotonic reads; `tight` when those were at most
// ClockReading::kTightNs apart, so the offset is known to that.
struct ClockReading {
  static constexpr std::int64_t kTightNs = 100'000;  // 0.1 ms
  std::int64_t realtime_ns = 0, monotonic_ns = 0;
  bool tight = false;
};
template <class ReadMonotonic, class ReadRealtime>
ClockReading readClocks(ReadMonotonic monotonic, ReadRealtime realtime) {
  ClockReading r;
  for (int attempt = 0; attempt < 3 && !r.tight; ++attempt) {
    const std::int64_t before = monotonic();
    r.realtime_ns = realtime();
    r.monotonic_ns = monotonic();
    r.tight = r.monotonic_ns - before <= ClockReading::kTightNs;
    r.realtime_ns += (r.monotonic_ns - before) / 2;  // read mid-bracket: carried to its end, monotonic_ns
  }
  return r;
}

class WallToMonotonic {
 public:
  static constexpr std::int64_t kStepNs = 1'000'000;  // 1 ms

  // `wall_ns` on the monotonic axis, given the two clocks read now.
  std::int64_t map(std::int64_t wall_ns, const ClockReading& now) {
    const std::int64_t monotonic_now_ns = now.monotonic_ns;
    const std::int64_t offset = now.realtime_ns - now.monotonic_ns;
    if (!have_offset_) {
      current_ = previous_ = offset;
      have_offset_ = now.tight;
    } else if (!now.tight) {
      // A loose reading: map with the offset known.
    } else if (offset - current_ > kStepNs || current_ - offset > kStepNs) {
      previous_ = current_;
      current_ = offset;
      ++steps_;
    } else {
      previous_ += offset - current_;  // slewing moves both regimes alike
      current_ = offset;
    }
    const std::int64_t by_current = wall_ns - current_;
    const std::int64_t by_previous = wall_ns - previous_;
    std::int64_t t = by_current;
    if (by_current > monotonic_now_ns || (by_previous <= monotonic_now_ns && by_previous > by_current)) t = by_previous;
    if (t > monotonic_now_ns) {  // stamped in the future by both: never on a sane clock
      t = monotonic_now_ns;
      ++clamped_;
    }
    return t;
  }
  std::uint64_t steps() const { return steps_; }      // wall-clock steps seen between two frames
  std::uint64_t clamped() const { return clamped_; }  // times after now, set to now

 private:
  bool have_offset_ = false;
  std::int64_t current_ = 0, previous_ = 0;
  std::uint64_t steps_ = 0, clamped_ = 0;
};

}  // namespace headingd::daemon
