#pragma once
// Bit-level extraction and insertion of DBC signals in a classic CAN payload (8 bytes),
// for both byte orders, with sign extension and the factor/offset scaling.
#include <array>
#include <cstdint>

#include "headingd/can/dbc.hpp"

namespace headingd::can {

using Payload = std::array<std::uint8_t, 8>;

// Number of payload bytes a signal needs (its last byte + 1); 0 if the layout is impossible
// (beyond 64 bits, zero or over-long length).
unsigned signalBytesNeeded(const DbcSignal& signal);

// The raw bits of the signal, right-aligned; signed signals sign-extended to 64 bits.
std::int64_t extractRaw(const DbcSignal& signal, const Payload& data);
std::uint64_t extractRawBits(const DbcSignal& signal, const Payload& data);

// Physical value: raw * factor + offset.
double decodeSignal(const DbcSignal& signal, const Payload& data);

// Whether the signal reads its full scale: the largest code its bits hold, the smallest when
// that stands for a negative value (signed, or an offset below zero), or the DBC's [min|max]
// where it gives one. A sensor pinned there saturated: what it measured was larger.
bool atFullScale(const DbcSignal& signal, const Payload& data);

// Writes `raw_bits` (the low `length` bits are used) into the signal's position.
void insertRawBits(const DbcSignal& signal, std::uint64_t raw_bits, Payload& data);

enum class EncodeResult {
  exact_or_rounded,  // raw = round((value - offset) / factor)
  clamped,           // the value was outside what the signal can represent; the nearest end was written
  not_finite,        // NaN or infinite value: nothing written
};

// The inverse of decodeSignal, rounding to the nearest representable step.
EncodeResult encodeSignal(const DbcSignal& signal, double value, Payload& data);

}  // namespace headingd::can
