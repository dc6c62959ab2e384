#pragma once
// NMEA 0183 heading sentences as headingd sends them ([nmea_out]): HDT (true heading), THS
// (true heading with a mode) and HDG (magnetic heading, deviation and variation). Pure: the
// text of one sentence from numbers, '$' through "*hh\r\n", in a fixed buffer (no allocation),
// headings to 0.1° (the x.x of NMEA 0183).
#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace headingd::nmea {

// What the sentences carry: 0.1°. A heading that rounds to 360.0 is sent as 0.0.
inline constexpr double kHeadingResolutionDeg = 0.1;

// THS mode indicator (NMEA 0183 3.0): A autonomous, E estimated (dead reckoning), M manual
// input, S simulator, V not valid.
enum class ThsMode : char {
  kAutonomous = 'A',
  kEstimated = 'E',
  kManual = 'M',
  kSimulator = 'S',
  kInvalid = 'V',
};

// One sentence. NMEA 0183 caps a sentence at 82 characters with CR LF; the heading sentences
// are far shorter (HDG, the longest: 35).
class SentenceText {
 public:
  static constexpr std::size_t kMaxLength = 82;
  std::string_view view() const { return {chars_.data(), size_}; }

 private:
  friend class SentenceWriter;
  std::array<char, kMaxLength> chars_{};
  std::size_t size_ = 0;
};

// A talker ID is two upper-case letters (HE: north-seeking gyro, headingd's default; HC:
// magnetic compass; II: integrated instrumentation).
bool isTalkerId(std::string_view talker);

// A heading that is absent or not finite leaves its field empty (a sentence without data, as
// NMEA 0183 has it). `talker` must pass isTalkerId (else "??" is sent).
// $--HDT,x.x,T*hh
SentenceText formatHdt(std::string_view talker, std::optional<double> true_heading_deg);
// $--THS,x.x,a*hh
SentenceText formatThs(std::string_view talker, std::optional<double> true_heading_deg, ThsMode mode);
// $--HDG,x.x,x.x,a,x.x,a*hh: magnetic heading, deviation and variation (east positive, sent
// as a magnitude with E/W; to 0.1°, within ±180°). True = magnetic + deviation + variation.
SentenceText formatHdg(std::string_view talker, std::optional<double> magnetic_heading_deg,
                       std::optional<double> deviation_deg, std::optional<double> variation_deg);

}  // namespace headingd::nmea
