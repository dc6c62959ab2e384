#include "field_reader.hpp"

namespace headingd::nmea {

// $--THS,x.x,a*hh
std::optional<Ths> decodeThs(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  if (f.dataFields() != 2) return std::nullopt;
  Ths t;
  t.heading_deg = f.bearing(1);
  t.mode = f.letter(2);
  if (t.mode && std::string_view("AEMSV").find(*t.mode) == std::string_view::npos) {
    f.countInvalid();
    t.mode.reset();
  }
  return t;
}

}  // namespace headingd::nmea
