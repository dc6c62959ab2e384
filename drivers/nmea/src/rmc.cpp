#include "field_reader.hpp"

#include <cmath>

namespace headingd::nmea {

// $--RMC,hhmmss.ss,A,llll.ll,a,yyyyy.yy,a,x.x,x.x,ddmmyy,x.x,a[,m[,s]]*hh
std::optional<Rmc> decodeRmc(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  // 11 data fields in NMEA 2.0, + mode indicator (2.3), + navigation status (4.1).
  if (f.dataFields() < 11 || f.dataFields() > 13) return std::nullopt;
  Rmc r;
  r.time_of_day_ns = f.timeOfDay(1);
  r.status = f.letter(2).value_or('V');
  r.position = f.position(3);
  if (const auto knots = f.nonNegative(7)) r.speed_mps = *knots * kKnotToMps;
  r.course_deg = f.bearing(8);
  r.date = f.ddmmyy(9);
  const auto magvar = f.decimal(10);
  const auto direction = f.letter(11);
  if (magvar && !(std::fabs(*magvar) <= 180.0)) {
    f.countInvalid();  // a variation is 0..180 degrees east or west: more is a corrupt field, not used
  } else if (magvar && direction && (*direction == 'E' || *direction == 'W')) {
    r.magvar_deg = *direction == 'W' ? -*magvar : *magvar;
  } else if (magvar || direction) {
    f.countInvalid();  // a variation without a side, or a side without a variation
  }
  r.mode_indicator = f.letter(12);
  r.nav_status = f.letter(13);
  return r;
}

}  // namespace headingd::nmea
