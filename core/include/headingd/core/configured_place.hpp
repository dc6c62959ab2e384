#pragma once
// A place given in the configuration (the [place] table, headingd-replay --place): where the
// World Magnetic Model is evaluated until a GPS fix says where the person is. It gives the
// estimator the reference field (strength and dip for the disturbance tests, the whole field
// for MAU, Khedr et al. 2020) and the WMM declination, so the heading is true heading indoors
// or without a receiver. Parsing and date choice only: core reads no clock.
#include <toml++/toml.h>
#include <optional>
#include <string>

#include "headingd/core/wmm.hpp"

namespace headingd::core {

struct ConfiguredPlace {
  GeodeticPosition position;
  std::optional<double> decimal_year;  // the table's date; none: the day the run starts
};

// The [place] table (null: no place). Keys: latitude_deg, longitude_deg (both required),
// height_m (above the WGS-84 ellipsoid, default 0), and at most one of date (a TOML date,
// 2026-12-07) or decimal_year (what a recording writes: exact). Throws ConfigError naming
// `source`, the line and the key.
std::optional<ConfiguredPlace> parsePlaceTable(const toml::table* place, const std::string& source);

// The year the model is evaluated on for `place`. A date the table gives must lie within the
// model's validity (ConfigError otherwise: the user typed it). Without one, `today` (the
// system's date) is used; a system clock outside the validity (a computer without a
// real-time clock still in 1970) is moved to the nearest end of it and *warning says so.
double placeDecimalYear(const ConfiguredPlace& place, double today_decimal_year, const WorldMagneticModel& wmm,
                        std::string* warning);

// One line for the log: the place, the date, and the model's declination, strength and dip
// there ("place 59.3500, 18.0700, 30 m on 2026.93: WMM2025 declination 8.12 deg, ...").
std::string describePlace(const GeodeticPosition& position, double decimal_year, const WorldMagneticModel& wmm);

// Decimal year (decimalYear's definition) of a time in nanoseconds since 1970-01-01 UTC.
double decimalYearOfUnixNs(std::int64_t unix_ns);

}  // namespace headingd::core
