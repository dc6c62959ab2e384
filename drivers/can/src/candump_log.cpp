#include "headingd/can/candump_log.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace headingd::can {
namespace {

constexpr std::uint32_t kErrFlag = 0x20000000u;  // CAN_ERR_FLAG in linux/can.h
constexpr std::uint32_t kErrMask = 0x1FFFFFFFu;

bool fail(std::string* reason, const char* what) {
  if (reason != nullptr) *reason = what;
  return false;
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string_view nextField(std::string_view& s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  std::size_t n = 0;
  while (n < s.size() && s[n] != ' ' && s[n] != '\t' && s[n] != '\r') ++n;
  std::string_view field = s.substr(0, n);
  s.remove_prefix(n);
  return field;
}

// "(seconds.fraction)" -> nanoseconds.
bool parseTime(std::string_view t, std::int64_t& ns, std::string* reason) {
  if (t.size() < 3 || t.front() != '(' || t.back() != ')') return fail(reason, "a timestamp '(seconds.microseconds)'");
  t = t.substr(1, t.size() - 2);
  const std::size_t dot = t.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 >= t.size() || t.size() - dot - 1 > 9) {
    return fail(reason, "a timestamp '(seconds.microseconds)'");
  }
  // from_chars takes "-0" for 0: a sign would turn (-0.5) into +0.5 s. candump writes none.
  if (t.front() < '0' || t.front() > '9') return fail(reason, "a timestamp '(seconds.microseconds)' without a sign");
  std::int64_t seconds = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + dot, seconds);
  if (ec != std::errc() || end != t.data() + dot || seconds < 0 || seconds > 9'000'000'000) {
    return fail(reason, "a timestamp '(seconds.microseconds)' with plausible seconds");
  }
  std::int64_t fraction_ns = 0;
  std::int64_t scale = 100'000'000;
  for (char c : t.substr(dot + 1)) {
    if (c < '0' || c > '9') return fail(reason, "digits after the timestamp's '.'");
    fraction_ns += (c - '0') * scale;
    scale /= 10;
  }
  ns = seconds * 1'000'000'000 + fraction_ns;
  return true;
}

bool parseFrame(std::string_view f, CanFrame& frame, std::string* reason) {
  const std::size_t hash = f.find('#');
  if (hash == std::string_view::npos) return fail(reason, "a frame 'ID#DATA'");
  const std::string_view id_text = f.substr(0, hash);
  std::string_view data = f.substr(hash + 1);
  if (!data.empty() && data.front() == '#') return fail(reason, "a classic CAN frame (CAN FD '##' is not supported)");
  if (id_text.size() != 3 && id_text.size() != 8)
    return fail(reason, "an id of 3 (standard) or 8 (extended) hex digits");
  std::uint32_t id = 0;
  for (char c : id_text) {
    const int v = hexValue(c);
    if (v < 0) return fail(reason, "hex digits in the id");
    id = (id << 4) | static_cast<std::uint32_t>(v);
  }
  if (id_text.size() == 3) {
    if (id > kStandardIdMask) return fail(reason, "a standard id up to 7FF");
    frame.id = id;
  } else if (id > 0x3FFFFFFFu) {
    return fail(reason, "an extended id up to 1FFFFFFF (or an error frame with 20000000 set)");
  } else if ((id & kErrFlag) != 0) {
    frame.error_frame = true;
    frame.extended = false;
    frame.id = id & kErrMask;
  } else {
    if (id > kExtendedIdMask) return fail(reason, "an extended id up to 1FFFFFFF");
    frame.extended = true;
    frame.id = id;
  }
  if (!data.empty() && (data.front() == 'R' || data.front() == 'r')) {
    frame.remote = true;
    data.remove_prefix(1);
    // "R" optionally followed by a DLC digit; a remote frame carries no data.
    if (data.size() == 1 && data.front() >= '0' && data.front() <= '8') {
      frame.len = static_cast<std::uint8_t>(data.front() - '0');
      return true;
    }
    if (!data.empty()) return fail(reason, "nothing or a DLC digit after 'R'");
    return true;
  }
  // "_X" after 8 bytes: a raw DLC 9..15 (len8_dlc); the length stays 8.
  const std::size_t underscore = data.find('_');
  if (underscore != std::string_view::npos) {
    if (underscore != 16 || data.size() != 18 || hexValue(data[17]) < 9) {
      return fail(reason, "'_' only after 8 data bytes, followed by a DLC 9..F");
    }
    data = data.substr(0, 16);
  }
  std::size_t n = 0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (data[i] == '.') continue;  // candump -l never writes it, but cansend accepts separators
    const int v = hexValue(data[i]);
    if (v < 0) return fail(reason, "hex data bytes after '#'");
    if (n >= 2 * kClassicMaxLen) return fail(reason, "at most 8 data bytes");
    if (n % 2 == 0)
      frame.data[n / 2] = static_cast<std::uint8_t>(v << 4);
    else
      frame.data[n / 2] = static_cast<std::uint8_t>(frame.data[n / 2] | v);
    ++n;
  }
  if (n % 2 != 0) return fail(reason, "an even number of hex digits (whole bytes)");
  frame.len = static_cast<std::uint8_t>(n / 2);
  return true;
}

}  // namespace

std::optional<LoggedFrame> parseCandumpLine(std::string_view line, std::string* reason) {
  LoggedFrame out;
  std::string_view rest = line;
  if (!parseTime(nextField(rest), out.frame.t_ns, reason)) return std::nullopt;
  out.interface = nextField(rest);
  // Linux interface names are printable: a control byte there (a NUL, say) is corruption,
  // and would cut the name short when the line is written again.
  const bool printable = std::all_of(out.interface.begin(), out.interface.end(),
                                     [](char c) { return static_cast<unsigned char>(c) > ' ' && c != 0x7F; });
  if (out.interface.empty() || !printable) {
    fail(reason, "an interface name after the timestamp");
    return std::nullopt;
  }
  if (!parseFrame(nextField(rest), out.frame, reason)) return std::nullopt;
  // Newer candump versions may add a direction flag (T/R); anything else is an error.
  const std::string_view extra = nextField(rest);
  if (!(extra.empty() || extra == "T" || extra == "R") || !nextField(rest).empty()) {
    fail(reason, "end of line after the frame");
    return std::nullopt;
  }
  return out;
}

std::size_t formatCandumpLine(const CanFrame& f, std::string_view interface, char (&out)[kCandumpLineMaxBytes]) {
  const std::int64_t seconds = f.t_ns / 1'000'000'000;
  const std::int64_t micros = (f.t_ns % 1'000'000'000) / 1000;
  const std::string_view iface = interface.substr(0, 15);
  int n = std::snprintf(out, sizeof out, "(%lld.%06lld) %.*s", static_cast<long long>(seconds),
                        static_cast<long long>(micros), static_cast<int>(iface.size()), iface.data());
  std::size_t len = static_cast<std::size_t>(n);
  const unsigned id = f.error_frame ? (f.id & kErrMask) | kErrFlag
                      : f.extended  ? f.id & kExtendedIdMask
                                    : f.id & kStandardIdMask;
  n = std::snprintf(out + len, sizeof out - len, (f.error_frame || f.extended) ? " %08X#" : " %03X#", id);
  len += static_cast<std::size_t>(n);
  if (f.remote) {
    out[len++] = 'R';
    return len;
  }
  static constexpr char kHex[] = "0123456789ABCDEF";
  for (std::size_t i = 0; i < f.len && i < kClassicMaxLen; ++i) {
    out[len++] = kHex[f.data[i] >> 4];
    out[len++] = kHex[f.data[i] & 0xF];
  }
  return len;
}

std::string formatCandumpLine(const CanFrame& f, std::string_view interface) {
  char buf[kCandumpLineMaxBytes];
  return std::string(buf, formatCandumpLine(f, interface, buf));
}

std::optional<CanFrame> CandumpReader::next() {
  while (std::getline(in_, line_)) {
    ++counters_.lines;
    std::string_view view = line_;
    while (!view.empty() && (view.back() == '\r' || view.back() == ' ')) view.remove_suffix(1);
    if (view.empty()) {
      ++counters_.blank_lines;
      continue;
    }
    if (view.front() == '#') {  // a note (canplayer skips every line not starting with '(')
      ++counters_.comment_lines;
      continue;
    }
    std::string reason;
    if (auto parsed = parseCandumpLine(view, &reason)) {
      ++counters_.frames;
      return parsed->frame;
    }
    ++counters_.bad_lines;
    if (counters_.first_bad_line == 0) {
      counters_.first_bad_line = counters_.lines;
      counters_.first_bad_reason = "expected " + reason;
    }
  }
  return std::nullopt;
}

}  // namespace headingd::can
