#pragma once
// Publishes LCM messages from the estimator thread without making it wait for the network
// stack. publish() encodes the message on the caller's thread into a byte queue (lock-free,
// single producer, single consumer; no allocation per message); a sender thread of the
// publisher's own hands each one to LCM in the order queued. LCM's send is a sendto() per
// message, which on loopback multicast runs the whole local delivery in the caller: about
// 18 µs a message on the 2-CPU test machine, 55 of the tick's 80 µs with a 286 Hz IMU's
// messages (measured with and without [lcm] publish_imu). The tick now only encodes.
//
// How the sender learns of new messages. Waking it (a futex wake) costs the estimator a
// cross-CPU interrupt: 14 µs a tick on the test VM when quiet, 30-40 µs when busy, as much as
// the sends it saved. So by default the sender is time-triggered: the estimator tells it
// when its next tick is due (expectFlushAt) and flush() only bumps a counter; the sender
// sleeps until that deadline on its own timer, then looks every kPollNs until the tick's
// messages are there (a tick takes 20-50 µs) and sends them. That adds at most about kPollNs
// to a message's age.
//
// When flushes do not follow a schedule ([daemon] publish = "imu": a HEADING as each IMU
// sample arrives) the consumer wants the lowest latency, and waking a sender would add its
// wake-up (about 40 µs to the age's median here): setSendInline(true) then sends each message
// on the caller's thread as it is published, as LCM itself would.
//
// Nothing is lost silently: a message that cannot be encoded, that finds the queue full (the
// sender stalled for about a second of traffic), or that LCM refuses to send is counted in
// errors(); a full queue is also logged, at a bounded rate.
//
// The age of a sample at publish is taken where it is published: a message may carry the
// CLOCK_MONOTONIC arrival time of the newest IMU sample in it, and after sending it the sender
// thread measures that sample's age and passes it back (drainSampleAges) to the thread that
// keeps the figures. So the age includes the hand-over to the sender.
#include <atomic>
#include <boost/lockfree/spsc_queue.hpp>
#include <cstdint>
#include <cstring>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thread>
#include <vector>

#include "headingd/daemon/loop/doorbell.hpp"
#include "headingd/daemon/system/repeat_limiter.hpp"

namespace headingd::daemon {

class LcmPublisher {
 public:
  static constexpr std::int64_t kNoSample = -1;
  // Over a second of everything the daemon publishes at a 1 kHz IMU (about 250 kB/s).
  static constexpr std::size_t kDefaultQueueBytes = 1 << 20;

  // Throws std::runtime_error when LCM cannot be set up for `url`. Sends nothing before start().
  // `queue_full_log` bounds the warnings about a full queue ([log] repeat_burst, repeat_interval_s).
  LcmPublisher(const std::string& url, RepeatLimiter queue_full_log, std::size_t queue_bytes = kDefaultQueueBytes);
  ~LcmPublisher() { stop(); }
  LcmPublisher(const LcmPublisher&) = delete;
  LcmPublisher& operator=(const LcmPublisher&) = delete;

  // Starts the sender thread; it runs `on_thread_start` first (name, scheduling). No thread
  // when sending inline.
  void start(std::function<void()> on_thread_start = {});
  // Sends everything queued, then ends the sender thread. Idempotent.
  void stop();

  // One producer thread. True when the message is queued (sent, inline); false (and counted)
  // when it cannot be encoded, the queue is full or, inline, LCM refused it. `sample_arrival_ns`: the newest IMU
  // sample's arrival (CLOCK_MONOTONIC), whose age at send is measured; kNoSample for none.
  template <class Message>
  bool publish(const std::string& channel, const Message& message, std::int64_t sample_arrival_ns = kNoSample) {
    const int size = message.getEncodedSize();
    if (size < 0) return fail();
    const std::size_t total = sizeof(RecordHeader) + channel.size() + static_cast<std::size_t>(size);
    if (record_.size() < total) record_.resize(total);  // only grows: no allocation once warm
    const RecordHeader header{static_cast<std::uint32_t>(channel.size()), static_cast<std::uint32_t>(size),
                              sample_arrival_ns};
    std::memcpy(record_.data(), &header, sizeof header);
    std::memcpy(record_.data() + sizeof header, channel.data(), channel.size());
    std::uint8_t* payload = record_.data() + sizeof header + channel.size();
    if (message.encode(payload, 0, size) != size) return fail();
    if (send_inline_) return send(channel, payload, header);
    return enqueue(total, channel);
  }
  // What was queued since the last flush may go out: after a tick's messages.
  void flush() { doorbell_.post(); }
  // The producer's next flush comes soon after `deadline_ns` (CLOCK_MONOTONIC): the sender
  // looks then. Any thread.
  void expectFlushAt(std::int64_t deadline_ns) { next_flush_ns_.store(deadline_ns, std::memory_order_release); }
  // Before start(): each message is sent as it is published, on the caller's thread.
  void setSendInline(bool send_inline) { send_inline_ = send_inline; }

  // The sender's timing when it is time-triggered: how often it looks once a tick is due,
  // for how long, and how often after that (a late tick, or no loop running).
  static constexpr std::int64_t kPollNs = 25'000;
  static constexpr std::int64_t kPollWindowNs = 2'000'000;
  static constexpr std::int64_t kIdlePollNs = 1'000'000;

  // The producer's thread: each age measured since the last call, in ns, oldest first.
  template <class F>
  void drainSampleAges(F&& f) {
    sample_ages_.consume_all(f);
  }

  std::uint64_t published() const { return published_.load(std::memory_order_relaxed); }
  std::uint64_t errors() const { return errors_.load(std::memory_order_relaxed); }

 private:
  struct RecordHeader {
    std::uint32_t channel_size;
    std::uint32_t payload_size;
    std::int64_t sample_arrival_ns;
  };

  bool enqueue(std::size_t total, const std::string& channel);
  bool fail() {
    errors_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  void sendLoop();
  void sendQueued();
  // Hands one encoded message to LCM and counts it; measures the sample's age if it has one.
  bool send(const std::string& channel, const std::uint8_t* payload, const RecordHeader& header);
  std::int64_t nextLook(std::int64_t now_ns) const;

  lcm::LCM lcm_;
  // Records: header, channel name, encoded message. One push per record, so the sender never
  // sees half of one.
  boost::lockfree::spsc_queue<std::uint8_t> queue_;
  // Ages flow back; a tick drains them, so 1024 is dozens of ticks' worth.
  boost::lockfree::spsc_queue<std::int64_t, boost::lockfree::capacity<1024>> sample_ages_;
  Doorbell doorbell_;
  bool send_inline_ = false;
  std::atomic<std::int64_t> next_flush_ns_{0};  // 0: not known yet
  std::atomic<bool> stopping_{false};
  std::thread sender_;

  std::vector<std::uint8_t> record_;   // the producer's
  RepeatLimiter queue_full_log_;       // the producer's
  std::uint64_t queue_full_ = 0;       // the producer's
  std::string channel_;                // the sender's
  std::vector<std::uint8_t> payload_;  // the sender's

  std::atomic<std::uint64_t> published_{0};
  std::atomic<std::uint64_t> errors_{0};
};

}  // namespace headingd::daemon
