// DBC text: parseDbc on arbitrary text. Invariants: only DbcError is thrown; every signal of
// a database that parsed fits its message (the codec reads only the message's bytes) and
// decodes any payload to a value without tripping the sanitizers; encoding a decoded value
// and decoding it again gives it back (for
// signals whose scaling doubles hold exactly enough).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/can/dbc.hpp"
#include "headingd/can/signal_codec.hpp"

using namespace headingd;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The first 8 bytes are a payload to decode, the rest the DBC text.
  can::Payload payload{};
  const std::size_t payload_bytes = size < payload.size() ? size : payload.size();
  std::memcpy(payload.data(), data, payload_bytes);
  const std::string_view text(reinterpret_cast<const char*>(data + payload_bytes), size - payload_bytes);

  can::DbcDatabase db;
  try {
    db = can::parseDbc(text, "fuzz.dbc");
  } catch (const can::DbcError&) {
    return 0;
  }
  for (const can::DbcMessage& message : db.messages) {
    FUZZ_CHECK(message.dlc <= 64);
    FUZZ_CHECK(db.findMessage(message.name) != nullptr);
    for (const can::DbcSignal& signal : message.signals) {
      FUZZ_CHECK(signal.length >= 1 && signal.length <= 64);
      FUZZ_CHECK(message.findSignal(signal.name) != nullptr);
      if (signal.multiplexed || message.dlc > 8) continue;
      FUZZ_CHECK(can::signalBytesNeeded(signal) <= message.dlc);
      const double value = can::decodeSignal(signal, payload);
      // The round trip is exact only where doubles hold raw * factor + offset exactly enough.
      const bool well_scaled = signal.length <= 32 && std::abs(signal.factor) >= 1e-6 &&
                               std::abs(signal.factor) <= 1e6 && std::abs(signal.offset) <= 1e6;
      if (!std::isfinite(value) || !well_scaled) continue;
      can::Payload encoded{};
      if (can::encodeSignal(signal, value, encoded) == can::EncodeResult::exact_or_rounded) {
        FUZZ_CHECK(can::extractRawBits(signal, encoded) == can::extractRawBits(signal, payload));
      }
    }
  }
  return 0;
}
