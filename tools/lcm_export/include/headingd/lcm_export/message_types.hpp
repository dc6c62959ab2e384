#pragma once
// headingd's LCM message types, told apart by the 8-byte fingerprint that starts every
// encoded message (the generated types' getHash()), not by channel name: a channel renamed
// by an [lcm] *_channel key exports the same way.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "headingd/lcm_export/columns.hpp"

namespace headingd::lcm_export {

struct MessageType {
  std::string_view name;  // "heading_t"
  std::int64_t fingerprint;
  // Decodes `data` (fingerprint first) and appends its columns to `row`. False, with the
  // reason in `error`, when the data is not a whole message of this type.
  bool (*flatten)(std::span<const std::uint8_t> data, FlatRow& row, std::string& error);
};

// heading_t, attitude_t, imu_t, gps_t, status_t (the types the daemon publishes).
std::span<const MessageType> knownMessageTypes();
// The type with this fingerprint, nullptr for an unknown one.
const MessageType* findMessageType(std::int64_t fingerprint);
// The big-endian fingerprint at the start of an encoded message (`data` has >= 8 bytes).
std::int64_t fingerprintOf(std::span<const std::uint8_t> data);

}  // namespace headingd::lcm_export
