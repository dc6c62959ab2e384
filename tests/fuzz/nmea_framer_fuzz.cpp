// NMEA byte stream: Framer and Parser on arbitrary bytes, cut into chunks the input chooses.
// Invariants: every byte counted, the buffer bounded, the same lines whatever the chunking
// (byte by byte and all at once), every good line decoded or counted as not decoded, and
// every GpsObservation made from a fix finite where it is set.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string_view>
#include <vector>

#include "fuzz_check.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"
#include "headingd/nmea/parser.hpp"

using namespace headingd;

namespace {

void checkObservation(const core::GpsObservation& o) {
  if (o.position) {
    FUZZ_CHECK(std::isfinite(o.position->latitude_deg) && std::abs(o.position->latitude_deg) <= 90.0);
    FUZZ_CHECK(std::isfinite(o.position->longitude_deg) && std::isfinite(o.position->height_km));
  }
  if (o.decimal_year) FUZZ_CHECK(std::isfinite(*o.decimal_year));
  if (o.course_rad) FUZZ_CHECK(std::isfinite(*o.course_rad));
  if (o.speed_mps) FUZZ_CHECK(std::isfinite(*o.speed_mps));
  if (o.hdop) FUZZ_CHECK(std::isfinite(*o.hdop));
  if (o.magvar_rad) FUZZ_CHECK(std::isfinite(*o.magvar_rad));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte sets the chunk length (1..64) of the chunked feed.
  const std::size_t chunk = 1 + data[0] % 64;
  const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);

  nmea::Parser whole;
  std::vector<nmea::FixUpdate> whole_updates;
  whole.feed(bytes, whole_updates);
  whole.finish();

  nmea::Parser chunked;
  std::vector<nmea::FixUpdate> chunked_updates;
  for (std::size_t i = 0; i < bytes.size(); i += chunk) {
    chunked.feed(bytes.substr(i, chunk), chunked_updates);
    FUZZ_CHECK(chunked.buffered() <= nmea::FramerConfig{}.max_line_length);
  }
  chunked.finish();

  FUZZ_CHECK(whole_updates.size() == chunked_updates.size());
  for (std::size_t i = 0; i < whole_updates.size(); ++i) {
    FUZZ_CHECK(whole_updates[i].sentence == chunked_updates[i].sentence);
    checkObservation(nmea::gpsObservationFromFix(whole_updates[i].fix, static_cast<std::int64_t>(i)));
  }

  const nmea::Counters c = whole.counters();
  FUZZ_CHECK(c.framing.bytes == bytes.size());
  const auto& s = c.sentences;
  FUZZ_CHECK(c.framing.lines == s.ais + s.unsupported_talker + s.unsupported_type + s.malformed + s.decoded);
  FUZZ_CHECK(s.decoded == std::accumulate(s.decoded_by_type.begin(), s.decoded_by_type.end(), std::uint64_t{0}));
  FUZZ_CHECK(s.decoded == whole_updates.size());
  return 0;
}
