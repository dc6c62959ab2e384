#pragma once
// sd_notify(3) for Type=notify: READY=1, STATUS=, STOPPING=1, and watchdog pings
// (WatchdogSec= in the unit sets WATCHDOG_USEC; we ping at half that interval). Outside
// systemd (no NOTIFY_SOCKET) every call does nothing.
#include <cstdint>
#include <string>

namespace headingd::daemon {

class SystemdNotifier {
 public:
  SystemdNotifier();
  bool underSystemd() const { return enabled_; }
  std::uint64_t watchdogIntervalUs() const { return watchdog_us_; }

  void ready();
  void stopping();
  void status(const std::string& text);
  // Sends WATCHDOG=1 when half the watchdog interval has passed since the last ping.
  void watchdogPing(std::int64_t mono_ns);

 private:
  bool enabled_ = false;
  std::uint64_t watchdog_us_ = 0;
  std::int64_t last_ping_ns_ = 0;
};

}  // namespace headingd::daemon
