#pragma once
// Everything the parser counts, for STATUS reports and the dump tool. Framing counters come
// from the Framer; these are the ones about lines that passed the checksum.
#include <cstdint>

#include "headingd/nmea/framer.hpp"

namespace headingd::nmea {

struct SentenceCounters {
  std::uint64_t ais = 0;                 // '!' lines (AIS): counted, not decoded
  std::uint64_t unsupported_talker = 0;  // proprietary or non-GNSS talker: ignored
  std::uint64_t unsupported_type = 0;    // GNSS talker, sentence we do not decode: ignored
  std::uint64_t malformed = 0;           // ours, but a field count NMEA does not allow
  std::uint64_t invalid_fields = 0;      // unparsable fields in decoded sentences (left out)
  std::uint64_t decoded = 0;             // sum of the per-type counts below
  std::uint64_t gga = 0;
  std::uint64_t rmc = 0;
  std::uint64_t vtg = 0;
  std::uint64_t gns = 0;
  std::uint64_t gsa = 0;
  std::uint64_t gst = 0;
  std::uint64_t hdt = 0;
  std::uint64_t zda = 0;
  std::uint64_t gll = 0;
};

struct Counters {
  FramerCounters framing;
  SentenceCounters sentences;
};

// Calls fn(name, value) for every counter, in a fixed order, with stable snake_case names.
template <class Fn>
void forEachCounter(const Counters& c, Fn&& fn) {
  const auto& f = c.framing;
  fn("bytes", f.bytes);
  fn("lines", f.lines);
  fn("garbage_bytes", f.garbage_bytes);
  fn("binary_lines", f.binary_lines);
  fn("truncated", f.truncated);
  fn("overlong", f.overlong);
  fn("missing_checksum", f.missing_checksum);
  fn("bad_checksum", f.bad_checksum);
  const auto& s = c.sentences;
  fn("ais", s.ais);
  fn("unsupported_talker", s.unsupported_talker);
  fn("unsupported_type", s.unsupported_type);
  fn("malformed", s.malformed);
  fn("invalid_fields", s.invalid_fields);
  fn("decoded", s.decoded);
  fn("gga", s.gga);
  fn("rmc", s.rmc);
  fn("vtg", s.vtg);
  fn("gns", s.gns);
  fn("gsa", s.gsa);
  fn("gst", s.gst);
  fn("hdt", s.hdt);
  fn("zda", s.zda);
  fn("gll", s.gll);
}

}  // namespace headingd::nmea
