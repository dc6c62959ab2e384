#include "headingd/daemon/realtime.hpp"

#include <cerrno>
#include <cstring>
#include <pthread.h>
#include <sched.h>
#include <spdlog/spdlog.h>
#include <sys/mman.h>

namespace headingd::daemon {

void applyThreadRealtime(const RealtimeConfig& config) {
  if (config.sched_fifo_priority > 0) {
    sched_param param{};
    param.sched_priority = config.sched_fifo_priority;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (rc == 0) {
      spdlog::info("estimator thread: SCHED_FIFO priority {}", config.sched_fifo_priority);
    } else {
      spdlog::warn("estimator thread: SCHED_FIFO priority {} not permitted ({}); it needs CAP_SYS_NICE "
                   "(the unit grants it) or an RLIMIT_RTPRIO of at least {}; continuing with normal scheduling",
                   config.sched_fifo_priority, std::strerror(rc), config.sched_fifo_priority);
    }
  }
  if (!config.cpu_affinity.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    std::string list;
    for (const int cpu : config.cpu_affinity) {
      CPU_SET(static_cast<std::size_t>(cpu), &set);
      list += (list.empty() ? "" : ",") + std::to_string(cpu);
    }
    const int rc = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
    if (rc == 0) {
      spdlog::info("estimator thread: pinned to CPU {}", list);
    } else {
      spdlog::warn("estimator thread: CPU affinity {} refused ({}; does this machine have those CPUs, and does "
                   "the cgroup's cpuset allow them?); continuing on any CPU",
                   list, std::strerror(rc));
    }
  }
}

void applyMemoryLock(const RealtimeConfig& config) {
  if (!config.lock_memory) return;
  // MCL_ONFAULT: pages are locked as they are first touched, so thread stacks do not count
  // in full against the resident memory.
  if (mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT) == 0) {
    spdlog::info("memory locked (mlockall)");
  } else {
    spdlog::warn("mlockall refused ({}); it needs CAP_IPC_LOCK or a large enough RLIMIT_MEMLOCK "
                 "(LimitMEMLOCK= in the unit); continuing with pageable memory",
                 std::strerror(errno));
  }
}

}  // namespace headingd::daemon
