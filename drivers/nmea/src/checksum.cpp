#include "headingd/nmea/checksum.hpp"

#include <optional>

namespace headingd::nmea {
namespace {

std::optional<std::uint8_t> hexValue(char c) {
  if (c >= '0' && c <= '9') return static_cast<std::uint8_t>(c - '0');
  if (c >= 'A' && c <= 'F') return static_cast<std::uint8_t>(c - 'A' + 10);
  if (c >= 'a' && c <= 'f') return static_cast<std::uint8_t>(c - 'a' + 10);
  return std::nullopt;
}

}  // namespace

std::uint8_t checksumOf(std::string_view body) {
  std::uint8_t sum = 0;
  for (const char c : body) sum ^= static_cast<std::uint8_t>(c);
  return sum;
}

ChecksumVerdict verifyChecksum(std::string_view line) {
  // Shortest frame: start character, '*', two digits.
  if (line.size() < 4 || line[line.size() - 3] != '*') return ChecksumVerdict::kMissing;
  const auto hi = hexValue(line[line.size() - 2]);
  const auto lo = hexValue(line[line.size() - 1]);
  if (!hi || !lo) return ChecksumVerdict::kMissing;
  const std::string_view body = line.substr(1, line.size() - 4);
  return checksumOf(body) == ((*hi << 4) | *lo) ? ChecksumVerdict::kOk : ChecksumVerdict::kBad;
}

}  // namespace headingd::nmea
