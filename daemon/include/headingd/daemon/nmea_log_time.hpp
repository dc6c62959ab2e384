#pragma once
// Where an NMEA epoch lies on the log clock of [nmea_log]: its UTC (the date comes from RMC
// or ZDA) plus a configured offset. A fix with a time of day but no date of its own (a GGA-only
// epoch) takes the date of the last dated one, or of the first dated one in the log, with a
// day added when the time of day goes back by more than 12 hours (midnight).
#include <cstdint>
#include <optional>

#include "headingd/nmea/fix.hpp"

namespace headingd::daemon {

class NmeaLogTime {
 public:
  static constexpr std::int64_t kDayNs = 86'400'000'000'000;

  // `day_start_ns`: 00:00 UTC of the day assumed until a fix brings a date (0 = 1970-01-01).
  NmeaLogTime(std::int64_t offset_ns, std::int64_t day_start_ns) : offset_ns_(offset_ns), day_ns_(day_start_ns) {}

  // nullopt for a fix without a time of day.
  std::optional<std::int64_t> of(const nmea::Fix& fix) {
    if (!fix.time_of_day_ns) return std::nullopt;
    const std::int64_t tod = *fix.time_of_day_ns;
    if (fix.utc_ns) {
      day_ns_ = *fix.utc_ns - tod;
    } else if (have_last_tod_ && tod < last_tod_ns_ - kDayNs / 2) {
      day_ns_ += kDayNs;
    }
    have_last_tod_ = true;
    last_tod_ns_ = tod;
    return day_ns_ + tod + offset_ns_;
  }

 private:
  std::int64_t offset_ns_;
  std::int64_t day_ns_;
  // (Not an optional: GCC 12 warns that one "may be used uninitialized".)
  bool have_last_tod_ = false;
  std::int64_t last_tod_ns_ = 0;
};

}  // namespace headingd::daemon
