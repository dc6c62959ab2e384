#pragma once
// The usual step of a file source's time line: the median of the steps between its samples
// (or epochs), so that a gap or a burst here and there does not move it. The file sources use
// it for the length of a loop (playback_clock.hpp, imu_csv_source.cpp).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace headingd::daemon {

// The median of `steps` (the upper one of an even count), nullopt when there are none.
inline std::optional<std::int64_t> medianStep(std::vector<std::int64_t> steps) {
  if (steps.empty()) return std::nullopt;
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

}  // namespace headingd::daemon
