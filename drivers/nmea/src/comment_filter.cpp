#include "headingd/nmea/comment_filter.hpp"

namespace headingd::nmea {

void CommentFilter::filter(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out) {
  for (const std::uint8_t b : bytes) {
    if (in_comment_) {
      if (b == '\n') {
        in_comment_ = false;
        at_line_start_ = true;
        ++comment_bytes_;
        continue;
      }
      if ((b >= 0x20 && b <= 0x7e) || b == '\r' || b == '\t') {
        ++comment_bytes_;
        continue;
      }
      in_comment_ = false;  // binary: not a comment any more; the byte goes to the parser
    } else if (at_line_start_ && b == '#') {
      in_comment_ = true;
      ++comment_lines_;
      ++comment_bytes_;
      continue;
    }
    out.push_back(b);
    at_line_start_ = b == '\n' || b == '\r';
  }
}

}  // namespace headingd::nmea
