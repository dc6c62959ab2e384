#pragma once
// The NMEA 0183 checksum: XOR of every character between the start character ('$' or '!')
// and '*', sent as two hex digits after the '*'.
#include <cstdint>
#include <string_view>

namespace headingd::nmea {

enum class ChecksumVerdict {
  kOk,
  kMissing,  // no '*' followed by exactly two hex digits at the end of the line
  kBad,      // present, but does not match
};

// XOR of all characters of body (the text between the start character and '*').
std::uint8_t checksumOf(std::string_view body);

// line runs from its start character through the checksum digits (no CR/LF). Hex digits may
// be lower case (Magellan EC-10X sends them so).
ChecksumVerdict verifyChecksum(std::string_view line);

}  // namespace headingd::nmea
