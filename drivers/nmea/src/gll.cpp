#include "field_reader.hpp"

namespace headingd::nmea {

// $--GLL,llll.ll,a,yyyyy.yy,a,hhmmss.ss,A[,m]*hh
std::optional<Gll> decodeGll(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  // NMEA 2.3 added the mode indicator; older receivers send 6 fields.
  if (f.dataFields() < 6 || f.dataFields() > 7) return std::nullopt;
  Gll g;
  g.position = f.position(1);
  g.time_of_day_ns = f.timeOfDay(5);
  g.status = f.letter(6).value_or('V');
  g.mode_indicator = f.letter(7);
  return g;
}

}  // namespace headingd::nmea
