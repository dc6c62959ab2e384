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

// Constant-initialised, in zeroed memory: a program that never writes an output file pays
// nothing for them at start-up (no initialiser touching 256 KiB of pages).
constinit std::atomic<int> g_states[kMaxTemporaryFiles] = {};
char g_paths[kMaxTemporaryFiles][PATH_MAX];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

// Only async-signal-safe calls: unlink, sigaction, raise.
void removeAndDie(int signal_number) {
  for (int i = 0; i < kMaxTemporaryFiles; ++i) {
    if (g_states[i].load(std::memory_order_acquire) == kReady) ::unlink(g_paths[i]);
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
    if (g_states[i].compare_exchange_strong(expected, kClaimed, std::memory_order_acquire)) {
      std::memcpy(g_paths[i], path, length + 1);
      g_states[i].store(kReady, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void forgetOnFatalSignal(int slot) {
  if (slot >= 0 && slot < kMaxTemporaryFiles) g_states[slot].store(kFree, std::memory_order_release);
}

}  // namespace headingd::files
