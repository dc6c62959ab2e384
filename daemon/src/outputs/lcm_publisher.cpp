#include "headingd/daemon/outputs/lcm_publisher.hpp"

#include <spdlog/spdlog.h>
#include <stdexcept>

#include "headingd/live/clocks.hpp"

namespace headingd::daemon {

LcmPublisher::LcmPublisher(const std::string& url, RepeatLimiter queue_full_log, std::size_t queue_bytes)
    : lcm_(url), queue_(queue_bytes), queue_full_log_(queue_full_log) {
  if (!lcm_.good()) {
    throw std::runtime_error("LCM: cannot set up '" + url +
                             "' (for udpm: is there a multicast route, e.g. `ip route add 224.0.0.0/4 dev lo`?)");
  }
  // Larger than any message we send; grown if ever needed.
  record_.resize(64 * 1024);
  payload_.resize(64 * 1024);
  channel_.reserve(256);
}

void LcmPublisher::start(std::function<void()> on_thread_start) {
  if (send_inline_ || sender_.joinable()) return;
  stopping_.store(false);
  sender_ = std::thread([this, hook = std::move(on_thread_start)] {
    if (hook) hook();
    sendLoop();
  });
}

void LcmPublisher::stop() {
  if (!sender_.joinable()) return;
  stopping_.store(true);
  doorbell_.ring();
  sender_.join();
}

bool LcmPublisher::enqueue(std::size_t total, const std::string& channel) {
  // One producer: the room seen here cannot shrink before the push.
  if (queue_.write_available() < total) {
    ++queue_full_;
    std::uint64_t suppressed = 0;
    if (queue_full_log_.allow(live::monotonicNs(), &suppressed)) {
      spdlog::warn(
          "LCM send queue full (the sender thread is behind): a message on {} not published ({} in total; "
          "{} such messages suppressed)",
          channel, queue_full_, suppressed);
    }
    return fail();
  }
  queue_.push(record_.data(), total);
  return true;
}

void LcmPublisher::sendLoop() {
  for (;;) {
    const std::uint32_t seen = doorbell_.count();
    sendQueued();
    if (stopping_.load()) {
      sendQueued();  // what was queued before stop() was asked
      return;
    }
    // Returns at once if a flush came since `seen`, early if stop() rings.
    doorbell_.waitWhile(seen, live::toTimespec(nextLook(live::monotonicNs())));
  }
}

std::int64_t LcmPublisher::nextLook(std::int64_t now_ns) const {
  const std::int64_t due = next_flush_ns_.load(std::memory_order_acquire);
  if (due > now_ns) return due;                                           // sleep until the tick
  if (due != 0 && now_ns - due < kPollWindowNs) return now_ns + kPollNs;  // the tick is running
  return now_ns + kIdlePollNs;                                            // late, or no tick scheduled
}

void LcmPublisher::sendQueued() {
  RecordHeader header{};
  while (queue_.read_available() >= sizeof header) {
    queue_.pop(reinterpret_cast<std::uint8_t*>(&header), sizeof header);
    channel_.resize(header.channel_size);
    queue_.pop(reinterpret_cast<std::uint8_t*>(channel_.data()), header.channel_size);
    if (payload_.size() < header.payload_size) payload_.resize(header.payload_size);
    queue_.pop(payload_.data(), header.payload_size);
    send(channel_, payload_.data(), header);
  }
}

bool LcmPublisher::send(const std::string& channel, const std::uint8_t* payload, const RecordHeader& header) {
  const bool sent = lcm_.publish(channel, payload, header.payload_size) == 0;
  if (sent) {
    published_.fetch_add(1, std::memory_order_relaxed);
  } else {
    fail();
  }
  // A full ring only loses a figure, never a message.
  if (header.sample_arrival_ns != kNoSample) sample_ages_.push(live::monotonicNs() - header.sample_arrival_ns);
  return sent;
}

}  // namespace headingd::daemon
