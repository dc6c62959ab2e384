#pragma once
// Decoded sentences, one value type per sentence, holding what the receiver sent (units
// converted to SI/degrees, hemispheres applied) without judging it: whether a position is a
// fix is the FixAccumulator's call. Absent or unparsable fields are nullopt.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <variant>

#include "headingd/nmea/fields.hpp"
#include "headingd/nmea/sentence.hpp"

namespace headingd::nmea {

struct Position {
  double lat_deg = 0.0;  // WGS 84, north positive
  double lon_deg = 0.0;  // east positive
};

// FAA mode indicator (NMEA 2.3+): A autonomous, D differential, E estimated (dead reckoning),
// F float RTK, M manual, N not valid, P precise, R RTK, S simulator.
inline bool modeIndicatorIsValid(char m) { return m != 'N' && m != 'V'; }

// Global positioning system fix data.
struct Gga {
  std::optional<std::int64_t> time_of_day_ns;
  std::optional<Position> position;
  std::optional<int> quality;  // 0 no fix, 1 GPS, 2 DGPS, 3 PPS, 4 RTK, 5 float RTK, 6 DR, 7 manual, 8 sim
  std::optional<int> satellites_used;
  std::optional<double> hdop;
  std::optional<double> alt_msl_m;
  std::optional<double> geoid_separation_m;  // ellipsoid height minus MSL height
  std::optional<double> dgps_age_s;
  std::optional<int> dgps_station;
};

// Recommended minimum specific GNSS data.
struct Rmc {
  std::optional<std::int64_t> time_of_day_ns;
  char status = 'V';  // 'A' valid, 'V' navigation receiver warning
  std::optional<Position> position;
  std::optional<double> speed_mps;
  std::optional<double> course_deg;  // over ground, true
  std::optional<DayMonthYy> date;
  std::optional<double> magvar_deg;    // magnetic variation, east positive
  std::optional<char> mode_indicator;  // NMEA 2.3+
  std::optional<char> nav_status;      // NMEA 4.1+
};

// Geographic position, latitude/longitude.
struct Gll {
  std::optional<Position> position;
  std::optional<std::int64_t> time_of_day_ns;
  char status = 'V';                   // 'A' valid, 'V' invalid
  std::optional<char> mode_indicator;  // NMEA 2.3+
};

// Course over ground and ground speed.
struct Vtg {
  std::optional<double> course_deg;  // true
  std::optional<double> course_magnetic_deg;
  std::optional<double> speed_mps;     // from knots, or km/h when knots are absent
  std::optional<char> mode_indicator;  // NMEA 2.3+
};

// GNSS fix data, one mode indicator per constellation (GPS, GLONASS, Galileo, BeiDou, QZSS,
// NavIC).
struct Gns {
  std::optional<std::int64_t> time_of_day_ns;
  std::optional<Position> position;
  std::array<char, 8> mode_indicators{};  // NUL-padded
  std::optional<int> satellites_used;
  std::optional<double> hdop;
  std::optional<double> alt_msl_m;
  std::optional<double> geoid_separation_m;
  std::optional<double> dgps_age_s;
  std::optional<int> dgps_station;
  std::optional<char> nav_status;  // NMEA 4.1+: S safe, C caution, U unsafe, V not valid
};

// DOP and active satellites. Multi-constellation receivers send one per constellation.
struct Gsa {
  std::optional<char> selection;  // 'M' manual, 'A' automatic 2D/3D
  std::optional<int> fix_mode;    // 1 no fix, 2 2D, 3 3D
  int satellites_listed = 0;      // non-empty PRN fields
  std::optional<double> pdop;
  std::optional<double> hdop;
  std::optional<double> vdop;
  std::optional<int> system_id;  // NMEA 4.1+
};

// Pseudorange error statistics (1-sigma, metres).
struct Gst {
  std::optional<std::int64_t> time_of_day_ns;  // of the fix these statistics belong to
  std::optional<double> rms_m;
  std::optional<double> semi_major_m;
  std::optional<double> semi_minor_m;
  std::optional<double> orientation_deg;
  std::optional<double> lat_sigma_m;
  std::optional<double> lon_sigma_m;
  std::optional<double> alt_sigma_m;
};

// True heading (from a dual-antenna receiver or gyro compass).
struct Hdt {
  std::optional<double> heading_deg;
};

// True heading with a mode indicator (THS, NMEA 0183 3.0: A autonomous, E estimated, M
// manual, S simulator, V not valid). Heading sensors send it, not GNSS receivers: decoded
// by decodeThs on its own, not by decodeSentence (headingd's [nmea_out] is checked with it).
struct Ths {
  std::optional<double> heading_deg;
  std::optional<char> mode;
};

// Magnetic sensor heading, deviation and variation (HDG), east positive; decoded by
// decodeHdg on its own, as THS.
struct Hdg {
  std::optional<double> heading_deg;
  std::optional<double> deviation_deg;
  std::optional<double> variation_deg;
};

// UTC date and time with a four-digit year.
struct Zda {
  std::optional<std::int64_t> time_of_day_ns;
  std::optional<int> day;
  std::optional<int> month;
  std::optional<int> year;
  std::optional<int> zone_hours;
  std::optional<int> zone_minutes;
};

using SentenceData = std::variant<Gga, Rmc, Vtg, Gns, Gsa, Gst, Hdt, Zda, Gll>;

struct DecodedSentence {
  Talker talker = Talker::kGP;
  SentenceType type = SentenceType::kGGA;
  SentenceData data;
  int invalid_fields = 0;  // fields present but unparsable or out of range (left nullopt)
};

enum class DecodeStatus {
  kDecoded,
  kUnsupportedTalker,  // proprietary ($P...) or a talker not in Talker
  kUnsupportedType,    // known talker, sentence not in SentenceType (GSV, TXT, ...)
  kMalformed,          // ours, but the field count is not one NMEA 0183 allows
};

struct DecodeResult {
  DecodeStatus status = DecodeStatus::kMalformed;
  std::optional<DecodedSentence> sentence;  // set iff kDecoded
};

// Decodes a line that passed verifyChecksum() ('$' lines; '!' lines are not sentences).
DecodeResult decodeSentence(std::string_view line);

// One decoder per sentence type; fields.field(0) is the address. Each returns nullopt when
// the field count is not one NMEA 0183 allows (two sentences run together, a cut-off line
// whose checksum happens to match, a firmware bug), and counts unusable fields otherwise.
std::optional<Gga> decodeGga(const FieldList& f, int& invalid_fields);
std::optional<Rmc> decodeRmc(const FieldList& f, int& invalid_fields);
std::optional<Vtg> decodeVtg(const FieldList& f, int& invalid_fields);
std::optional<Gns> decodeGns(const FieldList& f, int& invalid_fields);
std::optional<Gsa> decodeGsa(const FieldList& f, int& invalid_fields);
std::optional<Gst> decodeGst(const FieldList& f, int& invalid_fields);
std::optional<Hdt> decodeHdt(const FieldList& f, int& invalid_fields);
std::optional<Zda> decodeZda(const FieldList& f, int& invalid_fields);
std::optional<Ths> decodeThs(const FieldList& f, int& invalid_fields);
std::optional<Hdg> decodeHdg(const FieldList& f, int& invalid_fields);
std::optional<Gll> decodeGll(const FieldList& f, int& invalid_fields);

}  // namespace headingd::nmea
