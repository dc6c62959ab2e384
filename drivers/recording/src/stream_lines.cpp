#include "headingd/recording/stream_lines.hpp"

#include <charconv>
#include <filesystem>

#include "headingd/recording/recording_format.hpp"

namespace headingd::recording {

StreamLines::StreamLines(std::string folder, std::string_view stream) : folder_(std::move(folder)), stream_(stream) {
  // The lowest segment number present: the cap deletes a long recording's oldest segments.
  std::error_code ec;
  const std::string prefix = stream_ + ".";
  for (const auto& entry : std::filesystem::directory_iterator(folder_, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != prefix.size() + 10 || name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - 4, 4, ".log") != 0) {
      continue;
    }
    std::uint32_t n = 0;
    const char* digits = name.data() + prefix.size();
    const auto [end, err] = std::from_chars(digits, digits + 6, n);
    if (err != std::errc() || end != digits + 6 || n == 0) continue;
    if (first_segment_ == 0 || n < first_segment_) first_segment_ = n;
  }
}

bool StreamLines::openNext() {
  if (first_segment_ == 0) return false;
  const std::uint32_t n = segment_ == 0 ? first_segment_ : segment_ + 1;
  const std::string path = segmentPath(folder_, stream_, n);
  if (!std::filesystem::exists(path)) return false;
  in_ = std::make_unique<files::LineReader>(path);
  path_ = path;
  segment_ = n;
  ++segments_;
  line_number_ = 0;
  return true;
}

bool StreamLines::next(std::string_view& line) {
  while (true) {
    if (in_ != nullptr && in_->next(&line)) {
      ++line_number_;
      return true;
    }
    if (!openNext()) return false;
  }
}

std::string StreamLines::where() const { return path_ + ":" + std::to_string(line_number_); }

}  // namespace headingd::recording
