#pragma once
// The writer thread's counters, read by any thread (Recorder::counters()). Only the writer
// thread adds, so relaxed atomics are enough: each counter is exact on its own.
#include <atomic>
#include <cstdint>

namespace headingd::daemon {

struct RecorderTally {
  std::atomic<std::uint64_t> lines_written{0};
  std::atomic<std::uint64_t> bytes_written{0};
  std::atomic<std::uint64_t> lines_dropped_io{0};
  std::atomic<std::uint64_t> write_errors{0};
  std::atomic<std::uint64_t> segments_opened{0};
  std::atomic<std::uint64_t> segments_deleted{0};
  std::atomic<std::uint64_t> bytes_on_disk{0};

  static void add(std::atomic<std::uint64_t>& counter, std::uint64_t n) {
    counter.store(counter.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
  }
};

}  // namespace headingd::daemon
