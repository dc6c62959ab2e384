// One decoder per sentence type, in the order of sentences.hpp: each checks the field count
// its sentence may have and reads the fields through FieldReader, which counts present but
// unusable fields. Each decoder is headed by its sentence's field layout (NMEA 0183).
#include <cmath>

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

// $--ZDA,hhmmss.ss,dd,mm,yyyy,zh,zm*hh
std::optional<Zda> decodeZda(const FieldList& fields, int& invalid_fields) {
  detail::FieldReader f(fields, invalid_fields);
  if (f.dataFields() != 6) return std::nullopt;
  Zda z;
  z.time_of_day_ns = f.timeOfDay(1);
  z.day = f.integer(2);
  z.month = f.integer(3);
  z.year = f.integer(4);
  if ((z.day && (*z.day < 1 || *z.day > 31)) || (z.month && (*z.month < 1 || *z.month > 12)) ||
      (z.year && (*z.year < 1980 || *z.year > 2200))) {
    // A date before GPS existed or out of range: keep the time, drop the date.
    f.countInvalid();
    z.day.reset();
    z.month.reset();
    z.year.reset();
  }
  // The local zone may be signed ("-05"); zones run from -12 to +14 hours. Anything beyond is
  // a bad field (and must not reach the int conversion: 1e50 does not fit; found by fuzzing).
  if (const auto h = f.decimal(5)) {
    if (std::abs(*h) <= 14.0) {
      z.zone_hours = static_cast<int>(*h);
    } else {
      f.countInvalid();
    }
  }
  z.zone_minutes = f.integer(6);
  return z;
}

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
