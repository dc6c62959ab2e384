#pragma once
// The CAN epoch assembler's counters on STATUS, named the same for every CAN source
// ([can] and [candump_log]).
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "headingd/can/epoch_assembler.hpp"
#include "headingd/daemon/sources/source.hpp"
#include "headingd/daemon/system/repeat_limiter.hpp"

namespace headingd::daemon {

// Sets them from counter index `*i` on and advances it.
inline void reportAssemblerCounters(SourceReport& out, std::size_t* i, const can::AssemblerCounters& a) {
  can::forEachCounter(a, [&](const char* name, std::uint64_t v) { out.set((*i)++, name, v); });
}

// A warning, at most once a minute, when axis values at their signal's full scale have come
// since the last one: a saturated sensor, whose readings are used as read (STATUS counts them
// as full_scale_values). Called after each frame, on the source's thread.
class FullScaleWarning {
 public:
  void look(const can::AssemblerCounters& a, std::int64_t now_ns, std::string_view source) {
    if (a.full_scale_values == warned_at_) return;
    std::uint64_t suppressed = 0;
    if (!limiter_.allow(now_ns, &suppressed)) return;
    spdlog::warn(
        "source {}: {} axis values at their signal's full scale ({} in all): the sensor saturated, and the rotation "
        "or acceleration it measured was larger than it says",
        source, a.full_scale_values - warned_at_, a.full_scale_values);
    warned_at_ = a.full_scale_values;
  }

 private:
  std::uint64_t warned_at_ = 0;
  RepeatLimiter limiter_{1, 60.0};
};

}  // namespace headingd::daemon
