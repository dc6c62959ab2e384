// EpochAssembler, the pure part of the serial driver and the log player: one Fix per epoch,
// the same as the parser's, delivered early on request and never twice.
#include <gtest/gtest.h>

#include "headingd/nmea/serial_epoch_assembler.hpp"
#include "nmea_test_support.hpp"
#include "pty_fixture.hpp"
#include "serial_test_support.hpp"
#include "test_data.hpp"

namespace headingd::test {
namespace {

using nmea::test::sentence;

struct Out {
  std::vector<std::string> fixes;
  std::vector<std::int64_t> receive_ns;
  std::vector<std::string> lines;
};

nmea::EpochAssembler makeAssembler(Out& out) {
  return nmea::EpochAssembler(
      {},
      [&out](const nmea::Fix& f, std::int64_t t) {
        out.fixes.push_back(fixText(f));
        out.receive_ns.push_back(t);
      },
      [&out](std::string_view line, std::int64_t) { out.lines.emplace_back(line); });
}

std::span<const std::uint8_t> bytesOf(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

const std::string kGga1 = sentence("GPGGA,120000.00,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,") + "\r\n";
const std::string kRmc1 = sentence("GPRMC,120000.00,A,4807.038,N,01131.000,E,1.5,84.4,230394,3.1,W") + "\r\n";
const std::string kVtg = sentence("GPVTG,84.4,T,,M,1.5,N,2.8,K,A") + "\r\n";
const std::string kGsv = sentence("GPGSV,1,1,01,05,40,083,46") + "\r\n";
const std::string kProprietary = sentence("PUBX,00,120000.00") + "\r\n";
const std::string kGga2 = sentence("GPGGA,120001.00,4807.039,N,01131.001,E,1,08,0.9,545.5,M,46.9,M,,") + "\r\n";

TEST(EpochAssembler, AnEpochEndsWhenTheNextStartsAndCarriesItsLastSentencesTime) {
  Out out;
  auto a = makeAssembler(out);
  a.feed(bytesOf(kGga1 + kRmc1), 100);
  a.feed(bytesOf(kVtg + kGsv), 200);  // VTG is the epoch's last decoded sentence
  EXPECT_TRUE(out.fixes.empty());
  EXPECT_TRUE(a.epochPending());
  a.feed(bytesOf(kGga2), 300);
  ASSERT_EQ(out.fixes.size(), 1u);
  EXPECT_EQ(out.receive_ns[0], 200);
  EXPECT_EQ(out.fixes[0], referenceEpochs(bytesOf(kGga1 + kRmc1 + kVtg + kGsv))[0]);
  EXPECT_NE(out.fixes[0].find("cog=84.4"), std::string::npos) << out.fixes[0];
  a.endOfStream();
  ASSERT_EQ(out.fixes.size(), 2u);
  EXPECT_EQ(out.receive_ns[1], 300);
  EXPECT_EQ(a.epochCounters().epochs, 2u);
}

TEST(EpochAssembler, AnEpochCompletedEarlyIsNotDeliveredAgainAndLateSentencesAreCounted) {
  Out out;
  auto a = makeAssembler(out);
  a.feed(bytesOf(kGga1), 1);
  a.completeEpoch();
  a.completeEpoch();
  ASSERT_EQ(out.fixes.size(), 1u);
  EXPECT_FALSE(a.epochPending());
  a.feed(bytesOf(kRmc1 + kVtg), 2);  // same epoch, after it went out
  a.feed(bytesOf(kGga2), 3);
  a.endOfStream();
  EXPECT_EQ(out.fixes.size(), 2u);
  EXPECT_EQ(a.epochCounters().late_sentences, 2u);
}

TEST(EpochAssembler, EveryChecksummedLineGoesToTheLineHandler) {
  Out out;
  auto a = makeAssembler(out);
  const std::string bad = kGga2.substr(0, 10) + "X" + kGga2.substr(11);
  a.feed(bytesOf(kProprietary + kGsv + bad + "$GPGGA,trunc"), 0);
  a.endOfStream();
  ASSERT_EQ(out.lines.size(), 2u);
  EXPECT_EQ(out.lines[0] + "\r\n", kProprietary);
  EXPECT_EQ(out.lines[1] + "\r\n", kGsv);
  const auto c = a.parserCounters();
  EXPECT_EQ(c.framing.bad_checksum, 1u);
  EXPECT_EQ(c.framing.truncated, 1u);
  EXPECT_EQ(c.sentences.unsupported_talker, 1u);
  EXPECT_EQ(c.sentences.unsupported_type, 1u);
}

TEST(EpochAssembler, SameFixesAsTheParserWhateverTheChunking) {
  const auto wire = readWireBytes(test_data::file(test_data::kGpsdLogs, "furuno_gl_ga.log"));
  const auto want = referenceEpochs(wire);
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{512}, wire.size()}) {
    Out out;
    auto a = makeAssembler(out);
    for (std::size_t at = 0; at < wire.size(); at += chunk) {
      a.feed(std::span(wire).subspan(at, std::min(chunk, wire.size() - at)), static_cast<std::int64_t>(at));
    }
    a.endOfStream();
    EXPECT_EQ(out.fixes, want) << "chunk " << chunk;
  }
}

}  // namespace
}  // namespace headingd::test
