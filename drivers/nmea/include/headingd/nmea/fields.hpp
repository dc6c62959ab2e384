#pragma once
// Parsing of single NMEA fields. Every function returns nullopt for an empty field and for a
// malformed one; callers tell the two apart with field.empty() to count malformed fields.
#include <cstdint>
#include <optional>
#include <string_view>

namespace headingd::nmea {

inline constexpr double kKnotToMps = 1852.0 / 3600.0;  // international knot, exact
inline constexpr double kKmhToMps = 1000.0 / 3600.0;

// Plain decimal number: optional sign, digits, optional fraction. No exponent, no inf/nan,
// no spaces: anything else in an NMEA field is corruption.
std::optional<double> parseDecimal(std::string_view field);

// Unsigned decimal integer (satellite counts, PRNs, day, month, year, quality).
std::optional<int> parseInteger(std::string_view field);

// UTC time of day "hhmmss" or "hhmmss.s…" as nanoseconds since midnight. Second 60 is
// accepted (leap second).
std::optional<std::int64_t> parseTimeOfDay(std::string_view field);

// Latitude "ddmm.mmm" with hemisphere "N"/"S", in degrees, north positive.
std::optional<double> parseLatitude(std::string_view value, std::string_view hemisphere);
// Longitude "dddmm.mmm" with hemisphere "E"/"W", in degrees, east positive.
std::optional<double> parseLongitude(std::string_view value, std::string_view hemisphere);

struct DayMonthYy {
  int day = 0;    // 1..31
  int month = 0;  // 1..12
  int yy = 0;     // 0..99, the century is not sent (RMC)
};
// RMC date "ddmmyy".
std::optional<DayMonthYy> parseDdmmyy(std::string_view field);

// An angle in degrees, wrapped into [0, 360): receivers send 360.0 for north.
std::optional<double> parseBearing(std::string_view field);

}  // namespace headingd::nmea
