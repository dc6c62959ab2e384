#pragma once
// lcm-gen's decoders size a vector or a string from the count or length in the data before
// they check it against the message's size: a corrupt count of 50 000 000 made one status_t
// of 168 bytes allocate and fill 7.8 GB for 72 s before it failed. While a limit is in
// force, any single allocation larger than it throws std::bad_alloc at once (this library
// replaces the global operator new, see decode_allocation_limit.cpp).
#include <cstddef>

namespace headingd::lcm_export {

// The largest allocation a valid message of `message_bytes` can need: every element of a
// variable-length array takes at least one byte on the wire, and no element type is larger
// in memory than this factor (checked where the types are listed).
inline constexpr std::size_t kMaxMemoryBytesPerWireByte = 256;

class DecodeAllocationLimit {
 public:
  explicit DecodeAllocationLimit(std::size_t max_bytes_per_allocation);
  ~DecodeAllocationLimit();
  DecodeAllocationLimit(const DecodeAllocationLimit&) = delete;
  DecodeAllocationLimit& operator=(const DecodeAllocationLimit&) = delete;

 private:
  std::size_t previous_;
};

}  // namespace headingd::lcm_export
