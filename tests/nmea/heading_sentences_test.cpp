// The heading sentences headingd sends ([nmea_out]): exact text, checksums, rounding, the wrap
// at north, THS modes, and every sentence read back by this project's own NMEA parser (framer,
// checksum check, field splitter, decoders).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "headingd/nmea/checksum.hpp"
#include "headingd/nmea/framer.hpp"
#include "headingd/nmea/heading_sentences.hpp"
#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea {
namespace {

std::string text(const SentenceText& s) { return std::string(s.view()); }

// The lines the framer hands out for these bytes (checksums checked by it).
std::vector<std::string> frame(const std::string& bytes) {
  Framer framer;
  std::vector<std::string> lines;
  for (const char c : bytes) {
    if (const auto line = framer.push(static_cast<std::uint8_t>(c))) lines.emplace_back(*line);
  }
  EXPECT_EQ(framer.counters().bad_checksum, 0u);
  EXPECT_EQ(framer.counters().missing_checksum, 0u);
  EXPECT_EQ(framer.counters().garbage_bytes, 0u);
  return lines;
}

template <class T>
T decodeWith(std::optional<T> (*decoder)(const FieldList&, int&), const SentenceText& s) {
  const auto lines = frame(text(s));
  EXPECT_EQ(lines.size(), 1u);
  EXPECT_EQ(verifyChecksum(lines.at(0)), ChecksumVerdict::kOk);
  const auto fields = FieldList::split(lines.at(0));
  EXPECT_TRUE(fields.has_value());
  int invalid = 0;
  const std::optional<T> decoded = decoder(*fields, invalid);
  EXPECT_TRUE(decoded.has_value()) << s.view();
  EXPECT_EQ(invalid, 0) << s.view();
  return decoded.value_or(T{});
}

TEST(HeadingSentences, HdtTextAndChecksumAreExact) {
  // Checksums computed by hand: XOR of "HEHDT,123.4,T" = 0x2B.
  EXPECT_EQ(text(formatHdt("HE", 123.4)), "$HEHDT,123.4,T*2B\r\n");
  EXPECT_EQ(text(formatHdt("HE", 0.0)), "$HEHDT,0.0,T*2F\r\n");
  EXPECT_EQ(text(formatHdt("HE", std::nullopt)), "$HEHDT,,T*01\r\n");
  EXPECT_EQ(text(formatHdt("II", 271.0)), "$IIHDT,271.0,T*26\r\n");
}

TEST(HeadingSentences, EveryChecksumIsTheXorOfTheBody) {
  for (double deg = -725.0; deg < 725.0; deg += 0.37) {
    for (const SentenceText& s :
         {formatHdt("HE", deg), formatThs("GP", deg, ThsMode::kEstimated), formatHdg("HC", deg, 0.0, deg / 4.0)}) {
      const std::string t = text(s);
      ASSERT_GE(t.size(), 6u);
      ASSERT_EQ(t.substr(t.size() - 2), "\r\n");
      EXPECT_EQ(verifyChecksum(t.substr(0, t.size() - 2)), ChecksumVerdict::kOk) << t;
      EXPECT_LE(t.size(), SentenceText::kMaxLength);
    }
  }
}

TEST(HeadingSentences, RoundsToATenthAndWrapsAtNorth) {
  EXPECT_EQ(text(formatHdt("HE", 12.34)).substr(0, 12), "$HEHDT,12.3,");
  EXPECT_EQ(text(formatHdt("HE", 12.35)).substr(0, 12), "$HEHDT,12.4,");  // 123.5 in doubles: half away from zero
  EXPECT_EQ(text(formatHdt("HE", 12.96)).substr(0, 12), "$HEHDT,13.0,");
  EXPECT_EQ(text(formatHdt("HE", 359.94)).substr(0, 13), "$HEHDT,359.9,");
  // 359.96 rounds to 360.0, which is north.
  EXPECT_EQ(text(formatHdt("HE", 359.96)).substr(0, 11), "$HEHDT,0.0,");
  EXPECT_EQ(text(formatHdt("HE", 360.0)).substr(0, 11), "$HEHDT,0.0,");
  EXPECT_EQ(text(formatHdt("HE", -0.01)).substr(0, 11), "$HEHDT,0.0,");
  EXPECT_EQ(text(formatHdt("HE", -90.0)).substr(0, 13), "$HEHDT,270.0,");
  EXPECT_EQ(text(formatHdt("HE", 725.0)).substr(0, 11), "$HEHDT,5.0,");
  EXPECT_EQ(text(formatHdt("HE", 1e300)).find("$HEHDT,"), 0u);  // any finite value is a bearing
  EXPECT_EQ(text(formatHdt("HE", std::numeric_limits<double>::quiet_NaN())).substr(0, 9), "$HEHDT,,T");
  EXPECT_EQ(text(formatHdt("HE", std::numeric_limits<double>::infinity())).substr(0, 9), "$HEHDT,,T");
}

TEST(HeadingSentences, ThsCarriesEachMode) {
  EXPECT_EQ(text(formatThs("HE", 45.0, ThsMode::kAutonomous)), "$HETHS,45.0,A*1C\r\n");
  for (const ThsMode mode :
       {ThsMode::kAutonomous, ThsMode::kEstimated, ThsMode::kManual, ThsMode::kSimulator, ThsMode::kInvalid}) {
    const Ths t = decodeWith(decodeThs, formatThs("HE", 45.0, mode));
    EXPECT_EQ(t.mode, static_cast<char>(mode));
    EXPECT_EQ(t.heading_deg, 45.0);
  }
  const Ths none = decodeWith(decodeThs, formatThs("HE", std::nullopt, ThsMode::kInvalid));
  EXPECT_FALSE(none.heading_deg.has_value());
  EXPECT_EQ(none.mode, 'V');
}

TEST(HeadingSentences, HdgCarriesDeviationAndVariationAsEastWest) {
  EXPECT_EQ(
      text(formatHdg("HE", 205.63, 0.0, -2.94)), "$HEHDG,205.6,0.0,E,2.9,W*" + [] {
        char hex[3];
        std::snprintf(hex, sizeof hex, "%02X", checksumOf("HEHDG,205.6,0.0,E,2.9,W"));
        return std::string(hex);
      }() + "\r\n");
  const Hdg east = decodeWith(decodeHdg, formatHdg("HE", 10.0, 1.5, 7.7));
  EXPECT_EQ(east.heading_deg, 10.0);
  EXPECT_EQ(east.deviation_deg, 1.5);
  EXPECT_EQ(east.variation_deg, 7.7);
  const Hdg west = decodeWith(decodeHdg, formatHdg("HE", 10.0, -1.5, -7.7));
  EXPECT_EQ(west.deviation_deg, -1.5);
  EXPECT_EQ(west.variation_deg, -7.7);
  // -0.04 rounds to 0.0, east (no "-0.0"); a variation beyond 180 is taken round the circle.
  EXPECT_NE(text(formatHdg("HE", 10.0, -0.04, 190.0)).find(",0.0,E,170.0,W*"), std::string::npos);
  const Hdg absent = decodeWith(decodeHdg, formatHdg("HE", 10.0, std::nullopt, std::nullopt));
  EXPECT_FALSE(absent.deviation_deg.has_value());
  EXPECT_FALSE(absent.variation_deg.has_value());
  EXPECT_EQ(text(formatHdg("HE", 10.0, std::nullopt, std::nullopt)).substr(0, 16), "$HEHDG,10.0,,,,*");
}

TEST(HeadingSentences, ParsedBackEveryTenthOfTheCircleWithinHalfTheResolution) {
  std::string stream;
  std::vector<double> sent;
  for (int i = -20; i < 3620; ++i) {
    const double deg = i * 0.1 + 0.0123;
    sent.push_back(deg);
    stream += text(formatHdt("HE", deg));
    stream += text(formatThs("HE", deg, ThsMode::kAutonomous));
  }
  const auto lines = frame(stream);
  ASSERT_EQ(lines.size(), 2 * sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const double expected = std::fmod(std::fmod(sent[i], 360.0) + 360.0, 360.0);
    // HDT through the decoder of the whole parser (decodeSentence) for a GNSS talker, and the
    // decoder alone for ours.
    const auto hdt_fields = FieldList::split(lines[2 * i]);
    const auto ths_fields = FieldList::split(lines[2 * i + 1]);
    ASSERT_TRUE(hdt_fields && ths_fields);
    int invalid = 0;
    const auto hdt = decodeHdt(*hdt_fields, invalid);
    const auto ths = decodeThs(*ths_fields, invalid);
    ASSERT_TRUE(hdt && hdt->heading_deg && ths && ths->heading_deg);
    EXPECT_EQ(invalid, 0);
    for (const double got : {*hdt->heading_deg, *ths->heading_deg}) {
      double diff = std::fabs(got - expected);
      diff = std::min(diff, 360.0 - diff);
      EXPECT_LE(diff, kHeadingResolutionDeg / 2 + 1e-9) << lines[2 * i];
      EXPECT_LT(got, 360.0);
    }
  }
  const auto decoded = decodeSentence(text(formatHdt("GP", 42.0)).substr(0, 16));
  ASSERT_EQ(decoded.status, DecodeStatus::kDecoded);
  EXPECT_EQ(std::get<Hdt>(decoded.sentence->data).heading_deg, 42.0);
}

TEST(HeadingSentences, TalkerIdsAreTwoUpperCaseLetters) {
  EXPECT_TRUE(isTalkerId("HE"));
  EXPECT_TRUE(isTalkerId("II"));
  EXPECT_FALSE(isTalkerId("he"));
  EXPECT_FALSE(isTalkerId("H"));
  EXPECT_FALSE(isTalkerId("HEX"));
  EXPECT_FALSE(isTalkerId("H1"));
  EXPECT_EQ(text(formatHdt("x", 1.0)).substr(0, 6), "$??HDT");
}

}  // namespace
}  // namespace headingd::nmea
