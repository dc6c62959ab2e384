#include <cmath>

#include "field_reader.hpp"

namespace headingd::nmea {

// $--ZDA,hhmmss.ss,dd,mm,yyyy,zh,zm*hh
std::optional<Zda> decodeZda(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  if (f.dataFields() != 6) return std::nullopt;
  Zda z;
  z.time_of_day_ns = f.timeOfDay(1);
  z.day = f.integer(2);
  z.month = f.integer(3);
  z.year = f.integer(4);
  if ((z.day && (*z.day < 1 || *z.day > 31)) || (z.month && (*z.month < 1 || *z.month > 12)) ||
      (z.year && (*z.year < 1980 || *z.year > 2200))) {
    // A date before GPS existed or out of range: keep the time, drop the date.
    f.countInvalid();
    z.day.reset();
    z.month.reset();
    z.year.reset();
  }
  // The local zone may be signed ("-05"); zones run from -12 to +14 hours. Anything beyond is
  // a bad field (and must not reach the int conversion: 1e50 does not fit; found by fuzzing).
  if (const auto h = f.decimal(5)) {
    if (std::abs(*h) <= 14.0) {
      z.zone_hours = static_cast<int>(*h);
    } else {
      f.countInvalid();
    }
  }
  z.zone_minutes = f.integer(6);
  return z;
}

}  // namespace headingd::nmea
