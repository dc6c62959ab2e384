#include "field_reader.hpp"

namespace headingd::nmea {

// $--GSA,a,x,xx,xx,xx,xx,xx,xx,xx,xx,xx,xx,xx,xx,x.x,x.x,x.x[,id]*hh
std::optional<Gsa> decodeGsa(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  // 12 PRN slots (17 data fields, 18 with the NMEA 4.1 system ID); the Navior-24 sends 24.
  std::size_t prn_slots = 0;
  switch (f.dataFields()) {
    case 17:
    case 18: prn_slots = 12; break;
    case 29:
    case 30: prn_slots = 24; break;
    default: return std::nullopt;
  }
  Gsa g;
  g.selection = f.letter(1);
  g.fix_mode = f.integer(2);
  if (g.fix_mode && (*g.fix_mode < 1 || *g.fix_mode > 3)) {
    f.countInvalid();
    g.fix_mode.reset();
  }
  for (std::size_t i = 0; i < prn_slots; ++i) {
    if (f.integer(3 + i)) ++g.satellites_listed;
  }
  const std::size_t dop = 3 + prn_slots;
  g.pdop = f.nonNegative(dop);
  g.hdop = f.nonNegative(dop + 1);
  g.vdop = f.nonNegative(dop + 2);
  if (f.dataFields() == dop + 3) g.system_id = f.integer(dop + 3);
  return g;
}

}  // namespace headingd::nmea
