#include "headingd/nmea/framer.hpp"

#include "headingd/nmea/checksum.hpp"

namespace headingd::nmea {
namespace {

bool isStart(std::uint8_t b) { return b == '$' || b == '!'; }
bool isEndOfLine(std::uint8_t b) { return b == '\r' || b == '\n'; }
// NMEA sentences are printable ASCII; anything else on a line is binary data.
bool isText(std::uint8_t b) { return b >= 0x20 && b <= 0x7e; }

}  // namespace

Framer::Framer(FramerConfig config) : config_(config) {
  if (config_.max_line_length < 4) config_.max_line_length = 4;  // "$*HH" is the shortest frame
  line_.reserve(config_.max_line_length);
}

void Framer::startLine(std::uint8_t start) {
  line_.clear();
  line_.push_back(static_cast<char>(start));
  state_ = State::kInLine;
}

std::optional<std::string_view> Framer::push(std::uint8_t byte) {
  ++counters_.bytes;
  switch (state_) {
    case State::kHunting:
      if (isStart(byte)) {
        startLine(byte);
      } else if (!isEndOfLine(byte)) {
        ++counters_.garbage_bytes;
      }
      return std::nullopt;

    case State::kSkippingOverlong:
      // A start character cannot be inside a sentence, so it resynchronises at once.
      if (isStart(byte)) {
        startLine(byte);
      } else if (isEndOfLine(byte)) {
        state_ = State::kHunting;
      }
      return std::nullopt;

    case State::kInLine:
      if (isEndOfLine(byte)) return endLine();
      if (isStart(byte)) {
        // Lost the end of the previous line (dropped bytes, or a receiver that restarts
        // output mid-sentence); the new line may well be good. A lone start character
        // ("$$GPGGA", st-teseo-liv4f.log) lost nothing: it is just a stray byte.
        if (line_.size() == 1) {
          ++counters_.garbage_bytes;
        } else {
          ++counters_.truncated;
        }
        startLine(byte);
        return std::nullopt;
      }
      if (!isText(byte)) {
        ++counters_.binary_lines;
        ++counters_.garbage_bytes;
        line_.clear();
        state_ = State::kHunting;
        return std::nullopt;
      }
      if (line_.size() >= config_.max_line_length) {
        ++counters_.overlong;
        line_.clear();
        state_ = State::kSkippingOverlong;
        return std::nullopt;
      }
      line_.push_back(static_cast<char>(byte));
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<std::string_view> Framer::endLine() {
  state_ = State::kHunting;
  switch (verifyChecksum(line_)) {
    case ChecksumVerdict::kOk: ++counters_.lines; return std::string_view(line_);
    case ChecksumVerdict::kMissing: ++counters_.missing_checksum; break;
    case ChecksumVerdict::kBad: ++counters_.bad_checksum; break;
  }
  line_.clear();
  return std::nullopt;
}

void Framer::finish() {
  if (state_ == State::kInLine) ++counters_.truncated;
  line_.clear();
  state_ = State::kHunting;
}

}  // namespace headingd::nmea
