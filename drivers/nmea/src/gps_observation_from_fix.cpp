#include "headingd/nmea/gps_observation_from_fix.hpp"

#include <chrono>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/core/wmm.hpp"

namespace headingd::nmea {
namespace {

using core::kRadPerDeg;

// Decimal year of a UTC instant, for the magnetic model (a day's resolution is plenty).
double decimalYearOfUtc(std::int64_t utc_ns) {
  using namespace std::chrono;
  const year_month_day date(floor<days>(sys_time<nanoseconds>(nanoseconds(utc_ns))));
  return core::decimalYear(static_cast<int>(date.year()), static_cast<int>(static_cast<unsigned>(date.month())),
                           static_cast<int>(static_cast<unsigned>(date.day())));
}

}  // namespace

core::GpsObservation gpsObservationFromFix(const nmea::Fix& fix, std::int64_t t_ns) {
  core::GpsObservation o;
  o.t_ns = t_ns;
  o.fix_ok = fix.position.has_value() && fix.mode.has_value() && *fix.mode != nmea::FixMode::kNoFix;
  if (fix.position) {
    // Height above the ellipsoid = above mean sea level + geoid separation (GGA).
    const double height_m = fix.alt_msl_m.value_or(0.0) + fix.geoid_separation_m.value_or(0.0);
    o.position = core::GeodeticPosition{fix.position->lat_deg, fix.position->lon_deg, height_m * 1e-3};
  }
  if (fix.utc_ns) o.decimal_year = decimalYearOfUtc(*fix.utc_ns);
  if (fix.course_deg) o.course_rad = *fix.course_deg * kRadPerDeg;
  o.speed_mps = fix.speed_mps;
  o.hdop = fix.hdop;
  if (fix.magvar_deg) o.magvar_rad = *fix.magvar_deg * kRadPerDeg;
  return o;
}

}  // namespace headingd::nmea
