#include "field_reader.hpp"

namespace headingd::nmea {

// $--VTG,x.x,T,x.x,M,x.x,N,x.x,K[,m]*hh
std::optional<Vtg> decodeVtg(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  if (f.dataFields() < 8 || f.dataFields() > 9) return std::nullopt;
  Vtg v;
  v.course_deg = f.bearing(1);
  v.course_magnetic_deg = f.bearing(3);
  const auto knots = f.nonNegative(5);
  const auto kmh = f.nonNegative(7);
  if (knots) {
    v.speed_mps = *knots * kKnotToMps;
  } else if (kmh) {
    v.speed_mps = *kmh * kKmhToMps;
  }
  v.mode_indicator = f.letter(9);
  return v;
}

}  // namespace headingd::nmea
