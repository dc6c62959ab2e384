// NMEA sentences: each input line becomes "$<line>*HH" with its correct checksum, so the
// decoders and the fix accumulator see the fields (the framer fuzz target rarely gets past
// the checksum). Invariants: decoding never throws; a decoded sentence's type matches its
// data; every fix turns into a finite GpsObservation.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/nmea/checksum.hpp"
#include "headingd/nmea/fix_accumulator.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"
#include "headingd/nmea/sentences.hpp"

using namespace headingd;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  nmea::FixAccumulator accumulator;
  std::int64_t epoch = 0;
  while (!input.empty()) {
    const std::size_t end = input.find('\n');
    std::string_view body = input.substr(0, end);
    input.remove_prefix(end == std::string_view::npos ? input.size() : end + 1);
    if (!body.empty() && body.front() == '$') body.remove_prefix(1);
    if (const std::size_t star = body.rfind('*'); star != std::string_view::npos) body = body.substr(0, star);

    char checksum[4];
    std::snprintf(checksum, sizeof checksum, "*%02X", nmea::checksumOf(body));
    const std::string line = "$" + std::string(body) + checksum;
    FUZZ_CHECK(nmea::verifyChecksum(line) == nmea::ChecksumVerdict::kOk);

    const nmea::DecodeResult r = nmea::decodeSentence(line);
    FUZZ_CHECK((r.status == nmea::DecodeStatus::kDecoded) == r.sentence.has_value());
    if (!r.sentence) continue;
    FUZZ_CHECK(r.sentence->invalid_fields >= 0);
    FUZZ_CHECK(static_cast<std::size_t>(r.sentence->data.index()) == static_cast<std::size_t>(r.sentence->type));
    accumulator.apply(*r.sentence);

    const nmea::Fix& fix = accumulator.fix();
    if (fix.course_deg) FUZZ_CHECK(*fix.course_deg >= 0.0 && *fix.course_deg < 360.0);
    if (fix.heading_deg) FUZZ_CHECK(*fix.heading_deg >= 0.0 && *fix.heading_deg < 360.0);
    const core::GpsObservation o = nmea::gpsObservationFromFix(fix, ++epoch);
    if (o.position) {
      FUZZ_CHECK(std::abs(o.position->latitude_deg) <= 90.0 && std::isfinite(o.position->longitude_deg));
      FUZZ_CHECK(std::isfinite(o.position->height_km));
    }
    if (o.decimal_year) FUZZ_CHECK(std::isfinite(*o.decimal_year));
    if (o.speed_mps) FUZZ_CHECK(std::isfinite(*o.speed_mps));
    if (o.hdop) FUZZ_CHECK(std::isfinite(*o.hdop));
    if (o.magvar_rad) FUZZ_CHECK(std::isfinite(*o.magvar_rad));
  }
  return 0;
}
