#include "headingd/files/temporary_file_cleanup.hpp"

#include <limits.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>

namespace headingd::files {
namespace {

// A slot's path is written while the slot is kClaimed and read by the handler only when
// kReady: the handler never sees a path being written.
enum SlotState : int { kFree = 0, kClaimed = 1, kReady = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};

Slot g_slots[kMaxTemporaryFiles];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

// Only async-signal-safe calls: unlink, sigaction, raise.
void removeAndDie(int signal_number) {
  for (Slot& slot : g_slots) {
    if (slot.state.load(std::memory_order_acquire) == kReady) ::unlink(slot.path);
  }
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  ::raise(signal_number);
}

void installHandlersOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int signal_number : kSignals) {
      struct sigaction current {};
      if (::sigaction(signal_number, nullptr, &current) != 0 || current.sa_handler != SIG_DFL) continue;
      struct sigaction action {};
      action.sa_handler = removeAndDie;
      sigemptyset(&action.sa_mask);
      ::sigaction(signal_number, &action, nullptr);
    }
  });
}

}  // namespace

int removeOnFatalSignal(const char* path) {
  const std::size_t length = std::strlen(path);
  if (length >= PATH_MAX) return -1;
  installHandlersOnce();
  for (int i = 0; i < kMaxTemporaryFiles; ++i) {
    int expected = kFree;
    if (g_slots[i].state.compare_exchange_strong(expected, kClaimed, std::memory_order_acquire)) {
      std::memcpy(g_slots[i].path, path, length + 1);
      g_slots[i].state.store(kReady, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void forgetOnFatalSignal(int slot) {
  if (slot >= 0 && slot < kMaxTemporaryFiles) g_slots[slot].state.store(kFree, std::memory_order_release);
}

}  // namespace headingd::files
