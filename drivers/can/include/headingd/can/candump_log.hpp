#pragma once
// The `candump -l` log format of can-utils, one frame a line:
//   (1700000000.123456) can0 123#DEADBEEF
//   (1700000000.123789) can0 18F02A80#0102030405060708      (extended: 8 hex digits)
//   (1700000000.124000) can0 123#R                          (remote request)
//   (1700000000.125000) can0 20000004#0000080000000000      (error frame: CAN_ERR_FLAG set)
// Pure parsing and formatting; a bad line is reported with the reason, never thrown.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <string_view>

#include "headingd/can/can_frame.hpp"

namespace headingd::can {

struct LoggedFrame {
  CanFrame frame;              // t_ns holds the logged time (the log's clock, microseconds resolution)
  std::string_view interface;  // points into the parsed line
};

// nullopt for a line that is not a classic CAN frame; `reason` (if given) then says what was
// expected. CAN FD lines ("##") are reported as unsupported.
std::optional<LoggedFrame> parseCandumpLine(std::string_view line, std::string* reason = nullptr);

// The line without a trailing newline, in the format above (timestamp with 6 decimals).
std::string formatCandumpLine(const CanFrame& frame, std::string_view interface);
// The same into `out` without allocating (for a real-time thread): returns its length. An
// interface name of up to 15 characters (IFNAMSIZ - 1) fits kCandumpLineMaxBytes.
inline constexpr std::size_t kCandumpLineMaxBytes = 80;
std::size_t formatCandumpLine(const CanFrame& frame, std::string_view interface, char (&out)[kCandumpLineMaxBytes]);

struct CandumpCounters {
  std::uint64_t lines = 0;
  std::uint64_t frames = 0;
  std::uint64_t blank_lines = 0;
  std::uint64_t comment_lines = 0;  // starting with '#': notes, e.g. a black-box recording's events
  std::uint64_t bad_lines = 0;
  std::uint64_t first_bad_line = 0;  // line number (1-based), 0 if none
  std::string first_bad_reason;
};

// Reads a log line by line, counting what it skips.
class CandumpReader {
 public:
  explicit CandumpReader(std::istream& in) : in_(in) {}
  // The next frame, or nullopt at the end of the input.
  std::optional<CanFrame> next();
  const CandumpCounters& counters() const { return counters_; }

 private:
  std::istream& in_;
  std::string line_;
  CandumpCounters counters_;
};

}  // namespace headingd::can
