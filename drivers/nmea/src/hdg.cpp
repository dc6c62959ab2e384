#include "field_reader.hpp"

namespace headingd::nmea {
namespace {

// "x.x" with "E"/"W" in the next field, east positive; a value without its letter is unusable.
std::optional<double> eastWest(detail::FieldReader& f, std::size_t i) {
  const auto v = f.nonNegative(i);
  if (!v) return std::nullopt;
  if (f.raw(i + 1) == "E") return *v;
  if (f.raw(i + 1) == "W") return -*v;
  f.countInvalid();
  return std::nullopt;
}

}  // namespace

// $--HDG,x.x,x.x,a,x.x,a*hh
std::optional<Hdg> decodeHdg(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  if (f.dataFields() != 5) return std::nullopt;
  Hdg h;
  h.heading_deg = f.bearing(1);
  h.deviation_deg = eastWest(f, 2);
  h.variation_deg = eastWest(f, 4);
  return h;
}

}  // namespace headingd::nmea
