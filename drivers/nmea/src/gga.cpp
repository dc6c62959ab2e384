#include "field_reader.hpp"

namespace headingd::nmea {

// $--GGA,hhmmss.ss,llll.ll,a,yyyyy.yy,a,q,nn,h.h,a.a,M,g.g,M,age,sta*hh
std::optional<Gga> decodeGga(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  // 14 data fields; some receivers drop the two DGPS fields.
  if (f.dataFields() < 12 || f.dataFields() > 14) return std::nullopt;
  Gga g;
  g.time_of_day_ns = f.timeOfDay(1);
  g.position = f.position(2);
  g.quality = f.integer(6);
  g.satellites_used = f.integer(7);
  g.hdop = f.nonNegative(8);
  g.alt_msl_m = f.withUnit(9, 'M');
  g.geoid_separation_m = f.withUnit(11, 'M');
  g.dgps_age_s = f.nonNegative(13);
  g.dgps_station = f.integer(14);
  return g;
}

}  // namespace headingd::nmea
