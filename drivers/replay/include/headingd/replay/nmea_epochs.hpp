#pragma once
// GPS epochs from an NMEA capture, placed on the IMU's time axis.
//
// Alignment rule (documented in the README and in headingd-replay --help): NMEA carries
// the UTC time of each fix but no IMU time, so the capture's first epoch (the first
// sentence with a UTC time of day) is taken to be IMU time `first_epoch_t_s` (default 0, the
// first IMU row, which is how headingd-sim writes its captures), and every later epoch lies
// at first_epoch_t_s + (its UTC − the first epoch's UTC). Times of day that go backwards by
// more than 12 hours are a midnight rollover (a day is added). All sentences of one epoch
// (same UTC time of day) form one observation, with the fix as it stands after the last.
#include <string>
#include <vector>

#include "headingd/core/gps_observation.hpp"
#include "headingd/nmea/counters.hpp"

namespace headingd::replay {

struct NmeaEpochs {
  std::vector<core::GpsObservation> epochs;  // in time order
  nmea::Counters counters;
};

// Throws CsvError (file errors) like the other readers. '#' comment lines are skipped.
NmeaEpochs readNmeaEpochs(const std::string& path, double first_epoch_t_s = 0.0);

}  // namespace headingd::replay
