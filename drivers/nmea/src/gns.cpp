#include "field_reader.hpp"

namespace headingd::nmea {

// $--GNS,hhmmss.ss,llll.ll,a,yyyyy.yy,a,c--c,xx,x.x,x.x,x.x,x.x,x.x[,s]*hh
std::optional<Gns> decodeGns(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  // 12 data fields, + navigation status in NMEA 4.1.
  if (f.dataFields() < 12 || f.dataFields() > 13) return std::nullopt;
  Gns g;
  g.time_of_day_ns = f.timeOfDay(1);
  g.position = f.position(2);
  const auto modes = f.raw(6);
  if (modes.size() <= g.mode_indicators.size()) {
    for (std::size_t i = 0; i < modes.size(); ++i) g.mode_indicators[i] = modes[i];
  } else {
    f.countInvalid();
  }
  g.satellites_used = f.integer(7);
  g.hdop = f.nonNegative(8);
  g.alt_msl_m = f.decimal(9);
  g.geoid_separation_m = f.decimal(10);
  g.dgps_age_s = f.nonNegative(11);
  g.dgps_station = f.integer(12);
  g.nav_status = f.letter(13);
  return g;
}

}  // namespace headingd::nmea
