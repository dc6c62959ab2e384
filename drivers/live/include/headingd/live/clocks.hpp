#pragma once
// The two clocks headingd reads, in int64 nanoseconds (as every time inside headingd:
// integer sums and differences are exact, with no rounding that grows with uptime), and the
// conversions a timer or a timed wait needs.
#include <chrono>
#include <cstdint>
#include <ctime>

namespace headingd::live {

// For stamping what arrives, deadlines, ages and pacing: never jumps.
std::int64_t monotonicNs();
// For LCM utime and the wall-clock side of a recording only (LCM convention: wall clock).
std::int64_t realtimeNs();

timespec toTimespec(std::int64_t ns);
std::chrono::nanoseconds secondsToNs(double seconds);

}  // namespace headingd::live
