#pragma once
// gpsd's capture files (../shared/data/gpsd-logs) carry '#' comment lines that were never
// on the wire. The parser sees only wire bytes, so readers of those files pass them through
// this filter first. A comment starts with '#' at the beginning of a line and ends at LF;
// like gpsd, a non-text byte also ends it (comments are text, binary data after a stray
// "\n#" must not be swallowed).
#include <cstdint>
#include <span>
#include <vector>

namespace headingd::nmea {

class CommentFilter {
 public:
  // Appends the non-comment bytes to out.
  void filter(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out);

  std::uint64_t commentLines() const { return comment_lines_; }
  std::uint64_t commentBytes() const { return comment_bytes_; }

 private:
  bool at_line_start_ = true;
  bool in_comment_ = false;
  std::uint64_t comment_lines_ = 0;
  std::uint64_t comment_bytes_ = 0;
};

}  // namespace headingd::nmea
