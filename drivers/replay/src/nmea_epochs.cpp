#include "headingd/replay/nmea_epochs.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

#include "headingd/core/wmm.hpp"
#include "headingd/nmea/comment_filter.hpp"
#include "headingd/nmea/parser.hpp"
#include "headingd/replay/numeric_csv.hpp"

namespace headingd::replay {
namespace {

constexpr std::int64_t kDayNs = 86'400'000'000'000;
constexpr double kRad = std::numbers::pi / 180.0;

// Decimal year of a UTC instant (for the WMM; a day's resolution is plenty).
double decimalYearOf(std::int64_t utc_ns) {
  using namespace std::chrono;
  const sys_days day = floor<days>(sys_time<nanoseconds>(nanoseconds(utc_ns)));
  const year_month_day ymd(day);
  return core::decimalYear(static_cast<int>(ymd.year()), static_cast<int>(static_cast<unsigned>(ymd.month())),
                           static_cast<int>(static_cast<unsigned>(ymd.day())));
}

core::GpsObservation toObservation(const nmea::Fix& fix, std::int64_t t_ns) {
  core::GpsObservation o;
  o.t_ns = t_ns;
  o.fix_ok = fix.position && fix.mode && *fix.mode != nmea::FixMode::kNoFix;
  if (fix.position) {
    o.position = core::GeodeticPosition{fix.position->lat_deg, fix.position->lon_deg,
                                        (fix.alt_msl_m.value_or(0.0) + fix.geoid_separation_m.value_or(0.0)) * 1e-3};
  }
  if (fix.utc_ns) o.decimal_year = decimalYearOf(*fix.utc_ns);
  if (fix.course_deg) o.course_rad = *fix.course_deg * kRad;
  o.speed_mps = fix.speed_mps;
  o.hdop = fix.hdop;
  if (fix.magvar_deg) o.magvar_rad = *fix.magvar_deg * kRad;
  return o;
}

}  // namespace

NmeaEpochs readNmeaEpochs(const std::string& path, double first_epoch_t_s) {
  const std::string text = readMaybeGzipFile(path);
  std::vector<std::uint8_t> bytes;
  nmea::CommentFilter comments;
  comments.filter({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, bytes);

  nmea::Parser parser;
  std::vector<nmea::FixUpdate> updates;
  parser.feed(std::span<const std::uint8_t>(bytes), updates);
  parser.finish();

  NmeaEpochs result;
  result.counters = parser.counters();
  const auto first_epoch_ns = static_cast<std::int64_t>(std::llround(first_epoch_t_s * 1e9));
  std::optional<std::int64_t> first_tod, previous_tod;
  std::int64_t day_offset_ns = 0;
  for (std::size_t i = 0; i < updates.size(); ++i) {
    const nmea::Fix& fix = updates[i].fix;
    if (!fix.time_of_day_ns) continue;
    // Only the last update of an epoch (the next update has another time, or none follows).
    const bool last_of_epoch = i + 1 == updates.size() || updates[i + 1].fix.time_of_day_ns != fix.time_of_day_ns;
    if (!last_of_epoch) continue;
    const std::int64_t tod = *fix.time_of_day_ns;
    if (!first_tod) first_tod = tod;
    if (previous_tod && tod < *previous_tod - kDayNs / 2) day_offset_ns += kDayNs;  // midnight
    previous_tod = tod;
    result.epochs.push_back(toObservation(fix, first_epoch_ns + tod + day_offset_ns - *first_tod));
  }
  return result;
}

}  // namespace headingd::replay
