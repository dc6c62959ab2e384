// SampleRing with two real threads: nothing lost below capacity, exact drop counts above.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "headingd/daemon/loop/sample_ring.hpp"

namespace headingd::daemon {
namespace {

struct Item {
  std::uint64_t sequence = 0;
  double payload[12] = {};  // about the size of an IMU entry
};

TEST(SampleRing, ConcurrentProducerAndConsumerLoseNothingBelowCapacity) {
  constexpr std::size_t kCapacity = 256;
  constexpr std::uint64_t kItems = 200'000;
  SampleRing<Item> ring("test", kCapacity);
  std::atomic<bool> producer_done{false};
  std::vector<std::uint64_t> received;
  received.reserve(kItems);

  // The producer never gets more than kCapacity ahead of the consumer: it waits for the
  // consumer's acknowledgements, so every push must succeed.
  std::atomic<std::uint64_t> consumed{0};
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kItems; ++i) {
      while (i - consumed.load(std::memory_order_acquire) >= kCapacity) std::this_thread::yield();
      Item item;
      item.sequence = i;
      item.payload[11] = static_cast<double>(i);
      ASSERT_TRUE(ring.push(item)) << "push " << i;
    }
    producer_done.store(true, std::memory_order_release);
  });
  std::thread consumer([&] {
    for (;;) {
      const bool done = producer_done.load(std::memory_order_acquire);
      const std::size_t n = ring.drain([&](const Item& item) {
        EXPECT_EQ(item.payload[11], static_cast<double>(item.sequence));
        received.push_back(item.sequence);
      });
      consumed.fetch_add(n, std::memory_order_release);
      if (done && n == 0) break;
    }
  });
  producer.join();
  consumer.join();

  ASSERT_EQ(received.size(), kItems);
  for (std::uint64_t i = 0; i < kItems; ++i) ASSERT_EQ(received[i], i);
  const RingStats s = ring.stats();
  EXPECT_EQ(s.capacity, kCapacity);
  EXPECT_EQ(s.pushed, kItems);
  EXPECT_EQ(s.dropped, 0u);
  EXPECT_GE(s.high_water, 1u);
  EXPECT_LE(s.high_water, kCapacity);
}

TEST(SampleRing, FullRingDropsExactlyTheOverflowAndKeepsTheOldest) {
  constexpr std::size_t kCapacity = 100;
  constexpr std::uint64_t kOverflow = 37;
  SampleRing<Item> ring("test", kCapacity);
  std::atomic<bool> pushed_all{false};
  std::vector<bool> push_results;

  // The consumer thread waits until the producer thread has pushed capacity + overflow.
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kCapacity + kOverflow; ++i) {
      Item item;
      item.sequence = i;
      push_results.push_back(ring.push(item));
    }
    pushed_all.store(true, std::memory_order_release);
  });
  std::vector<std::uint64_t> received;
  std::thread consumer([&] {
    while (!pushed_all.load(std::memory_order_acquire)) std::this_thread::yield();
    ring.drain([&](const Item& item) { received.push_back(item.sequence); });
  });
  producer.join();
  consumer.join();

  const RingStats s = ring.stats();
  EXPECT_EQ(s.dropped, kOverflow);
  EXPECT_EQ(s.pushed, kCapacity);
  EXPECT_EQ(s.high_water, kCapacity);
  ASSERT_EQ(received.size(), kCapacity);
  for (std::uint64_t i = 0; i < kCapacity; ++i) EXPECT_EQ(received[i], i);  // the newest were dropped
  for (std::uint64_t i = 0; i < kCapacity + kOverflow; ++i) EXPECT_EQ(push_results[i], i < kCapacity) << i;

  // After draining there is room again.
  Item item;
  item.sequence = 999;
  EXPECT_TRUE(ring.push(item));
  EXPECT_EQ(ring.stats().dropped, kOverflow);
}

TEST(SampleRing, DrainTakesOnlyWhatWasThereAtTheStart) {
  SampleRing<Item> ring("test", 8);
  for (std::uint64_t i = 0; i < 3; ++i) ring.push(Item{i, {}});
  std::size_t calls = 0;
  // Pushing from inside the callback (as a fast producer would) does not extend this drain.
  const std::size_t n = ring.drain([&](const Item&) {
    ++calls;
    ring.push(Item{100 + calls, {}});
  });
  EXPECT_EQ(n, 3u);
  EXPECT_EQ(calls, 3u);
  EXPECT_EQ(ring.drain([](const Item&) {}), 3u);
}

TEST(SampleRing, WindowHighWaterIsTheMostWaitingAtADrainSinceItWasLastTaken) {
  SampleRing<Item> ring("test", 16);
  const auto pushAndDrain = [&ring](std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i) ring.push(Item{i, {}});
    ring.drain([](const Item&) {});
  };
  EXPECT_EQ(ring.takeWindowHighWater(), 0u);  // no drain yet
  pushAndDrain(5);
  pushAndDrain(9);
  pushAndDrain(2);
  EXPECT_EQ(ring.takeWindowHighWater(), 9u);
  // A new window: the 9 stays in high_water (since start) only.
  pushAndDrain(3);
  EXPECT_EQ(ring.takeWindowHighWater(), 3u);
  EXPECT_EQ(ring.takeWindowHighWater(), 0u);
  EXPECT_EQ(ring.stats().high_water, 9u);
}

}  // namespace
}  // namespace headingd::daemon
