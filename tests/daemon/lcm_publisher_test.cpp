// The LCM publisher: messages encoded on the caller's thread, sent by its own thread, every
// one in order, none lost silently. Real LCM over UDP multicast (ttl=0, a port of its own; in
// a private network namespace where permitted).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <thread>
#include <vector>

#include "headingd/daemon/outputs/lcm_publisher.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/live/clocks.hpp"

namespace headingd::daemon {
namespace {

const std::string kUrl = "udpm://239.255.76.67:7693?ttl=0";

// Keeps the utime of every HEADING received on channel "T".
class Subscriber {
 public:
  Subscriber() : lcm_(kUrl) {
    if (!lcm_.good()) throw std::runtime_error("LCM subscriber: cannot open " + kUrl);
    lcm_.subscribe("T", &Subscriber::onMessage, this)->setQueueCapacity(1 << 16);
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  ~Subscriber() {
    stop_.store(true);
    thread_.join();
  }
  // Waits (at most 10 s) until `n` messages came.
  std::vector<std::int64_t> waitFor(std::size_t n) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < until) {
      {
        std::lock_guard lock(mutex_);
        if (utimes_.size() >= n) break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // and nothing more
    std::lock_guard lock(mutex_);
    return utimes_;
  }

 private:
  void onMessage(const lcm::ReceiveBuffer*, const std::string&, const heading_t* m) {
    std::lock_guard lock(mutex_);
    utimes_.push_back(m->utime);
  }
  lcm::LCM lcm_;
  std::mutex mutex_;
  std::vector<std::int64_t> utimes_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

heading_t headingAt(std::int64_t utime) {
  heading_t m{};
  m.utime = utime;
  return m;
}

RepeatLimiter logLimit() { return RepeatLimiter(5, 10.0); }

TEST(LcmPublisher, SendsEveryMessageInOrderFromAThreadOfItsOwn) {
  Subscriber subscriber;
  LcmPublisher publisher(kUrl, logLimit());
  std::thread::id sender_thread;
  publisher.start([&] { sender_thread = std::this_thread::get_id(); });
  // Ten ticks' worth of a 286 Hz IMU's messages at 10x real time, a tick every 10 ms: a
  // pace the subscriber keeps up with on a busy machine (it is not what is tested here).
  constexpr int kMessages = 3000;
  for (int i = 0; i < kMessages; ++i) {
    ASSERT_TRUE(publisher.publish("T", headingAt(i)));
    if (i % 30 == 29) {
      publisher.flush();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  publisher.flush();
  const std::vector<std::int64_t> got = subscriber.waitFor(kMessages);
  publisher.stop();
  EXPECT_NE(sender_thread, std::this_thread::get_id());
  ASSERT_EQ(got.size(), static_cast<std::size_t>(kMessages));
  for (int i = 0; i < kMessages; ++i) ASSERT_EQ(got[static_cast<std::size_t>(i)], i) << "message " << i;
  EXPECT_EQ(publisher.published(), static_cast<std::uint64_t>(kMessages));
  EXPECT_EQ(publisher.errors(), 0u);
}

TEST(LcmPublisher, AFullQueueRefusesAndCountsWithoutBlockingAndWhatWasQueuedStillGoesOut) {
  Subscriber subscriber;
  // Room for a few dozen HEADING messages; the sender is not running yet, as if it stalled.
  LcmPublisher publisher(kUrl, logLimit(), 4096);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 500; ++i) (publisher.publish("T", headingAt(i)) ? accepted : refused) += 1;
  EXPECT_GT(accepted, 10);
  EXPECT_GT(refused, 0);
  EXPECT_EQ(publisher.errors(), static_cast<std::uint64_t>(refused));
  publisher.start();
  publisher.flush();
  const std::vector<std::int64_t> got = subscriber.waitFor(static_cast<std::size_t>(accepted));
  publisher.stop();
  ASSERT_EQ(got.size(), static_cast<std::size_t>(accepted));
  for (int i = 0; i < accepted; ++i) EXPECT_EQ(got[static_cast<std::size_t>(i)], i);  // the first ones, in order
  EXPECT_EQ(publisher.published(), static_cast<std::uint64_t>(accepted));
}

TEST(LcmPublisher, StopSendsEverythingQueuedEvenWithoutAFlush) {
  Subscriber subscriber;
  LcmPublisher publisher(kUrl, logLimit());
  publisher.start();
  for (int i = 0; i < 200; ++i) ASSERT_TRUE(publisher.publish("T", headingAt(i)));
  publisher.stop();
  EXPECT_EQ(publisher.published(), 200u);
  EXPECT_EQ(subscriber.waitFor(200).size(), 200u);
}

// Every way the sender can learn of a flush delivers it: a tick that comes when it was
// announced, one that comes late (past the sender's short-poll window), a flush with no tick
// announced at all; and the same when sending inline ([daemon] publish = "imu").
TEST(LcmPublisher, EveryFlushGoesOutOnTimeLateUnannouncedOrInline) {
  for (const bool send_inline : {false, true}) {
    SCOPED_TRACE(send_inline ? "inline" : "time-triggered sender thread");
    Subscriber subscriber;
    LcmPublisher publisher(kUrl, logLimit());
    publisher.setSendInline(send_inline);
    std::thread::id sender_thread;
    publisher.start([&] { sender_thread = std::this_thread::get_id(); });
    int sent = 0;
    const auto tick = [&](std::chrono::microseconds after_announced, std::chrono::microseconds announced_in) {
      const std::int64_t due = live::monotonicNs() + announced_in.count() * 1000;
      publisher.expectFlushAt(due);
      std::this_thread::sleep_for(announced_in + after_announced);
      ASSERT_TRUE(publisher.publish("T", headingAt(sent++)));
      publisher.flush();
    };
    for (int i = 0; i < 20; ++i) tick(std::chrono::microseconds(40), std::chrono::milliseconds(2));  // on time
    for (int i = 0; i < 5; ++i) tick(std::chrono::milliseconds(4), std::chrono::milliseconds(1));    // late
    publisher.expectFlushAt(0);                                                                      // none announced
    for (int i = 0; i < 5; ++i) {
      ASSERT_TRUE(publisher.publish("T", headingAt(sent++)));
      publisher.flush();
      std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
    if (send_inline) {
      EXPECT_EQ(publisher.published(), static_cast<std::uint64_t>(sent)) << "sent as published";
    }
    const std::vector<std::int64_t> got = subscriber.waitFor(static_cast<std::size_t>(sent));
    publisher.stop();
    EXPECT_EQ(sender_thread == std::thread::id(), send_inline) << "a sender thread only when not inline";
    ASSERT_EQ(got.size(), static_cast<std::size_t>(sent));
    for (int i = 0; i < sent; ++i) EXPECT_EQ(got[static_cast<std::size_t>(i)], i);
  }
}

TEST(LcmPublisher, TheSampleAgeIsMeasuredWhenTheMessageWasSent) {
  LcmPublisher publisher(kUrl, logLimit());
  const std::int64_t arrival = live::monotonicNs() - 5'000'000;  // a sample that came 5 ms ago
  ASSERT_TRUE(publisher.publish("T", headingAt(1), arrival));
  ASSERT_TRUE(publisher.publish("T", headingAt(2)));           // carries no sample: no age
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // queued, not yet sent
  const std::int64_t before_send = live::monotonicNs();
  publisher.start();
  publisher.stop();
  std::vector<std::int64_t> ages;
  publisher.drainSampleAges([&](std::int64_t age) { ages.push_back(age); });
  ASSERT_EQ(ages.size(), 1u);
  EXPECT_GE(ages[0], before_send - arrival);  // includes the time it waited in the queue
  EXPECT_LT(ages[0], live::monotonicNs() - arrival + 1);
}

}  // namespace
}  // namespace headingd::daemon
