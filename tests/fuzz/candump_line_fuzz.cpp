// candump -l lines: parseCandumpLine on each line, and CandumpReader on the whole input.
// Invariants: a frame that parsed is a valid classic CAN frame; formatting it and parsing
// the result gives the same frame; the reader counts every line once.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/can/candump_log.hpp"

using namespace headingd;

namespace {

// A remote frame's DLC digit ("123#R4") is not written back: the log line says "R" only.
bool sameFrame(const can::CanFrame& a, const can::CanFrame& b) {
  if (a.id != b.id || a.extended != b.extended || a.error_frame != b.error_frame || a.remote != b.remote ||
      (!a.remote && a.len != b.len) || a.t_ns != b.t_ns) {
    return false;
  }
  for (std::size_t i = 0; i < a.len && !a.remote; ++i) {
    if (a.data[i] != b.data[i]) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string_view rest = text;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    const std::string_view line = rest.substr(0, end);
    rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + 1);
    std::string reason;
    const auto parsed = can::parseCandumpLine(line, &reason);
    if (!parsed) {
      FUZZ_CHECK(!reason.empty());
      continue;
    }
    const can::CanFrame& frame = parsed->frame;
    FUZZ_CHECK(frame.len <= 8);
    FUZZ_CHECK(frame.id <= (frame.extended || frame.error_frame ? 0x1FFFFFFFu : 0x7FFu));
    FUZZ_CHECK(frame.t_ns >= 0);
    const std::string formatted = can::formatCandumpLine(frame, parsed->interface);
    const auto again = can::parseCandumpLine(formatted);
    // Interface names longer than 15 characters are cut when formatted (IFNAMSIZ).
    FUZZ_CHECK(again.has_value());
    // The log keeps microseconds: the round trip drops what is below them.
    can::CanFrame expected = frame;
    expected.t_ns -= expected.t_ns % 1000;
    FUZZ_CHECK(sameFrame(again->frame, expected));
  }

  std::istringstream in(text);
  can::CandumpReader reader(in);
  std::uint64_t frames = 0;
  while (reader.next()) ++frames;
  const can::CandumpCounters& c = reader.counters();
  FUZZ_CHECK(c.frames == frames);
  FUZZ_CHECK(c.lines == c.frames + c.blank_lines + c.comment_lines + c.bad_lines);
  FUZZ_CHECK((c.bad_lines == 0) == (c.first_bad_line == 0));
  return 0;
}
