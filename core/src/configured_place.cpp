#include "headingd/core/configured_place.hpp"

#include <chrono>
#include <cstdio>

#include "headingd/core/config_error.hpp"
#include "headingd/core/toml_table_reader.hpp"

namespace headingd::core {

std::optional<ConfiguredPlace> parsePlaceTable(const toml::table* place, const std::string& source) {
  if (place == nullptr || place->empty()) return std::nullopt;
  TomlTableReader r(place, source, "place");
  const bool has_latitude = r.has("latitude_deg"), has_longitude = r.has("longitude_deg");
  ConfiguredPlace p;
  p.position.latitude_deg = r.number("latitude_deg", 0.0, -90.0, 90.0, "deg");
  p.position.longitude_deg = r.number("longitude_deg", 0.0, -180.0, 180.0, "deg");
  // The WMM is valid from 1 km below the ellipsoid to 850 km above it.
  p.position.height_km = 1e-3 * r.number("height_m", 0.0, -1000.0, 850000.0, "m");
  if (r.has("date") && r.has("decimal_year")) r.failBetween("date", "decimal_year", "give one of date or decimal_year");
  if (const toml::node* date = r.node("date")) {
    const auto* d = date->as_date();
    if (d == nullptr) r.fail("date", "expected a TOML date such as 2026-12-07 (no quotes)");
    try {
      p.decimal_year = decimalYear(d->get().year, d->get().month, d->get().day);
    } catch (const std::invalid_argument& e) {
      r.fail("date", e.what());
    }
  }
  if (r.has("decimal_year")) p.decimal_year = r.number("decimal_year", 0.0, 1900.0, 2100.0, "year");
  r.rejectUnknownKeys("config/headingd.toml documents them");
  if (!has_latitude || !has_longitude) {
    r.fail(has_latitude ? "longitude_deg" : "latitude_deg", "missing: a [place] needs latitude_deg and longitude_deg");
  }
  return p;
}

double placeDecimalYear(const ConfiguredPlace& place, double today_decimal_year, const WorldMagneticModel& wmm,
                        std::string* warning) {
  const double first = wmm.epochYear(), last = wmm.validUntilYear();
  char range[96];
  std::snprintf(range, sizeof range, "%s's validity (%.1f to %.1f)", wmm.modelName().c_str(), first, last);
  if (place.decimal_year) {
    if (!wmm.isDateWithinValidity(*place.decimal_year)) {
      throw ConfigError("[place] date " + std::to_string(*place.decimal_year) + " is outside " + range +
                        "; expected a date the model covers");
    }
    return *place.decimal_year;
  }
  if (wmm.isDateWithinValidity(today_decimal_year)) return today_decimal_year;
  const double moved = today_decimal_year < first ? first : last;
  if (warning != nullptr) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "the system date (%.2f) is outside %s: the place's field is taken on %.2f; set [place] date if the "
                  "clock is not set",
                  today_decimal_year, range, moved);
    *warning = text;
  }
  return moved;
}

std::string describePlace(const GeodeticPosition& position, double decimal_year, const WorldMagneticModel& wmm) {
  const MagneticFieldElements f = wmm.field(position, decimal_year);
  char text[256];
  std::snprintf(text, sizeof text,
                "place %.4f, %.4f, %.0f m on %.2f: %s declination %.2f deg, field %.1f uT, dip %.1f deg (until a GPS "
                "fix gives the position)",
                position.latitude_deg, position.longitude_deg, 1e3 * position.height_km, decimal_year,
                wmm.modelName().c_str(), f.declination_deg, 1e-3 * f.f_nT, f.inclination_deg);
  return text;
}

double decimalYearOfUnixNs(std::int64_t unix_ns) {
  using namespace std::chrono;
  const sys_days day = floor<days>(sys_time<nanoseconds>(nanoseconds(unix_ns)));
  const year_month_day ymd(day);
  const double start_of_day =
      decimalYear(static_cast<int>(ymd.year()), static_cast<int>(static_cast<unsigned>(ymd.month())),
                  static_cast<int>(static_cast<unsigned>(ymd.day())));
  const double days_in_year = ymd.year().is_leap() ? 366.0 : 365.0;
  const double day_fraction =
      static_cast<double>(unix_ns - duration_cast<nanoseconds>(day.time_since_epoch()).count()) / 86400e9;
  return start_of_day + day_fraction / days_in_year;
}

}  // namespace headingd::core
