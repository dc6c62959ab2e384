// Bit extraction/insertion for both byte orders, sign extension, scaling, and round trips.
#include <gtest/gtest.h>

#include <random>

#include "headingd/can/signal_codec.hpp"

namespace headingd::can {
namespace {

DbcSignal sig(unsigned start, unsigned length, ByteOrder order, bool is_signed, double factor = 1.0,
              double offset = 0.0) {
  DbcSignal s;
  s.name = "S";
  s.start_bit = start;
  s.length = length;
  s.byte_order = order;
  s.is_signed = is_signed;
  s.factor = factor;
  s.offset = offset;
  return s;
}

constexpr auto LE = ByteOrder::little_endian;
constexpr auto BE = ByteOrder::big_endian;

TEST(SignalCodec, IntelWithinAndAcrossBytes) {
  const Payload d{0x34, 0x12, 0xF0, 0x0F, 0xAB, 0x00, 0x00, 0x80};
  EXPECT_EQ(extractRawBits(sig(0, 16, LE, false), d), 0x1234u);
  EXPECT_EQ(extractRawBits(sig(4, 12, LE, false), d), 0x123u);  // high nibble of byte 0, all of byte 1
  EXPECT_EQ(extractRawBits(sig(20, 8, LE, false), d), 0xFFu);   // nibble 2.hi + nibble 3.lo
  EXPECT_EQ(extractRawBits(sig(63, 1, LE, false), d), 1u);
  EXPECT_EQ(extractRaw(sig(32, 8, LE, true), d), static_cast<std::int64_t>(0xAB) - 256);
  EXPECT_EQ(extractRawBits(sig(0, 64, LE, false), d), 0x800000AB0FF01234ull);
  EXPECT_EQ(signalBytesNeeded(sig(4, 12, LE, false)), 2u);
  EXPECT_EQ(signalBytesNeeded(sig(60, 8, LE, false)), 0u);  // beyond 64 bits
}

TEST(SignalCodec, MotorolaDbcNumbering) {
  // Start bit = MSB in DBC numbering (bit 7 of byte 0 is 7, bit 0 of byte 1 is 8).
  const Payload d{0x12, 0x34, 0x56, 0x78, 0x9A, 0xBC, 0xDE, 0xF0};
  EXPECT_EQ(extractRawBits(sig(7, 16, BE, false), d), 0x1234u);           // byte 0 then byte 1
  EXPECT_EQ(extractRawBits(sig(3, 12, BE, false), d), 0x234u);            // low nibble of byte 0, then byte 1
  EXPECT_EQ(extractRawBits(sig(4, 3, BE, false), d), (0x12u >> 2) & 7u);  // bits 4..2 of byte 0
  EXPECT_EQ(extractRawBits(sig(0, 2, BE, false), d),
            ((0x12u & 1u) << 1) | (0x34u >> 7));  // bit 0 of byte 0, bit 7 of byte 1
  EXPECT_EQ(extractRawBits(sig(15, 8, BE, false), d), 0x34u);
  EXPECT_EQ(extractRawBits(sig(7, 64, BE, false), d), 0x123456789ABCDEF0ull);
  EXPECT_EQ(extractRawBits(sig(56, 1, BE, false), d), 0u);    // bit 0 of byte 7 (0xF0)
  EXPECT_EQ(extractRawBits(sig(63, 4, BE, false), d), 0xFu);  // top nibble of byte 7
  EXPECT_EQ(signalBytesNeeded(sig(7, 16, BE, false)), 2u);
  EXPECT_EQ(signalBytesNeeded(sig(0, 2, BE, false)), 2u);
  EXPECT_EQ(signalBytesNeeded(sig(56, 2, BE, false)), 0u);  // would run past byte 7
  EXPECT_EQ(signalBytesNeeded(sig(63, 8, BE, false)), 8u);
}

TEST(SignalCodec, SignExtensionAndScaling) {
  Payload d{};
  d[0] = 0xFF;
  d[1] = 0xFF;
  EXPECT_EQ(extractRaw(sig(0, 16, LE, true), d), -1);
  EXPECT_EQ(extractRaw(sig(0, 16, LE, false), d), 65535);
  EXPECT_DOUBLE_EQ(decodeSignal(sig(0, 16, LE, true, 0.01, 5.0), d), 4.99);
  d = Payload{0x80, 0x00};
  EXPECT_EQ(extractRaw(sig(7, 16, BE, true), d), -32768);
  EXPECT_EQ(extractRaw(sig(7, 1, BE, true), d), -1);  // a 1-bit signed signal is 0 or -1
  // OpenIMU style: unsigned with a negative offset.
  d = Payload{0x00, 0x7D};  // raw 32000 -> 32000/128 - 250 = 0 deg/s
  EXPECT_DOUBLE_EQ(decodeSignal(sig(0, 16, LE, false, 1.0 / 128, -250.0), d), 0.0);
}

TEST(SignalCodec, EncodeInvertsDecodeAndClamps) {
  const DbcSignal s = sig(12, 20, LE, true, 1e-4, 0.0);
  Payload d{};
  EXPECT_EQ(encodeSignal(s, -12.34567, d), EncodeResult::exact_or_rounded);
  EXPECT_NEAR(decodeSignal(s, d), -12.34567, 0.5e-4 + 1e-12);
  EXPECT_EQ(encodeSignal(s, 1000.0, d), EncodeResult::clamped);
  EXPECT_NEAR(decodeSignal(s, d), 52.4287, 1e-9);
  EXPECT_EQ(encodeSignal(s, -1000.0, d), EncodeResult::clamped);
  EXPECT_NEAR(decodeSignal(s, d), -52.4288, 1e-9);
  EXPECT_EQ(encodeSignal(s, std::nan(""), d), EncodeResult::not_finite);
  const DbcSignal u = sig(7, 16, BE, false, 0.00025, -8.0);
  EXPECT_EQ(encodeSignal(u, -9.0, d), EncodeResult::clamped);
  EXPECT_DOUBLE_EQ(decodeSignal(u, d), -8.0);
  const DbcSignal full = sig(0, 64, LE, true);
  EXPECT_EQ(encodeSignal(full, 1e30, d), EncodeResult::clamped);
  EXPECT_EQ(extractRaw(full, d), INT64_MAX);
}

// Random layouts of both byte orders: insert a value into random background bytes, read it
// back, and check that no bit outside the signal changed.
TEST(SignalCodec, RandomRoundTripsLeaveOtherBitsAlone) {
  std::mt19937_64 rng(7);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const ByteOrder order = (rng() & 1u) != 0 ? LE : BE;
    const unsigned length = 1 + static_cast<unsigned>(rng() % 64);
    const unsigned start = static_cast<unsigned>(rng() % 64);
    const bool is_signed = (rng() & 1u) != 0;
    const DbcSignal s = sig(start, length, order, is_signed);
    if (signalBytesNeeded(s) == 0) continue;
    Payload background{};
    for (auto& b : background) b = static_cast<std::uint8_t>(rng());
    const std::uint64_t mask = length == 64 ? ~0ull : (1ull << length) - 1;
    const std::uint64_t value = rng() & mask;
    Payload d = background;
    insertRawBits(s, value, d);
    ASSERT_EQ(extractRawBits(s, d), value) << "start " << start << " length " << length;
    // Clearing the signal in both payloads must make them equal again.
    Payload a = d, b = background;
    insertRawBits(s, 0, a);
    insertRawBits(s, 0, b);
    ASSERT_EQ(a, b) << "bits outside the signal changed, start " << start << " length " << length;
    if (is_signed && length < 64 && ((value >> (length - 1)) & 1u) != 0) {
      ASSERT_LT(extractRaw(s, d), 0);
    }
    ++checked;
  }
  EXPECT_GT(checked, 5000);
}

}  // namespace
}  // namespace headingd::can
