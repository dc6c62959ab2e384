#include "headingd/can/signal_codec.hpp"

#include <cmath>

namespace headingd::can {
namespace {

std::uint64_t lowMask(unsigned length) { return length >= 64 ? ~0ull : ((1ull << length) - 1); }

std::uint64_t asLittleEndian(const Payload& d) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | d[static_cast<std::size_t>(i)];
  return v;
}
std::uint64_t asBigEndian(const Payload& d) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | d[static_cast<std::size_t>(i)];
  return v;
}
void storeLittleEndian(std::uint64_t v, Payload& d) {
  for (std::size_t i = 0; i < 8; ++i) d[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void storeBigEndian(std::uint64_t v, Payload& d) {
  for (std::size_t i = 0; i < 8; ++i) d[i] = static_cast<std::uint8_t>(v >> (8 * (7 - i)));
}

// Motorola signals, in DBC numbering: bit b is bit (b % 8) of byte b / 8, and the start bit
// is the most significant bit. Counted MSB-first through the payload read as one big-endian
// 64-bit word, that bit sits at position 8 * (b / 8) + 7 - b % 8; the signal then occupies
// `length` consecutive positions from there.
unsigned motorolaMsbPosition(unsigned start_bit) { return 8 * (start_bit / 8) + 7 - start_bit % 8; }

}  // namespace

unsigned signalBytesNeeded(const DbcSignal& s) {
  if (s.length < 1 || s.length > 64 || s.start_bit > 63) return 0;
  unsigned last_bit = 0;  // in the numbering of the respective 64-bit word, counted from bit 0 / position 0
  if (s.byte_order == ByteOrder::little_endian) {
    last_bit = s.start_bit + s.length - 1;  // bit index in the little-endian word
  } else {
    last_bit = motorolaMsbPosition(s.start_bit) + s.length - 1;  // position, MSB-first
  }
  if (last_bit > 63) return 0;
  return last_bit / 8 + 1;
}

std::uint64_t extractRawBits(const DbcSignal& s, const Payload& data) {
  if (signalBytesNeeded(s) == 0) return 0;
  if (s.byte_order == ByteOrder::little_endian) {
    return (asLittleEndian(data) >> s.start_bit) & lowMask(s.length);
  }
  const unsigned end = motorolaMsbPosition(s.start_bit) + s.length;  // one past the LSB position
  return (asBigEndian(data) >> (64 - end)) & lowMask(s.length);
}

std::int64_t extractRaw(const DbcSignal& s, const Payload& data) {
  const std::uint64_t bits = extractRawBits(s, data);
  if (s.is_signed && s.length < 64 && ((bits >> (s.length - 1)) & 1u) != 0) {
    return static_cast<std::int64_t>(bits | ~lowMask(s.length));  // two's complement sign extension
  }
  return static_cast<std::int64_t>(bits);
}

double decodeSignal(const DbcSignal& s, const Payload& data) {
  const double raw =
      s.is_signed ? static_cast<double>(extractRaw(s, data)) : static_cast<double>(extractRawBits(s, data));
  return raw * s.factor + s.offset;
}

bool atFullScale(const DbcSignal& s, const Payload& data) {
  if (s.maximum > s.minimum) {
    const double value = decodeSignal(s, data);
    if (value <= s.minimum || value >= s.maximum) return true;
  }
  if (s.length < 2 || s.length > 63) return false;  // a flag or a full 64-bit field: no scale
  if (s.is_signed) {
    const std::int64_t raw = extractRaw(s, data);
    const std::int64_t top = (std::int64_t{1} << (s.length - 1)) - 1;
    return raw == top || raw == -top - 1;
  }
  const std::uint64_t raw = extractRawBits(s, data);
  return raw == lowMask(s.length) || (raw == 0 && s.offset < 0.0);
}

void insertRawBits(const DbcSignal& s, std::uint64_t raw_bits, Payload& data) {
  if (signalBytesNeeded(s) == 0) return;
  const std::uint64_t mask = lowMask(s.length);
  raw_bits &= mask;
  if (s.byte_order == ByteOrder::little_endian) {
    std::uint64_t v = asLittleEndian(data);
    v = (v & ~(mask << s.start_bit)) | (raw_bits << s.start_bit);
    storeLittleEndian(v, data);
    return;
  }
  const unsigned shift = 64 - (motorolaMsbPosition(s.start_bit) + s.length);
  std::uint64_t v = asBigEndian(data);
  v = (v & ~(mask << shift)) | (raw_bits << shift);
  storeBigEndian(v, data);
}

EncodeResult encodeSignal(const DbcSignal& s, double value, Payload& data) {
  if (!std::isfinite(value)) return EncodeResult::not_finite;
  // Representable raw range; doubles hold every integer up to 2^53, enough for IMU signals.
  const double raw_min = s.is_signed ? -std::ldexp(1.0, static_cast<int>(s.length) - 1) : 0.0;
  const double raw_max = s.is_signed ? std::ldexp(1.0, static_cast<int>(s.length) - 1) - 1.0
                                     : std::ldexp(1.0, static_cast<int>(s.length)) - 1.0;
  double raw = std::nearbyint((value - s.offset) / s.factor);
  EncodeResult result = EncodeResult::exact_or_rounded;
  if (!(raw >= raw_min)) {
    raw = raw_min;
    result = EncodeResult::clamped;
  } else if (!(raw <= raw_max)) {
    raw = raw_max;
    result = EncodeResult::clamped;
  }
  std::uint64_t bits = 0;
  if (s.is_signed) {
    // 2^63 - 1 is not a double; the nearest double, 2^63, would overflow the conversion.
    bits = raw >= 9223372036854775807.0 ? 0x7FFFFFFFFFFFFFFFull
                                        : static_cast<std::uint64_t>(static_cast<std::int64_t>(raw));
  } else {
    bits = raw >= 18446744073709551615.0 ? ~0ull : static_cast<std::uint64_t>(raw);
  }
  insertRawBits(s, bits, data);
  return result;
}

}  // namespace headingd::can
