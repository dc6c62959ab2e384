#include "headingd/lcm_export/message_types.hpp"

#include <array>
#include <climits>
#include <exception>

#include "headingd/lcm_export/decode_allocation_limit.hpp"
#include "headingd/lcm_export/message_fields.hpp"

namespace headingd::lcm_export {
namespace {

template <class Message>
bool flattenAs(std::span<const std::uint8_t> data, FlatRow& row, std::string& error) {
  // One instance per type, reused: its vectors and strings keep their capacity.
  static Message message;
  if (data.size() > static_cast<std::size_t>(INT_MAX)) {
    error = "too large to decode";
    return false;
  }
  const int size = static_cast<int>(data.size());
  int used = -1;
  try {
    const DecodeAllocationLimit limit(kMaxMemoryBytesPerWireByte * data.size() + 4096);
    used = message.decode(data.data(), 0, size);
  } catch (const std::exception&) {
    // bad_alloc from the limit; length_error, out_of_range from a negative count or length.
    error = "does not decode (a count or length that does not fit the message)";
    return false;
  }
  if (used < 0) {
    error = "does not decode (a length or count runs past the message's end)";
    return false;
  }
  if (used != size) {
    error = "decodes from " + std::to_string(used) + " of its " + std::to_string(size) + " bytes";
    return false;
  }
  ColumnWriter writer(row);
  describeFields(message, writer);
  return true;
}

// The elements of headingd's variable-length arrays fit the allocation limit's factor.
static_assert(sizeof(headingd::source_status_t) <= kMaxMemoryBytesPerWireByte);
static_assert(sizeof(headingd::ring_status_t) <= kMaxMemoryBytesPerWireByte);
static_assert(sizeof(headingd::counter_t) <= kMaxMemoryBytesPerWireByte);

template <class Message>
MessageType typeOf() {
  return MessageType{Message::getTypeName(), Message::getHash(), &flattenAs<Message>};
}

}  // namespace

std::span<const MessageType> knownMessageTypes() {
  static const std::array<MessageType, 5> types{typeOf<headingd::heading_t>(), typeOf<headingd::attitude_t>(),
                                                typeOf<headingd::imu_t>(), typeOf<headingd::gps_t>(),
                                                typeOf<headingd::status_t>()};
  return types;
}

const MessageType* findMessageType(std::int64_t fingerprint) {
  for (const MessageType& type : knownMessageTypes()) {
    if (type.fingerprint == fingerprint) return &type;
  }
  return nullptr;
}

std::int64_t fingerprintOf(std::span<const std::uint8_t> data) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < 8; ++i) value = (value << 8) | data[i];
  return static_cast<std::int64_t>(value);
}

}  // namespace headingd::lcm_export
