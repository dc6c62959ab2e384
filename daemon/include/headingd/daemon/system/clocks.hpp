#pragma once
// The two clocks the daemon reads, in int64 nanoseconds (as every time inside headingd:
// integer sums and differences are exact, with no rounding that grows with uptime).
#include <cstdint>
#include <ctime>

namespace headingd::daemon {

inline std::int64_t nowNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
// For deadlines, ages and pacing: never jumps.
inline std::int64_t monotonicNs() { return nowNs(CLOCK_MONOTONIC); }
// For LCM utime only (LCM convention: wall clock).
inline std::int64_t realtimeNs() { return nowNs(CLOCK_REALTIME); }

inline timespec toTimespec(std::int64_t ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  return ts;
}

}  // namespace headingd::daemon
