#pragma once
// An input of the daemon: something that runs its own thread(s) (or I/O loop) and pushes
// IMU samples and GPS epochs into its rings (sample_ring.hpp). The estimator thread never
// calls into a source except for report(), once per status period.
//
// A driver plugs in by wrapping its callback in a Source: construct it with the rings the
// daemon made for it, push from the callback (SampleRing::push never blocks), and describe
// its state and counters in report().
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace headingd::daemon {

enum class SourceState { kStarting, kRunning, kWaiting, kFinished, kError };
const char* sourceStateName(SourceState s);  // "starting", "running", "waiting", "finished", "error"

struct NamedCounter {
  std::string name;
  std::uint64_t value = 0;
};

// A snapshot for STATUS. Reused from period to period (strings keep their capacity).
struct SourceReport {
  SourceState state = SourceState::kStarting;
  std::string last_error;  // "" if none
  std::vector<NamedCounter> counters;

  // Sets counter `i` (appending the first time), so a report can be refilled in place.
  void set(std::size_t i, std::string_view name, std::uint64_t value);
  // The same with the name `prefix` + `name` (e.g. "nmea_" + "bytes").
  void set(std::size_t i, std::string_view prefix, std::string_view name, std::uint64_t value);
  // The driver's last error (copied only when it changed: no allocation per report).
  void setLastError(const std::string& error) {
    if (last_error != error) last_error = error;
  }
};

class Source {
 public:
  virtual ~Source() = default;
  virtual const std::string& name() const = 0;  // as configured, e.g. "imu_csv"
  virtual const char* kind() const = 0;         // "imu_csv", "can", "gps_serial", ...

  // Starts the source's thread(s); returns at once. Throws only for errors that make the
  // source unusable for good (a missing device is not one: it waits and retries).
  virtual void start() = 0;
  // Asks the threads to stop and joins them; returns within a fraction of a second.
  virtual void stop() = 0;
  // Any thread. Fills `out` with the current state and counters.
  virtual void report(SourceReport& out) const = 0;
  // True once the source has finished and asks the daemon to stop (a file played to the
  // end with at_end = "exit").
  virtual bool wantsExit() const { return false; }
  // True while a file source still has data to play. The daemon stops for a source that
  // wants to exit only once no file source is playing any more.
  virtual bool playing() const { return false; }

  // True when the source's threads read at real-time pace: a device, or a file played at
  // speed 1 or slower. Those threads run at [realtime] driver_fifo_priority (realtime.hpp); a
  // file played faster decodes as fast as it can and keeps normal scheduling, so that it
  // cannot hold a CPU from the rest of the machine.
  virtual bool readsAtRealTimePace() const = 0;
  // Set before start(): called first on each thread the source starts (the daemon's
  // scheduling for driver threads).
  void setThreadStartHook(std::function<void()> hook) { thread_start_hook_ = std::move(hook); }

 protected:
  void runThreadStartHook() const {
    if (thread_start_hook_) thread_start_hook_();
  }

 private:
  std::function<void()> thread_start_hook_;
};

}  // namespace headingd::daemon
