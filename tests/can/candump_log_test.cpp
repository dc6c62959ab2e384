// candump -l lines: parsing of every frame kind, rejection of bad lines with a reason,
// formatting, and the reader's counts with line numbers over a real file.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "can_test_support.hpp"
#include "headingd/can/candump_log.hpp"

namespace headingd::can {
namespace {

TEST(CandumpLog, ParsesStandardExtendedRemoteAndErrorFrames) {
  auto a = parseCandumpLine("(1700000000.123456) can0 123#DEADBEEF");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->frame.t_ns, 1700000000123456000LL);
  EXPECT_EQ(a->interface, "can0");
  EXPECT_EQ(a->frame.id, 0x123u);
  EXPECT_FALSE(a->frame.extended);
  ASSERT_EQ(a->frame.len, 4);
  EXPECT_EQ(a->frame.data[0], 0xDE);
  EXPECT_EQ(a->frame.data[3], 0xEF);

  auto b = parseCandumpLine("(1.000001) vcan0 18F02A80#0102030405060708");
  ASSERT_TRUE(b);
  EXPECT_TRUE(b->frame.extended);
  EXPECT_EQ(b->frame.id, 0x18F02A80u);
  EXPECT_EQ(b->frame.len, 8);
  EXPECT_EQ(b->frame.data[7], 8);

  auto empty = parseCandumpLine("(1.0) can0 7FF#");
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->frame.len, 0);

  auto r = parseCandumpLine("(2.5) can0 123#R");
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->frame.remote);
  auto r4 = parseCandumpLine("(2.5) can0 00000123#R4");
  ASSERT_TRUE(r4);
  EXPECT_TRUE(r4->frame.extended);
  EXPECT_EQ(r4->frame.len, 4);

  auto e = parseCandumpLine("(3.0) can0 20000040#0000000000000000");
  ASSERT_TRUE(e);
  EXPECT_TRUE(e->frame.error_frame);
  EXPECT_EQ(e->frame.id, 0x40u);

  auto dir = parseCandumpLine("(3.0) can0 123#11 R");  // direction flag of newer candump
  ASSERT_TRUE(dir);
  auto dlc = parseCandumpLine("(3.0) can0 123#1122334455667788_C");
  ASSERT_TRUE(dlc);
  EXPECT_EQ(dlc->frame.len, 8);
}

TEST(CandumpLog, RejectsBadLinesWithAReason) {
  const char* bad[] = {
      "",
      "garbage",
      "1700000000.1 can0 123#00",
      "(1700000000.) can0 123#00",
      "(abc.def) can0 123#00",
      "(1.0)",
      "(1.0) can0",
      "(1.0) can0 123",
      "(1.0) can0 12#00",
      "(1.0) can0 800#00",
      "(1.0) can0 1234#00",
      "(1.0) can0 4FFFFFFF#00",
      "(1.0) can0 123#0",
      "(1.0) can0 123#GG",
      "(1.0) c\x05"
      "n0 123#00",  // a control byte in the interface name
      "(1.0) can0 123#001122334455667788",
      "(1.0) can0 123##1DEADBEEF",
      "(1.0) can0 123#00 extra words",
      "(1.0) can0 123#RR",
  };
  for (const char* line : bad) {
    std::string reason;
    EXPECT_FALSE(parseCandumpLine(line, &reason)) << line;
    EXPECT_FALSE(reason.empty()) << line;
  }
  std::string reason;
  parseCandumpLine("(1.0) can0 123##1DEADBEEF", &reason);
  EXPECT_NE(reason.find("CAN FD"), std::string::npos);
}

TEST(CandumpLog, RejectsSignedAndOutOfRangeTimes) {
  // from_chars reads "-0" as 0: (-0.5) was taken for +0.5 s. A sign is no candump time.
  for (const char* line : {"(-0.5) can0 123#00", "(-1.000000) can0 123#00", "(+1.000000) can0 123#00",
                           "(-0.000000) can0 123#00", "(9000000001.000000) can0 123#00", "( 1.0) can0 123#00"}) {
    std::string reason;
    EXPECT_FALSE(parseCandumpLine(line, &reason)) << line;
    EXPECT_NE(reason.find("timestamp"), std::string::npos) << line << ": " << reason;
  }
  std::istringstream log("(1.000000) can0 123#00\n(-0.500000) can0 123#00\n(2.000000) can0 123#00\n");
  CandumpReader reader(log);
  ASSERT_EQ(reader.next()->t_ns, 1'000'000'000);
  ASSERT_EQ(reader.next()->t_ns, 2'000'000'000);
  EXPECT_FALSE(reader.next());
  EXPECT_EQ(reader.counters().bad_lines, 1u);
  EXPECT_EQ(reader.counters().first_bad_line, 2u);
}

// Found by fuzzing (tests/fuzz/corpus/candump_line/regression-nul-in-interface): a NUL in
// the interface name was accepted, and the line written back lost the rest of the name.
TEST(CandumpLog, RejectsANulInTheInterfaceName) {
  using namespace std::string_view_literals;
  std::string reason;
  EXPECT_FALSE(parseCandumpLine("(1780315254.580000) \0\x05n0 122#8EFCFFF4FD686120"sv, &reason));
  EXPECT_EQ(reason, "an interface name after the timestamp");
}

TEST(CandumpLog, FormatParsesBack) {
  CanFrame f = test::frame(0x1ABCDEF0 & kExtendedIdMask, true, {1, 2, 0xFF}, 1700000000123456789LL);
  const std::string line = formatCandumpLine(f, "can0");
  EXPECT_EQ(line, "(1700000000.123456) can0 1ABCDEF0#0102FF");
  const auto back = parseCandumpLine(line);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->frame.id, f.id);
  EXPECT_EQ(back->frame.len, 3);
  EXPECT_EQ(back->frame.t_ns, 1700000000123456000LL);  // microseconds in the log
  EXPECT_EQ(formatCandumpLine(test::frame(0x12, false, {}, 5'000'000'000LL), "vcan1"), "(5.000000) vcan1 012#");
  CanFrame err;
  err.error_frame = true;
  err.id = 0x4;
  err.len = 8;
  EXPECT_EQ(formatCandumpLine(err, "can0"), "(0.000000) can0 20000004#0000000000000000");
}

TEST(CandumpLog, ReaderCountsBadLinesWithTheirNumbers) {
  test::TempDir dir;
  const std::string path = dir.write("log.txt",
                                     "(1.000000) can0 120#0011223344556677\n"
                                     "\n"
                                     "(1.000200) can0 121#00112233445566\r\n"
                                     "this is not a frame\n"
                                     "(1.000400) can0 12#00\n"
                                     "(1.000600) can0 122#0011223344556677");  // no final newline
  std::ifstream in(path);
  CandumpReader reader(in);
  int frames = 0;
  while (reader.next()) ++frames;
  EXPECT_EQ(frames, 3);
  const auto& n = reader.counters();
  EXPECT_EQ(n.lines, 6u);
  EXPECT_EQ(n.frames, 3u);
  EXPECT_EQ(n.blank_lines, 1u);
  EXPECT_EQ(n.bad_lines, 2u);
  EXPECT_EQ(n.first_bad_line, 4u);
  EXPECT_NE(n.first_bad_reason.find("expected a timestamp"), std::string::npos) << n.first_bad_reason;
}

TEST(CandumpLog, BinaryGarbageNeverCrashes) {
  std::uint32_t state = 1;
  for (int i = 0; i < 20000; ++i) {
    std::string line = "(1700000000.000000) can0 123#0011223344556677";
    for (int k = 0; k < 3; ++k) {
      state = state * 1664525u + 1013904223u;
      line[state % line.size()] = static_cast<char>(state >> 24);
    }
    std::string reason;
    if (auto f = parseCandumpLine(line, &reason)) {
      EXPECT_LE(f->frame.len, 8);
    }
  }
}

}  // namespace
}  // namespace headingd::can
