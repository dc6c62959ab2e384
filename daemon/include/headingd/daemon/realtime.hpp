#pragma once
// Optional real-time settings from [realtime]. Each one that the system refuses is logged
// with what would permit it, and the daemon carries on without it.
#include "headingd/daemon/config.hpp"

namespace headingd::daemon {

// For the calling thread (the estimator thread): SCHED_FIFO priority and CPU affinity.
void applyThreadRealtime(const RealtimeConfig& config);
// For the process, before threads start: mlockall.
void applyMemoryLock(const RealtimeConfig& config);

}  // namespace headingd::daemon
