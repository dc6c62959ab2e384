#pragma once
// Splits gpsd's byte stream into lines ("\n"-terminated, a "\r" before it dropped), with a
// bound on a line's length: a longer one is counted and skipped up to its end, so a peer that
// never sends a newline costs at most max_line_bytes of memory.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace headingd::gpsd {

struct LineCounters {
  std::uint64_t bytes = 0;
  std::uint64_t lines = 0;      // complete lines handed on
  std::uint64_t oversized = 0;  // lines longer than the bound, skipped
  std::uint64_t cut = 0;        // lines the stream ended in the middle of (connection closed)
};

class JsonLineFramer {
 public:
  explicit JsonLineFramer(std::size_t max_line_bytes) : max_line_bytes_(max_line_bytes) {}

  // Calls on_line(std::string_view) for each complete line in `bytes`, in order.
  template <class OnLine>
  void feed(std::span<const std::uint8_t> bytes, OnLine&& on_line) {
    counters_.bytes += bytes.size();
    for (const std::uint8_t b : bytes) {
      if (b == '\n') {
        if (skipping_) {
          skipping_ = false;
        } else {
          if (!line_.empty() && line_.back() == '\r') line_.pop_back();
          ++counters_.lines;
          on_line(std::string_view(line_));
        }
        line_.clear();
        continue;
      }
      if (skipping_) continue;
      if (line_.size() >= max_line_bytes_) {
        ++counters_.oversized;
        skipping_ = true;
        line_.clear();
        continue;
      }
      line_.push_back(static_cast<char>(b));
    }
  }
  // The stream ended (closed, reconnecting): a partial line is dropped and counted; true if
  // there was one.
  bool endOfStream() {
    const bool cut = !line_.empty() && !skipping_;
    if (cut) ++counters_.cut;
    line_.clear();
    skipping_ = false;
    return cut;
  }
  const LineCounters& counters() const { return counters_; }

 private:
  std::size_t max_line_bytes_;
  std::string line_;
  bool skipping_ = false;
  LineCounters counters_;
};

}  // namespace headingd::gpsd
