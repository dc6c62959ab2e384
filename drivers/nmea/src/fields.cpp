#include "headingd/nmea/fields.hpp"

#include <charconv>
#include <cmath>

namespace headingd::nmea {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

bool allDigits(std::string_view s) {
  for (const char c : s) {
    if (!isDigit(c)) return false;
  }
  return !s.empty();
}

int twoDigits(std::string_view s) { return (s[0] - '0') * 10 + (s[1] - '0'); }

// "ddmm.mmm" / "dddmm.mmm" to degrees. Degrees and whole minutes are split in integers so
// that no binary rounding moves a value across a minute boundary.
std::optional<double> parseDegreesMinutes(std::string_view value, double max_deg) {
  const auto dot = value.find('.');
  const std::string_view whole = value.substr(0, dot);
  if (whole.size() < 2 || whole.size() > 5 || !allDigits(whole)) return std::nullopt;
  int ddmm = 0;
  std::from_chars(whole.data(), whole.data() + whole.size(), ddmm);
  double minutes = ddmm % 100;
  const int degrees = ddmm / 100;
  if (dot != std::string_view::npos) {
    const std::string_view fraction = value.substr(dot + 1);
    if (!fraction.empty()) {
      if (!allDigits(fraction)) return std::nullopt;
      double f = 0.0;
      // Parse ".mmm" as a whole so the fraction keeps all its digits.
      const std::string_view with_dot = value.substr(dot);
      const auto r = std::from_chars(with_dot.data(), with_dot.data() + with_dot.size(), f);
      if (r.ec != std::errc{} || r.ptr != with_dot.data() + with_dot.size()) return std::nullopt;
      minutes += f;
    }
  }
  if (minutes >= 60.0) return std::nullopt;
  const double deg = degrees + minutes / 60.0;
  if (deg > max_deg) return std::nullopt;
  return deg;
}

}  // namespace

std::optional<double> parseDecimal(std::string_view field) {
  if (field.empty()) return std::nullopt;
  bool negative = false;
  if (field.front() == '+' || field.front() == '-') {
    negative = field.front() == '-';
    field.remove_prefix(1);
  }
  // Digits with at most one '.', and at least one digit: from_chars alone would also take
  // "inf", "nan" and exponents, none of which an NMEA field may hold.
  int digits = 0, dots = 0;
  for (const char c : field) {
    if (isDigit(c)) {
      ++digits;
    } else if (c == '.') {
      ++dots;
    } else {
      return std::nullopt;
    }
  }
  if (digits == 0 || dots > 1) return std::nullopt;
  double v = 0.0;
  const auto r = std::from_chars(field.data(), field.data() + field.size(), v, std::chars_format::fixed);
  if (r.ec != std::errc{} || r.ptr != field.data() + field.size()) return std::nullopt;
  return negative ? -v : v;
}

std::optional<int> parseInteger(std::string_view field) {
  if (field.empty() || field.size() > 9 || !allDigits(field)) return std::nullopt;
  int v = 0;
  std::from_chars(field.data(), field.data() + field.size(), v);
  return v;
}

std::optional<std::int64_t> parseTimeOfDay(std::string_view field) {
  if (field.size() < 6 || !allDigits(field.substr(0, 6))) return std::nullopt;
  const int hh = twoDigits(field.substr(0, 2));
  const int mm = twoDigits(field.substr(2, 2));
  const int ss = twoDigits(field.substr(4, 2));
  if (hh > 23 || mm > 59 || ss > 60) return std::nullopt;
  std::int64_t ns = 0;
  if (field.size() > 6) {
    if (field[6] != '.') return std::nullopt;
    const std::string_view fraction = field.substr(7);
    if (!fraction.empty() && !allDigits(fraction)) return std::nullopt;
    std::int64_t scale = 100'000'000;
    for (std::size_t i = 0; i < fraction.size() && i < 9; ++i, scale /= 10) ns += (fraction[i] - '0') * scale;
  }
  return ((hh * 60LL + mm) * 60LL + ss) * 1'000'000'000LL + ns;
}

std::optional<double> parseLatitude(std::string_view value, std::string_view hemisphere) {
  if (hemisphere != "N" && hemisphere != "S") return std::nullopt;
  const auto deg = parseDegreesMinutes(value, 90.0);
  if (!deg) return std::nullopt;
  return hemisphere == "S" ? -*deg : *deg;
}

std::optional<double> parseLongitude(std::string_view value, std::string_view hemisphere) {
  if (hemisphere != "E" && hemisphere != "W") return std::nullopt;
  const auto deg = parseDegreesMinutes(value, 180.0);
  if (!deg) return std::nullopt;
  return hemisphere == "W" ? -*deg : *deg;
}

std::optional<DayMonthYy> parseDdmmyy(std::string_view field) {
  if (field.size() != 6 || !allDigits(field)) return std::nullopt;
  const DayMonthYy d{twoDigits(field.substr(0, 2)), twoDigits(field.substr(2, 2)), twoDigits(field.substr(4, 2))};
  if (d.day < 1 || d.day > 31 || d.month < 1 || d.month > 12) return std::nullopt;
  return d;
}

std::optional<double> parseBearing(std::string_view field) {
  const auto v = parseDecimal(field);
  if (!v || *v < 0.0 || *v > 360.0) return std::nullopt;
  return *v == 360.0 ? 0.0 : *v;
}

}  // namespace headingd::nmea
