#pragma once
// What the receiver says about one output epoch (one UTC time of fix), accumulated from the
// sentences of that epoch. Absent fields are nullopt: a field is never carried over from an
// earlier epoch, so a course or speed here is always the receiver's current one.
#include <cstdint>
#include <optional>

#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea {

enum class FixMode { kNoFix, k2D, k3D };
const char* fixModeName(FixMode m);  // "no_fix", "2d", "3d"

struct Fix {
  std::optional<std::int64_t> time_of_day_ns;  // UTC, since midnight: identifies the epoch
  std::optional<std::int64_t> utc_ns;          // since 1970-01-01 UTC; needs a date (RMC/ZDA)
  std::optional<Position> position;
  std::optional<double> alt_msl_m;
  std::optional<double> geoid_separation_m;
  std::optional<double> course_deg;  // over ground, true, [0, 360)
  std::optional<double> speed_mps;   // over ground
  std::optional<FixMode> mode;
  std::optional<int> quality;  // GGA fix quality, see Gga::quality
  std::optional<double> hdop;
  std::optional<double> pdop;
  std::optional<double> vdop;
  std::optional<int> satellites_used;
  std::optional<double> magvar_deg;   // receiver's magnetic variation (RMC), east positive
  std::optional<double> heading_deg;  // true heading (HDT), [0, 360)
  std::optional<double> lat_sigma_m;  // GST 1-sigma errors
  std::optional<double> lon_sigma_m;
  std::optional<double> alt_sigma_m;
};

}  // namespace headingd::nmea
