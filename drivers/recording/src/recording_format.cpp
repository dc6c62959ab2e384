#include "headingd/recording/recording_format.hpp"

#include <charconv>
#include <cstdio>

namespace headingd::recording {
namespace {

std::size_t put(LineBuffer& out, std::size_t at, std::string_view s) {
  for (const char c : s) {
    if (at < kMaxLineBytes) out[at++] = c;
  }
  return at;
}

// Signed times and unsigned counts alike (a count above 2^63 must not come out negative).
template <class Integer>
std::size_t putInt(LineBuffer& out, std::size_t at, Integer v) {
  const auto [end, ec] = std::to_chars(out + at, out + kMaxLineBytes, v);
  return ec == std::errc() ? static_cast<std::size_t>(end - out) : at;
}

// "(s.us)" as candump writes it.
std::size_t putCandumpTime(LineBuffer& out, std::size_t at, std::int64_t ns) {
  const int n = std::snprintf(out + at, kMaxLineBytes - at, "(%lld.%06lld)", static_cast<long long>(ns / 1'000'000'000),
                              static_cast<long long>((ns % 1'000'000'000) / 1000));
  return at + static_cast<std::size_t>(n);
}

std::size_t timeAndOp(std::int64_t t_ns, std::string_view op, LineBuffer& out) {
  std::size_t n = putInt(out, 0, t_ns);
  out[n++] = ' ';
  return put(out, n, op);
}

bool parseInt(std::string_view s, std::int64_t& v) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

bool parseUnsigned(std::string_view s, std::uint64_t& v) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

// "(s.us)" -> ns; the same strictness as a candump frame's time (6 decimals written).
bool parseCandumpTime(std::string_view t, std::int64_t& ns) {
  if (t.size() < 4 || t.front() != '(' || t.back() != ')') return false;
  t = t.substr(1, t.size() - 2);
  const std::size_t dot = t.find('.');
  if (dot == std::string_view::npos || t.size() - dot - 1 != 6) return false;
  std::int64_t s = 0, us = 0;
  // Seconds bounded as in a candump frame's time (candump_log.cpp), so that s * 10^9 fits.
  if (!parseInt(t.substr(0, dot), s) || !parseInt(t.substr(dot + 1), us) || s < 0 || s > 9'000'000'000 || us < 0) {
    return false;
  }
  ns = s * 1'000'000'000 + us * 1000;
  return true;
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// Splits "first rest" at the first space.
std::string_view field(std::string_view& s) {
  const std::size_t space = s.find(' ');
  const std::string_view f = s.substr(0, space);
  s = space == std::string_view::npos ? std::string_view() : s.substr(space + 1);
  return f;
}

}  // namespace

std::size_t formatCanFlush(std::int64_t candump_ns, LineBuffer& out) {
  return putCandumpTime(out, put(out, 0, "#flush "), candump_ns);
}

std::size_t formatCanDropped(std::int64_t candump_ns, LineBuffer& out) {
  return putCandumpTime(out, put(out, 0, "#dropped "), candump_ns);
}

std::size_t formatGpsRead(std::int64_t t_ns, std::span<const std::uint8_t> bytes, LineBuffer& out,
                          std::size_t* bytes_used) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::size_t n = timeAndOp(t_ns, "r ", out);
  std::size_t used = 0;
  for (const std::uint8_t b : bytes) {
    char escaped[4];
    std::size_t len = 0;
    if (b == '\r') {
      escaped[0] = '\\', escaped[1] = 'r', len = 2;
    } else if (b == '\n') {
      escaped[0] = '\\', escaped[1] = 'n', len = 2;
    } else if (b == '\\') {
      escaped[0] = '\\', escaped[1] = '\\', len = 2;
    } else if (b >= 0x20 && b < 0x7F) {
      escaped[0] = static_cast<char>(b), len = 1;
    } else {
      escaped[0] = '\\', escaped[1] = 'x', escaped[2] = kHex[b >> 4], escaped[3] = kHex[b & 0xF], len = 4;
    }
    if (n + len > kMaxLineBytes) break;
    for (std::size_t i = 0; i < len; ++i) out[n++] = escaped[i];
    ++used;
  }
  *bytes_used = used;
  return n;
}

std::size_t formatGpsIdle(std::int64_t t_ns, LineBuffer& out) { return timeAndOp(t_ns, "i", out); }
std::size_t formatGpsEnd(std::int64_t t_ns, LineBuffer& out) { return timeAndOp(t_ns, "e", out); }

std::size_t formatGpsPlaced(std::int64_t gps_t_ns, std::uint64_t imu_samples_before, LineBuffer& out) {
  return putInt(out, timeAndOp(gps_t_ns, "g ", out), imu_samples_before);
}

std::size_t formatCalibrationReloaded(std::int64_t t_ns, std::uint64_t imu_samples_before, LineBuffer& out) {
  return putInt(out, timeAndOp(t_ns, "c ", out), imu_samples_before);
}

std::optional<ParsedCanNote> parseCanNote(std::string_view line) {
  ParsedCanNote note{};
  std::string_view rest = line;
  const std::string_view kind = field(rest);
  if (kind == "#flush") {
    note.kind = CanNote::kFlush;
  } else if (kind == "#dropped") {
    note.kind = CanNote::kDropped;
  } else {
    return std::nullopt;
  }
  if (!parseCandumpTime(rest, note.candump_ns)) return std::nullopt;
  return note;
}

std::optional<std::uint64_t> parseLostNote(std::string_view line) {
  constexpr std::string_view kPrefix = "# lost ";
  if (line.substr(0, kPrefix.size()) != kPrefix) return std::nullopt;
  std::string_view rest = line.substr(kPrefix.size());
  std::uint64_t n = 0;
  if (!parseUnsigned(field(rest), n)) return std::nullopt;
  return n;
}

bool parseGpsLine(std::string_view line, ParsedGpsLine& out, std::string* error) {
  std::string_view rest = line;
  if (!parseInt(field(rest), out.t_ns)) return *error = "expected '<time ns> r|i|e ...'", false;
  const std::string_view op = field(rest);
  out.bytes.clear();
  if (op == "i" || op == "e") {
    out.op = op == "i" ? GpsOp::kIdle : GpsOp::kEnd;
    return rest.empty() ? true : (*error = "nothing expected after '" + std::string(op) + "'", false);
  }
  if (op != "r") return *error = "expected the operation r, i or e after the time", false;
  out.op = GpsOp::kRead;
  // `rest` lost its leading space to field(); a read's payload is everything after "r ".
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (rest[i] != '\\') {
      out.bytes.push_back(rest[i]);
      continue;
    }
    if (i + 1 >= rest.size()) return *error = "a '\\' at the end of the line", false;
    const char e = rest[++i];
    if (e == 'r') {
      out.bytes.push_back('\r');
    } else if (e == 'n') {
      out.bytes.push_back('\n');
    } else if (e == '\\') {
      out.bytes.push_back('\\');
    } else if (e == 'x' && i + 2 < rest.size() && hexDigit(rest[i + 1]) >= 0 && hexDigit(rest[i + 2]) >= 0) {
      out.bytes.push_back(static_cast<char>(hexDigit(rest[i + 1]) * 16 + hexDigit(rest[i + 2])));
      i += 2;
    } else {
      return *error = "an escape \\r, \\n, \\\\ or \\xHH", false;
    }
  }
  if (out.bytes.empty()) return *error = "bytes after 'r'", false;
  return true;
}

bool parseEstimatorLine(std::string_view line, ParsedEstimatorLine& out, std::string* error) {
  std::string_view rest = line;
  if (!parseInt(field(rest), out.t_ns)) return *error = "expected '<time ns> g|c <samples>'", false;
  const std::string_view op = field(rest);
  if (op == "g") {
    out.op = EstimatorOp::kGpsPlaced;
  } else if (op == "c") {
    out.op = EstimatorOp::kCalibrationReloaded;
  } else {
    return *error = "expected the operation g or c after the time", false;
  }
  if (!parseUnsigned(rest, out.imu_samples_before)) return *error = "expected a sample count", false;
  return true;
}

std::string segmentPath(const std::string& folder, std::string_view stream, std::uint32_t index) {
  char number[16];
  std::snprintf(number, sizeof number, "%06u", index);
  return folder + "/" + std::string(stream) + "." + number + ".log";
}

}  // namespace headingd::recording
