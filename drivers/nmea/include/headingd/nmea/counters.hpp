#pragma once
// Everything the parser counts, for STATUS reports and the dump tool. Framing counters come
// from the Framer; these are the ones about lines that passed the checksum.
#include <array>
#include <cstddef>
#include <cstdint>

#include "headingd/nmea/framer.hpp"
#include "headingd/nmea/sentence.hpp"

namespace headingd::nmea {

struct SentenceCounters {
  std::uint64_t ais = 0;                 // '!' lines (AIS): counted, not decoded
  std::uint64_t unsupported_talker = 0;  // proprietary or non-GNSS talker: ignored
  std::uint64_t unsupported_type = 0;    // GNSS talker, sentence we do not decode: ignored
  std::uint64_t malformed = 0;           // ours, but a field count NMEA does not allow
  std::uint64_t invalid_fields = 0;      // unparsable fields in decoded sentences (left out)
  std::uint64_t decoded = 0;             // the sum of the per-type counts
  std::array<std::uint64_t, kSentenceTypes.size()> decoded_by_type{};  // indexed by SentenceType

  std::uint64_t& decodedOf(SentenceType t) { return decoded_by_type[static_cast<std::size_t>(t)]; }
  std::uint64_t decodedOf(SentenceType t) const { return decoded_by_type[static_cast<std::size_t>(t)]; }
};

struct Counters {
  FramerCounters framing;
  SentenceCounters sentences;
};

// Calls fn(name, value) for every counter, in a fixed order, with stable snake_case names
// (a sentence type's count under its type in lower case: "gga").
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
  for (const SentenceType t : kSentenceTypes) fn(sentenceTypeCounterName(t), s.decodedOf(t));
}

}  // namespace headingd::nmea
