#include "headingd/daemon/sources/nmea_log_time.hpp"

#include <map>

namespace headingd::daemon {

std::optional<std::int64_t> NmeaLogTime::logDayStart(std::span<const nmea::FixUpdate> updates) {
  std::map<std::int64_t, std::size_t> fixes_per_day;
  for (const nmea::FixUpdate& u : updates) {
    if (u.fix.utc_ns && u.fix.time_of_day_ns) ++fixes_per_day[*u.fix.utc_ns - *u.fix.time_of_day_ns];
  }
  if (fixes_per_day.empty()) return std::nullopt;
  std::int64_t usual_day = fixes_per_day.begin()->first;
  std::size_t most = 0;
  for (const auto& [day, count] : fixes_per_day) {
    if (count > most) {
      most = count;
      usual_day = day;
    }
  }
  for (const nmea::FixUpdate& u : updates) {
    if (!u.fix.utc_ns || !u.fix.time_of_day_ns) continue;
    const std::int64_t day = *u.fix.utc_ns - *u.fix.time_of_day_ns;
    if (std::llabs(day - usual_day) <= kBelievableDays * kDayNs) return day;
  }
  return usual_day;  // not reached: the usual day itself is within reach
}

}  // namespace headingd::daemon
