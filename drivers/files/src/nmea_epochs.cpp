#include "headingd/files/nmea_epochs.hpp"

#include <cmath>

#include "headingd/files/gzip_file.hpp"
#include "headingd/nmea/comment_filter.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"
#include "headingd/nmea/parser.hpp"

namespace headingd::files {
namespace {

constexpr std::int64_t kDayNs = 86'400'000'000'000;

}  // namespace

NmeaLogFixes readNmeaLogFixes(const std::string& path) {
  return parseNmeaLogFixes(readMaybeGzipFile(path, kWholeLogLimit));
}

NmeaLogFixes parseNmeaLogFixes(std::string_view text) {
  std::vector<std::uint8_t> bytes;
  nmea::CommentFilter comments;
  comments.filter({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, bytes);
  nmea::Parser parser;
  NmeaLogFixes log;
  parser.feed(std::span<const std::uint8_t>(bytes), log.updates);
  parser.finish();
  log.counters = parser.counters();
  return log;
}

NmeaEpochs readNmeaEpochs(const std::string& path, double first_epoch_t_s) {
  const NmeaLogFixes log = readNmeaLogFixes(path);
  const std::vector<nmea::FixUpdate>& updates = log.updates;
  NmeaEpochs result;
  result.counters = log.counters;
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
    result.epochs.push_back(gpsObservationFromFix(fix, first_epoch_ns + tod + day_offset_ns - *first_tod));
  }
  return result;
}

}  // namespace headingd::files
