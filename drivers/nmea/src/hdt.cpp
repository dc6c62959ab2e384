#include "field_reader.hpp"

namespace headingd::nmea {

// $--HDT,x.x,T*hh
std::optional<Hdt> decodeHdt(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  if (f.dataFields() != 2) return std::nullopt;
  Hdt h;
  h.heading_deg = f.bearing(1);
  if (h.heading_deg && f.raw(2) != "T") {
    // Only 'T' is defined; anything else leaves the reference unknown.
    f.countInvalid();
    h.heading_deg.reset();
  }
  return h;
}

}  // namespace headingd::nmea
