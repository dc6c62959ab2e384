#pragma once
// "Something is here for you", from producer threads to a consumer thread: from the source
// threads to the estimator thread for [daemon] publish = "imu", from the estimator thread to
// the LCM sender. A counter the producers bump, on which the consumer sleeps (a futex)
// until it changes (or a deadline passes). ring() never blocks and never allocates: one
// atomic add and one FUTEX_WAKE system call.
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>
#include <atomic>
#include <cstdint>
#include <ctime>

namespace headingd::daemon {

class Doorbell {
 public:
  // Any thread.
  void ring() noexcept {
    count_.fetch_add(1, std::memory_order_release);
    syscall(SYS_futex, word(), FUTEX_WAKE_PRIVATE, 1, nullptr, nullptr, 0);
  }
  // Bumps the count without waking anyone: for a consumer that looks on a timer of its own
  // (no system call here, and no cross-CPU interrupt, which costs tens of microseconds on a
  // busy virtual machine).
  void post() noexcept { count_.fetch_add(1, std::memory_order_release); }
  std::uint32_t count() const noexcept { return count_.load(std::memory_order_acquire); }
  // Sleeps while the count is still `seen`, at most until `deadline` (CLOCK_MONOTONIC,
  // absolute: FUTEX_WAIT_BITSET's clock). Returns at once when it has changed already.
  void waitWhile(std::uint32_t seen, const timespec& deadline) noexcept {
    syscall(SYS_futex, word(), FUTEX_WAIT_BITSET_PRIVATE, seen, &deadline, nullptr, FUTEX_BITSET_MATCH_ANY);
  }

 private:
  std::uint32_t* word() noexcept { return reinterpret_cast<std::uint32_t*>(&count_); }
  static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));
  std::atomic<std::uint32_t> count_{0};
};

}  // namespace headingd::daemon
