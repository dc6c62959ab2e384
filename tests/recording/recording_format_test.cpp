#include <gtest/gtest.h>

#include <array>

#include "headingd/recording/recording_format.hpp"

namespace headingd::recording {
namespace {

TEST(RecordingFormat, EverySerialByteValueSurvivesAGpsReadLine) {
  std::array<std::uint8_t, 256> all{};
  for (int i = 0; i < 256; ++i) all[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
  std::span<const std::uint8_t> rest(all);
  std::string back;
  ParsedGpsLine parsed;
  std::string error;
  while (!rest.empty()) {
    LineBuffer line;
    std::size_t used = 0;
    const std::size_t n = formatGpsRead(1234567890123, rest, line, &used);
    ASSERT_GT(used, 0u);
    ASSERT_LE(n, kMaxLineBytes);
    ASSERT_TRUE(parseGpsLine(std::string_view(line, n), parsed, &error)) << error << ": " << std::string(line, n);
    EXPECT_EQ(parsed.t_ns, 1234567890123);
    EXPECT_EQ(parsed.op, GpsOp::kRead);
    back += parsed.bytes;
    rest = rest.subspan(used);
  }
  ASSERT_EQ(back.size(), 256u);
  for (int i = 0; i < 256; ++i) EXPECT_EQ(static_cast<std::uint8_t>(back[static_cast<std::size_t>(i)]), i);
}

TEST(RecordingFormat, NmeaStaysReadable) {
  const std::string nmea = "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n";
  LineBuffer line;
  std::size_t used = 0;
  const std::size_t n =
      formatGpsRead(42, std::span(reinterpret_cast<const std::uint8_t*>(nmea.data()), nmea.size()), line, &used);
  EXPECT_EQ(used, nmea.size());
  EXPECT_EQ(std::string(line, n), "42 r $GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\\r\\n");
}

TEST(RecordingFormat, NotesAndPlacementsReadBack) {
  LineBuffer line;
  const auto flush = parseCanNote(std::string_view(line, formatCanFlush(1'700'000'000'123'456'000, line)));
  ASSERT_TRUE(flush);
  EXPECT_EQ(flush->kind, CanNote::kFlush);
  EXPECT_EQ(flush->candump_ns, 1'700'000'000'123'456'000);
  EXPECT_EQ(std::string(line, formatCanDropped(1'700'000'000'000'001'000, line)), "#dropped (1700000000.000001)");
  EXPECT_EQ(parseCanNote("#dropped (1700000000.000001)")->kind, CanNote::kDropped);
  EXPECT_FALSE(parseCanNote("# something else"));
  EXPECT_FALSE(parseCanNote("#flush (1700000000.1)"));  // candump times have 6 decimals
  // Seconds beyond a candump time's range (9e9 s) are refused, not overflowed (found by
  // tests/fuzz/recording_lines_fuzz.cpp).
  EXPECT_FALSE(parseCanNote("#flush (99999999999.000000)"));
  EXPECT_FALSE(parseCanNote("#dropped (9223372036854775807.000000)"));

  ParsedEstimatorLine placed;
  std::string error;
  ASSERT_TRUE(parseEstimatorLine(std::string_view(line, formatGpsPlaced(-5, 4711, line)), placed, &error)) << error;
  EXPECT_EQ(placed.t_ns, -5);
  EXPECT_EQ(placed.op, EstimatorOp::kGpsPlaced);
  EXPECT_EQ(placed.imu_samples_before, 4711u);
  ASSERT_TRUE(parseEstimatorLine(std::string_view(line, formatCalibrationReloaded(9, 3, line)), placed, &error));
  EXPECT_EQ(placed.op, EstimatorOp::kCalibrationReloaded);
  // A count above 2^63 is written unsigned, as it is read.
  ASSERT_TRUE(
      parseEstimatorLine(std::string_view(line, formatGpsPlaced(1, 18446744073709551615u, line)), placed, &error))
      << std::string(line, formatGpsPlaced(1, 18446744073709551615u, line));
  EXPECT_EQ(placed.imu_samples_before, 18446744073709551615u);
  EXPECT_FALSE(parseEstimatorLine("12 g", placed, &error));
  EXPECT_FALSE(parseEstimatorLine("12 x 3", placed, &error));

  EXPECT_EQ(parseLostNote("# lost 12 lines"), 12u);
  EXPECT_FALSE(parseLostNote("# lost many lines"));

  ParsedGpsLine gps;
  EXPECT_TRUE(parseGpsLine("5 i", gps, &error));
  EXPECT_EQ(gps.op, GpsOp::kIdle);
  EXPECT_TRUE(parseGpsLine("6 e", gps, &error));
  EXPECT_EQ(gps.op, GpsOp::kEnd);
  EXPECT_FALSE(parseGpsLine("7 r bad\\q", gps, &error));
  EXPECT_FALSE(parseGpsLine("7 r \\x4", gps, &error));
  EXPECT_FALSE(parseGpsLine("x r a", gps, &error));
}

TEST(RecordingFormat, SegmentNames) {
  EXPECT_EQ(segmentPath("/r/2026-12-02T06-00-00Z", "can", 12), "/r/2026-12-02T06-00-00Z/can.000012.log");
}

}  // namespace
}  // namespace headingd::recording
