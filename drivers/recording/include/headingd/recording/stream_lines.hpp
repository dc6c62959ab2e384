#pragma once
// The lines of one stream of a recording folder, segment after segment
// (<stream>.000001.log, <stream>.000002.log, ...), without holding a file in memory. A line
// longer than files::kMaxLineBytes throws (a damaged segment must not grow memory).
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "headingd/files/line_reader.hpp"

namespace headingd::recording {

class StreamLines {
 public:
  // A stream with no segment at all is empty (a run without a GPS, say).
  StreamLines(std::string folder, std::string_view stream);

  // The next line (without its newline; valid until the next call); false at the end.
  bool next(std::string_view& line);
  // "<segment file>:<line>" of the line last returned, for messages.
  std::string where() const;
  // The first segment found: greater than 1 when the recorder's cap deleted the start.
  std::uint32_t firstSegment() const { return first_segment_; }
  std::uint32_t segments() const { return segments_; }

 private:
  bool openNext();

  std::string folder_;
  std::string stream_;
  std::unique_ptr<files::LineReader> in_;  // the open segment (regular files only, lines bounded)
  std::string path_;
  std::uint32_t first_segment_ = 0;
  std::uint32_t segment_ = 0;   // open segment's number, 0 = none yet
  std::uint32_t segments_ = 0;  // opened so far
  std::uint64_t line_number_ = 0;
};

}  // namespace headingd::recording
