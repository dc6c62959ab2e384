#pragma once
// GPS epochs from an NMEA capture, placed on the IMU's time axis.
//
// Alignment rule (documented in docs/tools.md and in headingd-replay --help): NMEA carries
// the UTC time of each fix but no IMU time, so the capture's first epoch (the first
// sentence with a UTC time of day) is taken to be IMU time `first_epoch_t_s` (default 0, the
// first IMU row, which is how headingd-sim writes its captures), and every later epoch lies
// at first_epoch_t_s + (its UTC − the first epoch's UTC). Times of day that go backwards by
// more than 12 hours are a midnight rollover (a day is added). All sentences of one epoch
// (same UTC time of day) form one observation, with the fix as it stands after the last.
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/gps_observation.hpp"
#include "headingd/nmea/counters.hpp"
#include "headingd/nmea/parser.hpp"

namespace headingd::files {

// Every fix update of an NMEA log (plain or gzip; '#' comment lines skipped), in file order,
// with the parser's counters: what readNmeaEpochs places on the IMU axis, and what the
// daemon's NMEA log source reads its first epoch and date from.
struct NmeaLogFixes {
  std::vector<nmea::FixUpdate> updates;
  nmea::Counters counters;
};
NmeaLogFixes readNmeaLogFixes(const std::string& path);
// The same from the log's text, read by the caller.
NmeaLogFixes parseNmeaLogFixes(std::string_view text);

struct NmeaEpochs {
  std::vector<core::GpsObservation> epochs;  // in time order
  nmea::Counters counters;
};

// Throws FileError when the file cannot be read (gzip_file.hpp). '#' comment lines are skipped.
NmeaEpochs readNmeaEpochs(const std::string& path, double first_epoch_t_s = 0.0);

}  // namespace headingd::files
