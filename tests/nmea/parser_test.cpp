#include <gtest/gtest.h>
#include <numeric>

#include <random>

#include "headingd/nmea/comment_filter.hpp"
#include "headingd/nmea/parser.hpp"
#include "nmea_test_support.hpp"

namespace headingd::nmea {
namespace {

using test::sentence;

const std::vector<std::string> kCycle = {
    sentence("GPGGA,132820.60,4134.49821229,N,09345.03351845,W,2,09,1.0,278.020,M,-31.442,M,7.6,0133"),
    sentence("GPGSA,A,3,03,07,08,11,13,16,19,23,24,,,,1.8,1.0,1.5"),
    sentence("GPGSV,3,1,10,03,41,050,46,07,60,317,49,08,34,315,45,11,35,148,45"),
    sentence("GPRMC,132820.60,A,4134.49821229,N,09345.03351845,W,3.252,92.308,180320,11.5985,E,D"),
    sentence("GPVTG,92.308,T,80.7,M,3.252,N,6.023,K,D"),
    sentence("PGRME,15.0,M,45.0,M,25.0,M"),
    sentence("AIVDM,1,1,,A,13HOI:0P0000VOHLCnHQKwvL05Ip,0,0", '!'),
    sentence("GPZDA,132820.60,18,03,2020,00,00"),
    sentence("GPHDT,93.1,T"),
};

std::string cycleBytes() {
  std::string s;
  for (const auto& l : kCycle) s += l + "\r\n";
  return s;
}

TEST(Parser, OneUpdatePerDecodedSentence) {
  Parser p;
  std::vector<FixUpdate> updates;
  p.feed(cycleBytes(), updates);
  ASSERT_EQ(updates.size(), 6u);  // GGA GSA RMC VTG ZDA HDT
  EXPECT_EQ(updates[0].type, SentenceType::kGGA);
  EXPECT_EQ(updates[0].sentence, kCycle[0]);
  EXPECT_FALSE(updates[0].fix.speed_mps);
  EXPECT_TRUE(updates[2].fix.speed_mps);
  const Fix& last = updates.back().fix;
  EXPECT_DOUBLE_EQ(*last.heading_deg, 93.1);
  EXPECT_DOUBLE_EQ(*last.course_deg, 92.308);
  const auto c = p.counters();
  EXPECT_EQ(c.framing.lines, 9u);
  EXPECT_EQ(c.sentences.decoded, 6u);
  EXPECT_EQ(c.sentences.unsupported_type, 1u);    // GSV
  EXPECT_EQ(c.sentences.unsupported_talker, 1u);  // PGRME
  EXPECT_EQ(c.sentences.ais, 1u);
  EXPECT_EQ(c.sentences.decodedOf(headingd::nmea::SentenceType::kGGA), 1u);
  EXPECT_EQ(c.sentences.decodedOf(headingd::nmea::SentenceType::kHDT), 1u);
}

TEST(Parser, MalformedAndInvalidFieldsAreCounted) {
  Parser p;
  std::vector<FixUpdate> updates;
  p.feed(sentence("GPGSA,A,1,,,,") + "\r\n" + sentence("GPGGA,120000,4807.038,N,01131.000,E,1,08,0.9,545.4,F,,M,,") +
             "\r\n",
         updates);
  EXPECT_EQ(p.counters().sentences.malformed, 1u);
  EXPECT_EQ(p.counters().sentences.invalid_fields, 1u);
  EXPECT_EQ(updates.size(), 1u);
}

TEST(Parser, SameUpdatesWhateverTheChunking) {
  std::string stream;
  for (int i = 0; i < 20; ++i) stream += cycleBytes() + "\xb5\x62garbage$GPGGA,1";
  Parser whole;
  std::vector<FixUpdate> expected;
  whole.feed(stream, expected);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    Parser p;
    std::vector<FixUpdate> got;
    for (std::size_t at = 0; at < stream.size();) {
      const std::size_t n = std::min<std::size_t>(rng() % 97 + 1, stream.size() - at);
      p.feed(std::string_view(stream).substr(at, n), got);
      at += n;
    }
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].sentence, expected[i].sentence);
    EXPECT_EQ(p.counters().framing.garbage_bytes, whole.counters().framing.garbage_bytes);
    EXPECT_EQ(p.counters().framing.truncated, whole.counters().framing.truncated);
  }
}

// Every good line is classified exactly once.
void expectConsistent(const Counters& c, std::size_t updates) {
  const auto& s = c.sentences;
  EXPECT_EQ(s.ais + s.unsupported_talker + s.unsupported_type + s.malformed + s.decoded, c.framing.lines);
  EXPECT_EQ(std::accumulate(s.decoded_by_type.begin(), s.decoded_by_type.end(), std::uint64_t{0}), s.decoded);
  EXPECT_EQ(s.decoded, updates);
}

// Whatever comes in, what comes out is in range.
void expectSane(const Fix& f) {
  if (f.position) {
    EXPECT_LE(std::abs(f.position->lat_deg), 90.0);
    EXPECT_LE(std::abs(f.position->lon_deg), 180.0);
  }
  if (f.course_deg) {
    EXPECT_GE(*f.course_deg, 0.0);
    EXPECT_LT(*f.course_deg, 360.0);
  }
  if (f.speed_mps) {
    EXPECT_GE(*f.speed_mps, 0.0);
  }
  if (f.time_of_day_ns) {
    EXPECT_GE(*f.time_of_day_ns, 0);
    EXPECT_LT(*f.time_of_day_ns, 86'401'000'000'000LL);
  }
}

TEST(ParserFuzz, RandomBytes) {
  std::mt19937 rng(20240601);
  std::uniform_int_distribution<int> byte(0, 255);
  Parser p;
  std::vector<FixUpdate> updates;
  std::vector<std::uint8_t> chunk;
  for (int i = 0; i < 2000; ++i) {
    chunk.resize(rng() % 512);
    for (auto& b : chunk) b = static_cast<std::uint8_t>(byte(rng));
    p.feed(chunk, updates);
    ASSERT_LE(p.buffered(), FramerConfig{}.max_line_length);
  }
  p.finish();
  const auto c = p.counters();
  EXPECT_GT(c.framing.bytes, 400'000u);
  EXPECT_GT(c.framing.garbage_bytes, 0u);
  expectConsistent(c, updates.size());
  for (const auto& u : updates) expectSane(u.fix);
}

TEST(ParserFuzz, RandomPrintableTextWithStartCharacters) {
  // Printable noise with '$', ',', '*' and line ends often enough to reach the decoders.
  const std::string alphabet = "$$$,,,,***\r\n0123456789.ABCDEFGPNSEWMTKV-GPGGAGNRMC";
  std::mt19937 rng(42);
  Parser p;
  std::vector<FixUpdate> updates;
  std::string chunk;
  for (int i = 0; i < 2000; ++i) {
    chunk.clear();
    for (int j = 0; j < 256; ++j) chunk += alphabet[rng() % alphabet.size()];
    p.feed(chunk, updates);
  }
  expectConsistent(p.counters(), updates.size());
  for (const auto& u : updates) expectSane(u.fix);
}

TEST(ParserFuzz, MutatedValidSentencesWithFixedChecksums) {
  // Corrupt fields but recompute the checksum, so every mutation reaches the decoders.
  std::mt19937 rng(1234);
  const std::string chars = "0123456789.,-+ANSEWVMTK*$";
  Parser p;
  std::vector<FixUpdate> updates;
  for (int i = 0; i < 20000; ++i) {
    const std::string& base = kCycle[rng() % kCycle.size()];
    std::string body = base.substr(1, base.size() - 4);
    const int edits = static_cast<int>(rng() % 4) + 1;
    for (int e = 0; e < edits && !body.empty(); ++e) {
      const std::size_t at = rng() % body.size();
      switch (rng() % 3) {
        case 0: body[at] = chars[rng() % chars.size()]; break;
        case 1: body.erase(at, 1); break;
        default: body.insert(at, 1, chars[rng() % chars.size()]); break;
      }
    }
    p.feed(sentence(body) + "\r\n", updates);
  }
  const auto c = p.counters();
  expectConsistent(c, updates.size());
  EXPECT_GT(c.sentences.decoded, 1000u);
  EXPECT_GT(c.sentences.malformed, 100u);
  EXPECT_GT(c.sentences.invalid_fields, 100u);
  for (const auto& u : updates) expectSane(u.fix);
}

TEST(CommentFilter, StripsCommentLinesOnly) {
  const std::string in = "# Name: x\r\n" + kCycle[0] + "\r\n#comment\n" + kCycle[1] + "\n";
  CommentFilter f;
  std::vector<std::uint8_t> out;
  f.filter(std::span(reinterpret_cast<const std::uint8_t*>(in.data()), in.size()), out);
  EXPECT_EQ(std::string(out.begin(), out.end()), kCycle[0] + "\r\n" + kCycle[1] + "\n");
  EXPECT_EQ(f.commentLines(), 2u);
}

TEST(CommentFilter, HashInsideALineIsData) {
  const std::string in = "$GPTXT,#1*00\n";
  CommentFilter f;
  std::vector<std::uint8_t> out;
  f.filter(std::span(reinterpret_cast<const std::uint8_t*>(in.data()), in.size()), out);
  EXPECT_EQ(std::string(out.begin(), out.end()), in);
  EXPECT_EQ(f.commentLines(), 0u);
}

TEST(CommentFilter, BinaryEndsAComment) {
  // A stray "\n#" inside binary data must not swallow the bytes after it.
  const std::string in = std::string("\n#\xb5\x62", 4) + kCycle[0] + "\r\n";
  CommentFilter f;
  std::vector<std::uint8_t> out;
  f.filter(std::span(reinterpret_cast<const std::uint8_t*>(in.data()), in.size()), out);
  EXPECT_EQ(std::string(out.begin(), out.end()), std::string("\n\xb5\x62", 3) + kCycle[0] + "\r\n");
}

TEST(CommentFilter, SameResultWhateverTheChunking) {
  const std::string in = "#a\r\n" + kCycle[0] + "\r\n# b\n#c\n" + kCycle[1] + "\n";
  std::vector<std::uint8_t> whole, bytewise;
  CommentFilter a, b;
  a.filter(std::span(reinterpret_cast<const std::uint8_t*>(in.data()), in.size()), whole);
  for (std::size_t i = 0; i < in.size(); ++i) {
    b.filter(std::span(reinterpret_cast<const std::uint8_t*>(in.data()) + i, 1), bytewise);
  }
  EXPECT_EQ(whole, bytewise);
  EXPECT_EQ(a.commentLines(), 3u);
  EXPECT_EQ(b.commentLines(), 3u);
}

}  // namespace
}  // namespace headingd::nmea
