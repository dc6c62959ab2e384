#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "headingd/nmea/framer.hpp"
#include "nmea_test_support.hpp"

namespace headingd::nmea {
namespace {

using test::sentence;

std::vector<std::string> frame(Framer& f, std::string_view bytes) {
  std::vector<std::string> lines;
  for (const char c : bytes) {
    if (const auto l = f.push(static_cast<std::uint8_t>(c))) lines.emplace_back(*l);
  }
  return lines;
}

std::vector<std::string> frame(std::string_view bytes, FramerConfig config = {}) {
  Framer f(config);
  return frame(f, bytes);
}

const std::string kGsa = sentence("GPGSA,A,3,03,07,08,11,13,16,19,23,24,28,,,3.6,2.0,3.0");
const std::string kVtg = sentence("GPVTG,0.0,T,10.5,M,0.0,N,0.0,K");

TEST(Framer, FramesOnCrLfInAnyCombination) {
  for (const char* eol : {"\r\n", "\n", "\r", "\n\r", "\r\r\n"}) {
    const auto lines = frame(kGsa + eol + kVtg + eol);
    ASSERT_EQ(lines.size(), 2u) << "eol " << testing::PrintToString(std::string(eol));
    EXPECT_EQ(lines[0], kGsa);
    EXPECT_EQ(lines[1], kVtg);
  }
}

TEST(Framer, CountsMissingAndBadChecksums) {
  Framer f;
  std::string bad = kGsa;
  bad[10] = '9';
  const auto lines = frame(f, "$GPGSA,A,1,,,\r\n" + bad + "\r\n" + kVtg + "\r\n");
  EXPECT_EQ(lines, std::vector<std::string>{kVtg});
  EXPECT_EQ(f.counters().missing_checksum, 1u);
  EXPECT_EQ(f.counters().bad_checksum, 1u);
  EXPECT_EQ(f.counters().lines, 1u);
}

TEST(Framer, OverlongLineIsSkippedToItsEndAndCounted) {
  Framer f;
  const std::string longer = sentence("GPTXT," + std::string(200, 'x'));
  const auto lines = frame(f, longer + "\r\n" + kVtg + "\r\n");
  EXPECT_EQ(lines, std::vector<std::string>{kVtg});
  EXPECT_EQ(f.counters().overlong, 1u);
  EXPECT_EQ(f.counters().garbage_bytes, 0u);
}

TEST(Framer, LengthBoundIsConfigurable) {
  // 82 characters is NMEA's own limit (with CR/LF); this GSA is 56 long.
  FramerConfig strict;
  strict.max_line_length = 40;
  Framer f(strict);
  EXPECT_TRUE(frame(f, kGsa + "\r\n").empty());
  EXPECT_EQ(f.counters().overlong, 1u);
  FramerConfig exact;
  exact.max_line_length = kGsa.size();
  EXPECT_EQ(frame(kGsa + "\r\n", exact).size(), 1u);
}

TEST(Framer, BufferNeverExceedsTheBound) {
  Framer f;
  std::string endless = "$GP";
  endless += std::string(100000, 'A');
  for (const char c : endless) {
    f.push(static_cast<std::uint8_t>(c));
    ASSERT_LE(f.buffered(), FramerConfig{}.max_line_length);
  }
  EXPECT_EQ(f.counters().overlong, 1u);
}

TEST(Framer, NewStartCharacterTruncatesTheOpenLine) {
  Framer f;
  const auto lines = frame(f, "$GPGGA,1235" + kVtg + "\r\n");
  EXPECT_EQ(lines, std::vector<std::string>{kVtg});
  EXPECT_EQ(f.counters().truncated, 1u);
}

TEST(Framer, DoubledStartCharacterIsAStrayByteNotATruncation) {
  // st-teseo-liv4f.log: "$$GNGSA,...".
  Framer f;
  const auto lines = frame(f, "$" + kGsa + "\r\n");
  EXPECT_EQ(lines, std::vector<std::string>{kGsa});
  EXPECT_EQ(f.counters().truncated, 0u);
  EXPECT_EQ(f.counters().garbage_bytes, 1u);
}

TEST(Framer, BinaryBytesOutsideAndInsideLinesAreCounted) {
  Framer f;
  const std::string binary = std::string("\xb5\x62\x01\x07\x00\x00", 6);
  const auto lines = frame(f, binary + kGsa + "\r\n" + "$GPGGA,12" + binary + kVtg + "\r\n");
  EXPECT_EQ(lines, (std::vector<std::string>{kGsa, kVtg}));
  EXPECT_EQ(f.counters().binary_lines, 1u);  // "$GPGGA,12" broken off by 0xb5
  // 6 bytes before the GSA, then 0xb5 ends the GGA and 5 more follow.
  EXPECT_EQ(f.counters().garbage_bytes, 12u);
}

TEST(Framer, OpenLineAtEndOfStreamIsTruncated) {
  Framer f;
  frame(f, kGsa);
  EXPECT_EQ(f.counters().lines, 0u);
  f.finish();
  EXPECT_EQ(f.counters().truncated, 1u);
  EXPECT_EQ(f.buffered(), 0u);
}

TEST(Framer, AisLinesAreFramedToo) {
  const std::string ais = sentence("AIVDM,1,1,,A,13HOI:0P0000VOHLCnHQKwvL05Ip,0,0", '!');
  EXPECT_EQ(frame(ais + "\r\n"), std::vector<std::string>{ais});
}

}  // namespace
}  // namespace headingd::nmea
