#include "headingd/nmea/heading_sentences.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>

#include "headingd/nmea/checksum.hpp"

namespace headingd::nmea {

// Appends to a SentenceText; never past its end (the heading sentences cannot reach it).
class SentenceWriter {
 public:
  SentenceWriter(std::string_view talker, std::string_view type) {
    put('$');
    put(isTalkerId(talker) ? talker : "??");
    put(type);
  }

  void put(char c) {
    if (out_.size_ < SentenceText::kMaxLength) out_.chars_[out_.size_++] = c;
  }
  void put(std::string_view s) {
    for (const char c : s) put(c);
  }
  void field() { put(','); }

  // Tenths of a degree as "d.d".
  void tenths(std::int64_t t) {
    std::array<char, 24> digits{};
    const auto r = std::to_chars(digits.data(), digits.data() + digits.size(), t / 10);
    put(std::string_view(digits.data(), static_cast<std::size_t>(r.ptr - digits.data())));
    put('.');
    put(static_cast<char>('0' + t % 10));
  }

  SentenceText finish() {
    // The checksum covers what lies between '$' and '*'.
    const std::uint8_t sum = checksumOf(std::string_view(out_.chars_.data() + 1, out_.size_ - 1));
    constexpr char kHex[] = "0123456789ABCDEF";
    put('*');
    put(kHex[sum >> 4]);
    put(kHex[sum & 0x0F]);
    put("\r\n");
    return out_;
  }

 private:
  SentenceText out_;
};

namespace {

// A bearing in tenths of a degree, [0, 3600): wrapped before rounding (so that any finite
// value is in range) and after (359.96 rounds to 3600, which is north: 0).
std::optional<std::int64_t> bearingTenths(std::optional<double> deg) {
  if (!deg || !std::isfinite(*deg)) return std::nullopt;
  double d = std::fmod(*deg, 360.0);
  if (d < 0.0) d += 360.0;
  std::int64_t t = std::llround(d * 10.0);
  if (t >= 3600) t -= 3600;
  return t;
}

// A signed angle in tenths of a degree, [-1800, 1800], east positive.
std::optional<std::int64_t> signedTenths(std::optional<double> deg) {
  if (!deg || !std::isfinite(*deg)) return std::nullopt;
  return std::llround(std::remainder(*deg, 360.0) * 10.0);
}

void putBearing(SentenceWriter& w, std::optional<double> deg) {
  w.field();
  if (const auto t = bearingTenths(deg)) w.tenths(*t);
}

// "x.x,E" / "x.x,W"; both fields empty when absent. -0.04 rounds to 0.0, sent as east.
void putEastWest(SentenceWriter& w, std::optional<double> deg) {
  const auto t = signedTenths(deg);
  w.field();
  if (t) w.tenths(*t < 0 ? -*t : *t);
  w.field();
  if (t) w.put(*t < 0 ? 'W' : 'E');
}

}  // namespace

bool isTalkerId(std::string_view talker) {
  return talker.size() == 2 && talker[0] >= 'A' && talker[0] <= 'Z' && talker[1] >= 'A' && talker[1] <= 'Z';
}

SentenceText formatHdt(std::string_view talker, std::optional<double> true_heading_deg) {
  SentenceWriter w(talker, "HDT");
  putBearing(w, true_heading_deg);
  w.field();
  w.put('T');
  return w.finish();
}

SentenceText formatThs(std::string_view talker, std::optional<double> true_heading_deg, ThsMode mode) {
  SentenceWriter w(talker, "THS");
  putBearing(w, true_heading_deg);
  w.field();
  w.put(static_cast<char>(mode));
  return w.finish();
}

SentenceText formatHdg(std::string_view talker, std::optional<double> magnetic_heading_deg,
                       std::optional<double> deviation_deg, std::optional<double> variation_deg) {
  SentenceWriter w(talker, "HDG");
  putBearing(w, magnetic_heading_deg);
  putEastWest(w, deviation_deg);
  putEastWest(w, variation_deg);
  return w.finish();
}

}  // namespace headingd::nmea
