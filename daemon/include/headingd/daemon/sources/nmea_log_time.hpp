#pragma once
// Where an NMEA epoch lies on the log clock of [nmea_log]: its UTC (the date comes from RMC
// or ZDA) plus a configured offset. A fix with a time of day but no date of its own (a GGA-only
// epoch) takes the date of the last dated one, or of the first dated one in the log, with a
// day added when the time of day goes back by more than 12 hours (midnight).
// A date more than a day away from the log's own is not believed: receivers print a default
// (1980-01-06) before their first fix, or a date 1024 weeks back after a week-number rollover.
// Such a fix keeps the day in use and is counted; the log starts on its first date near the
// one most of its fixes carry (logDayStart), so a bad first date cannot move the whole log.
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>

#include "headingd/nmea/fix.hpp"
#include "headingd/nmea/parser.hpp"

namespace headingd::daemon {

class NmeaLogTime {
 public:
  static constexpr std::int64_t kDayNs = 86'400'000'000'000;

  // `day_start_ns`: 00:00 UTC of the log's first day (logDayStart), or nullopt when no fix has
  // a date (then 1970-01-01 until the first date comes).
  NmeaLogTime(std::int64_t offset_ns, std::optional<std::int64_t> day_start_ns)
      : offset_ns_(offset_ns), day_ns_(day_start_ns.value_or(0)), have_day_(day_start_ns.has_value()) {}

  // 00:00 UTC of the first date within kBelievableDays of the date most of these fixes carry
  // (a log may span days; a wrong date is years off); nullopt when none has a date.
  static constexpr std::int64_t kBelievableDays = 30;
  static std::optional<std::int64_t> logDayStart(std::span<const nmea::FixUpdate> updates);

  // nullopt for a fix without a time of day.
  std::optional<std::int64_t> of(const nmea::Fix& fix) {
    if (!fix.time_of_day_ns) return std::nullopt;
    const std::int64_t tod = *fix.time_of_day_ns;
    if (fix.utc_ns) {
      const std::int64_t day = *fix.utc_ns - tod;
      if (!have_day_ || std::llabs(day - day_ns_) <= kDayNs) {
        day_ns_ = day;
        have_day_ = true;
      } else {
        ++dates_not_believed_;
      }
    } else if (have_last_tod_ && tod < last_tod_ns_ - kDayNs / 2) {
      day_ns_ += kDayNs;
    }
    have_last_tod_ = true;
    last_tod_ns_ = tod;
    return day_ns_ + tod + offset_ns_;
  }

  // Fixes whose date was more than a day from the log's and was not used.
  std::uint64_t datesNotBelieved() const { return dates_not_believed_; }

 private:
  std::int64_t offset_ns_;
  std::int64_t day_ns_;
  bool have_day_;
  std::uint64_t dates_not_believed_ = 0;
  // (Not an optional: GCC 12 warns that one "may be used uninitialized".)
  bool have_last_tod_ = false;
  std::int64_t last_tod_ns_ = 0;
};

}  // namespace headingd::daemon
