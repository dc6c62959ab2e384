#pragma once
// The [realtime] settings, applied where they belong: mlockall for the process before any
// thread starts, SCHED_FIFO (and CPU affinity) for the estimator thread, the same priority for
// the LCM sender thread that sends what the estimator publishes, SCHED_FIFO at a priority of
// their own for the source threads that read at real-time pace. Each thread sets
// its own policy as it starts. What the system refuses (no CAP_SYS_NICE or RLIMIT_RTPRIO, a
// cgroup without a real-time budget, no CAP_IPC_LOCK or RLIMIT_MEMLOCK) is said once, with
// what would permit it, and the daemon runs on without it; STATUS reports what each thread
// actually got (read back from the kernel, not taken from the configuration).
#include <atomic>
#include <mutex>
#include <string>

#include "headingd/daemon/config/config.hpp"

namespace headingd::daemon {

// A scheduling policy in use, as STATUS reports it.
struct SchedulingInUse {
  std::string policy;  // "SCHED_FIFO", "SCHED_OTHER", ... ; "" = no such thread (no driver source)
  int priority = 0;    // the real-time priority (0 for SCHED_OTHER)
};

struct RealtimeReport {
  SchedulingInUse estimator;
  SchedulingInUse drivers;  // the weakest of the driver threads' policies
  bool memory_locked = false;
};

const char* schedulingPolicyName(int policy);  // "SCHED_FIFO", "SCHED_OTHER", ...

class RealtimeSettings {
 public:
  explicit RealtimeSettings(RealtimeConfig config) : config_(std::move(config)) {}

  // For the process, before threads start: mlockall (lock_memory).
  void lockMemory();
  // For the calling thread, the estimator's: sched_fifo_priority and cpu_affinity.
  void applyToEstimatorThread();
  // For the calling thread, the LCM sender's: sched_fifo_priority, as the estimator whose
  // messages it sends (not pinned: it runs beside the estimator where there is a second CPU).
  void applyToLcmSenderThread();
  // For the calling thread, one of source `name`'s: driver_fifo_priority.
  void applyToDriverThread(const std::string& name);
  // Any thread.
  RealtimeReport report() const;

 private:
  // Asks for SCHED_FIFO `priority` for the calling thread (0: leaves its policy as it is); a
  // refusal is said once for the whole process.
  void setFifo(int priority, const std::string& thread);

  RealtimeConfig config_;
  std::once_flag refusal_said_;
  std::atomic<int> estimator_policy_{-1}, estimator_priority_{0};
  std::atomic<int> driver_threads_{0}, driver_threads_other_{0}, driver_priority_{0};
  std::atomic<bool> memory_locked_{false};
};

// The calling thread's policy and real-time priority, from the kernel.
SchedulingInUse currentThreadScheduling(int* policy_out = nullptr);

}  // namespace headingd::daemon
