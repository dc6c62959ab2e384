#pragma once
// NMEA 0183 (v2.3 field layout) sentences for the simulated receiver: GGA, RMC and VTG,
// each "$<talker><type>,...*HH\r\n" with HH the XOR of the characters between '$' and '*'.
#include <cstdint>
#include <string>
#include <string_view>

#include "headingd/sim/gps_model.hpp"

namespace headingd::sim {

// Maps the simulation's time axis to UTC: t = 0 is `time_of_day_s` after midnight UTC of
// the given date. Epoch times are written to the hundredth of a second, so the GPS rate
// must divide 100 Hz exactly (1, 2, 4, 5, 10 Hz) for them to be exact.
struct UtcClock {
  int year = 2026;
  int month = 6;
  int day = 1;
  double time_of_day_s = 12.0 * 3600.0;
};

struct UtcStamp {
  std::string hhmmss;  // "hhmmss.ss"
  std::string ddmmyy;
};
UtcStamp utcAt(const UtcClock& clock, double t_s);

// XOR of the bytes of `body` (the text between '$' and '*').
std::uint8_t nmeaChecksum(std::string_view body);
// "$" + body + "*HH\r\n".
std::string nmeaSentence(std::string_view body);

struct NmeaContext {
  UtcClock clock;
  std::string talker = "GP";      // GP (GPS) or GN (multi-constellation)
  double magnetic_variation_deg;  // the receiver's: WMM declination, east positive
};

// The three sentences of one epoch, in the order GGA, RMC, VTG.
std::string nmeaEpoch(const GpsEpoch& epoch, const NmeaContext& context);

}  // namespace headingd::sim
