#pragma once
// Byte stream in, checksummed NMEA 0183 lines out. Pure: no I/O, no clock; the caller pushes
// whatever chunks its serial port or file gives it, and gets the same lines whatever the
// chunking. Every byte that does not end up in a good line is counted for the status
// report: bad input is never dropped silently.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace headingd::nmea {

struct FramerConfig {
  // Longest line accepted, from '$' (or '!') through the two checksum digits, CR/LF not
  // counted. NMEA 0183 says 82 with CR/LF, but real receivers exceed it (Skytraq $PSTI,
  // survey-grade GGA with 8 decimals of minutes: 117 in the gpsd corpus). The buffer never
  // grows beyond this, so it also bounds memory.
  std::size_t max_line_length = 120;
};

struct FramerCounters {
  std::uint64_t bytes = 0;             // every byte pushed
  std::uint64_t lines = 0;             // good lines handed out ('$' and '!')
  std::uint64_t garbage_bytes = 0;     // bytes outside any line (binary packets, junk text)
  std::uint64_t binary_lines = 0;      // a line broken off by a non-text byte (binary on the line)
  std::uint64_t truncated = 0;         // a line cut short by the next '$'/'!' or by end of stream
  std::uint64_t overlong = 0;          // longer than max_line_length: skipped to its end
  std::uint64_t missing_checksum = 0;  // ended without a trailing "*HH"
  std::uint64_t bad_checksum = 0;      // "*HH" does not match the XOR of the body
};

class Framer {
 public:
  explicit Framer(FramerConfig config = {});

  // Takes one byte. Returns a complete line that passed the checksum check (from its '$' or
  // '!' through "*HH", without CR/LF) when this byte ends one; the view stays valid until the
  // next push(). Framing is on CR or LF, either or both.
  std::optional<std::string_view> push(std::uint8_t byte);

  // End of stream: a line still open is counted as truncated and dropped.
  void finish();

  const FramerCounters& counters() const { return counters_; }
  std::size_t buffered() const { return line_.size(); }  // never above max_line_length

 private:
  enum class State { kHunting, kInLine, kSkippingOverlong };

  void startLine(std::uint8_t start);
  std::optional<std::string_view> endLine();

  FramerConfig config_;
  State state_ = State::kHunting;
  std::string line_;  // capacity reserved once: no allocation per line
  FramerCounters counters_;
};

}  // namespace headingd::nmea
