#pragma once
// The clock the live drivers stamp what they receive with (CLOCK_MONOTONIC, nanoseconds),
// and a configured number of seconds as a timer's wait.
#include <chrono>
#include <cstdint>

namespace headingd::live {

std::int64_t monotonicNowNs();
std::chrono::nanoseconds secondsToNs(double seconds);

}  // namespace headingd::live
