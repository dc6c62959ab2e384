#pragma once
// Publishes LCM messages without allocating per message: each is encoded into one buffer
// that only ever grows (lcm::LCM::publish(channel, msg*) would allocate a buffer per call).
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

namespace headingd::daemon {

class LcmPublisher {
 public:
  // Throws std::runtime_error when LCM cannot be set up for `url`.
  explicit LcmPublisher(const std::string& url);

  // False (and counted) when encoding or sending failed.
  template <class Message>
  bool publish(const std::string& channel, const Message& message) {
    const int size = message.getEncodedSize();
    if (size < 0) return fail();
    if (buffer_.size() < static_cast<std::size_t>(size)) buffer_.resize(static_cast<std::size_t>(size));
    if (message.encode(buffer_.data(), 0, size) != size) return fail();
    if (lcm_.publish(channel, buffer_.data(), static_cast<unsigned>(size)) != 0) return fail();
    ++published_;
    return true;
  }

  std::uint64_t published() const { return published_; }
  std::uint64_t errors() const { return errors_; }

 private:
  bool fail() {
    ++errors_;
    return false;
  }

  lcm::LCM lcm_;
  std::vector<std::uint8_t> buffer_;
  std::uint64_t published_ = 0;
  std::uint64_t errors_ = 0;
};

}  // namespace headingd::daemon
