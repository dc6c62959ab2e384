// gpsd's JSON protocol from a peer that may send anything: the line framer and the report
// parser on arbitrary bytes, cut into chunks the input chooses. Invariants: every byte
// counted, no line beyond the bound handed on, the same lines whatever the chunking, and every
// TPV fix and GpsObservation made from it finite where set, its latitude within ±90°.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fuzz_check.hpp"
#include "headingd/gpsd/gpsd_report.hpp"
#include "headingd/gpsd/json_line_framer.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"

using namespace headingd;

namespace {

constexpr std::size_t kMaxLine = 4096;

std::vector<std::string> framedLines(std::span<const std::uint8_t> bytes, std::size_t chunk) {
  gpsd::JsonLineFramer framer(kMaxLine);
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < bytes.size(); i += chunk) {
    framer.feed(bytes.subspan(i, std::min(chunk, bytes.size() - i)), [&](std::string_view line) {
      FUZZ_CHECK(line.size() <= kMaxLine);
      lines.emplace_back(line);
    });
  }
  FUZZ_CHECK(framer.counters().bytes == bytes.size());
  return lines;
}

void checkTpv(const gpsd::TpvReport& tpv) {
  const nmea::Fix& f = tpv.fix;
  if (f.position) {
    FUZZ_CHECK(std::isfinite(f.position->lat_deg) && std::abs(f.position->lat_deg) <= 90.0);
    FUZZ_CHECK(std::isfinite(f.position->lon_deg));
  }
  const core::GpsObservation o = nmea::gpsObservationFromFix(f, 0);
  if (o.position) FUZZ_CHECK(std::isfinite(o.position->longitude_deg) && std::isfinite(o.position->height_km));
  if (o.course_rad) FUZZ_CHECK(std::isfinite(*o.course_rad));
  if (o.speed_mps) FUZZ_CHECK(std::isfinite(*o.speed_mps));
  if (o.magvar_rad) FUZZ_CHECK(std::isfinite(*o.magvar_rad));
  if (o.decimal_year) FUZZ_CHECK(std::isfinite(*o.decimal_year));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + data[0] % 64;  // the first byte sets the chunk length
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  const std::vector<std::string> whole = framedLines(bytes, bytes.size() + 1);
  FUZZ_CHECK(framedLines(bytes, chunk) == whole);
  for (const std::string& line : whole) {
    const gpsd::GpsdReport report = gpsd::parseGpsdReport(line);
    if (const auto* tpv = std::get_if<gpsd::TpvReport>(&report)) checkTpv(*tpv);
  }
  // The whole input as one line too (the parser is also given lines no framer cut).
  const gpsd::GpsdReport report = gpsd::parseGpsdReport(std::string_view(reinterpret_cast<const char*>(data), size));
  if (const auto* tpv = std::get_if<gpsd::TpvReport>(&report)) checkTpv(*tpv);
  return 0;
}
