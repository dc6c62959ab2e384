#include "headingd/daemon/system/systemd_notify.hpp"

#include <systemd/sd-daemon.h>
#include <cstdlib>

namespace headingd::daemon {

SystemdNotifier::SystemdNotifier() {
  enabled_ = std::getenv("NOTIFY_SOCKET") != nullptr;
  std::uint64_t usec = 0;
  if (enabled_ && sd_watchdog_enabled(0, &usec) > 0) watchdog_us_ = usec;
}

void SystemdNotifier::ready() {
  if (enabled_) sd_notify(0, "READY=1");
}

void SystemdNotifier::stopping() {
  if (enabled_) sd_notify(0, "STOPPING=1");
}

void SystemdNotifier::status(const std::string& text) {
  if (enabled_) sd_notifyf(0, "STATUS=%s", text.c_str());
}

void SystemdNotifier::watchdogPing(std::int64_t mono_ns) {
  if (watchdog_us_ == 0) return;
  if (mono_ns - last_ping_ns_ < static_cast<std::int64_t>(watchdog_us_) * 500) return;  // half, in ns
  last_ping_ns_ = mono_ns;
  sd_notify(0, "WATCHDOG=1");
}

}  // namespace headingd::daemon
