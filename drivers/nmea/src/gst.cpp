#include "field_reader.hpp"

namespace headingd::nmea {

// $--GST,hhmmss.ss,rms,smaj,smin,orient,slat,slon,salt*hh
std::optional<Gst> decodeGst(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  if (f.dataFields() != 8) return std::nullopt;
  Gst g;
  g.time_of_day_ns = f.timeOfDay(1);
  g.rms_m = f.nonNegative(2);
  g.semi_major_m = f.nonNegative(3);
  g.semi_minor_m = f.nonNegative(4);
  g.orientation_deg = f.bearing(5);
  g.lat_sigma_m = f.nonNegative(6);
  g.lon_sigma_m = f.nonNegative(7);
  g.alt_sigma_m = f.nonNegative(8);
  return g;
}

}  // namespace headingd::nmea
