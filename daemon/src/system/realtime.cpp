#include "headingd/daemon/system/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <spdlog/spdlog.h>
#include <sys/mman.h>
#include <algorithm>
#include <cerrno>
#include <cstring>

namespace headingd::daemon {

const char* schedulingPolicyName(int policy) {
  switch (policy) {
    case SCHED_FIFO: return "SCHED_FIFO";
    case SCHED_RR: return "SCHED_RR";
    case SCHED_OTHER: return "SCHED_OTHER";
    case SCHED_BATCH: return "SCHED_BATCH";
    case SCHED_IDLE: return "SCHED_IDLE";
    default: return "unknown";
  }
}

SchedulingInUse currentThreadScheduling(int* policy_out) {
  int policy = SCHED_OTHER;
  sched_param param{};
  if (pthread_getschedparam(pthread_self(), &policy, &param) != 0) policy = SCHED_OTHER;
  if (policy_out != nullptr) *policy_out = policy;
  const bool realtime = policy == SCHED_FIFO || policy == SCHED_RR;
  return SchedulingInUse{schedulingPolicyName(policy), realtime ? param.sched_priority : 0};
}

void RealtimeSettings::setFifo(int priority, const std::string& thread) {
  if (priority <= 0) return;
  sched_param param{};
  param.sched_priority = priority;
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (rc == 0) {
    spdlog::info("{} thread: SCHED_FIFO priority {}", thread, priority);
    return;
  }
  // Every thread meets the same refusal (the process's credentials and limits): said once.
  std::call_once(refusal_said_, [&] {
    const int highest = std::max(config_.sched_fifo_priority, config_.driver_fifo_priority);
    spdlog::warn(
        "real-time scheduling refused: SCHED_FIFO priority {} for the {} thread not permitted ({}); "
        "[realtime] asks for the estimator at {} and the drivers at {}, which needs CAP_SYS_NICE (the unit "
        "grants it) or an RLIMIT_RTPRIO of at least {}, in a cgroup with a real-time budget; continuing "
        "with normal scheduling for the threads refused (STATUS estimator_policy, driver_policy)",
        priority, thread, std::strerror(rc), config_.sched_fifo_priority, config_.driver_fifo_priority, highest);
  });
}

void RealtimeSettings::applyToEstimatorThread() {
  setFifo(config_.sched_fifo_priority, "estimator");
  if (!config_.cpu_affinity.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    std::string list;
    for (const int cpu : config_.cpu_affinity) {
      CPU_SET(static_cast<std::size_t>(cpu), &set);
      list += (list.empty() ? "" : ",") + std::to_string(cpu);
    }
    const int rc = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
    if (rc == 0) {
      spdlog::info("estimator thread: pinned to CPU {}", list);
    } else {
      spdlog::warn(
          "estimator thread: CPU affinity {} refused ({}; does this machine have those CPUs, and does "
          "the cgroup's cpuset allow them?); continuing on any CPU",
          list, std::strerror(rc));
    }
  }
  int policy = SCHED_OTHER;
  estimator_priority_.store(currentThreadScheduling(&policy).priority);
  estimator_policy_.store(policy);
}

void RealtimeSettings::applyToLcmSenderThread() { setFifo(config_.sched_fifo_priority, "LCM sender"); }

void RealtimeSettings::applyToDriverThread(const std::string& name) {
  setFifo(config_.driver_fifo_priority, "source " + name);
  int policy = SCHED_OTHER;
  const SchedulingInUse in_use = currentThreadScheduling(&policy);
  if (policy == SCHED_FIFO || policy == SCHED_RR) {
    driver_priority_.store(in_use.priority);
  } else {
    driver_threads_other_.fetch_add(1);
  }
  driver_threads_.fetch_add(1);
}

void RealtimeSettings::lockMemory() {
  if (!config_.lock_memory) return;
  // MCL_ONFAULT: pages are locked as they are first touched, so thread stacks do not count
  // in full against the resident memory.
  if (mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT) == 0) {
    memory_locked_.store(true);
    spdlog::info("memory locked (mlockall)");
  } else {
    spdlog::warn(
        "mlockall refused ({}); it needs CAP_IPC_LOCK or an RLIMIT_MEMLOCK large enough for the "
        "whole address space (LimitMEMLOCK=infinity in the unit); continuing with pageable memory "
        "(STATUS memory_locked = false)",
        std::strerror(errno));
  }
}

RealtimeReport RealtimeSettings::report() const {
  RealtimeReport r;
  const int estimator = estimator_policy_.load();
  if (estimator >= 0) r.estimator = {schedulingPolicyName(estimator), estimator_priority_.load()};
  if (driver_threads_.load() > 0) {
    r.drivers = driver_threads_other_.load() > 0 ? SchedulingInUse{"SCHED_OTHER", 0}
                                                 : SchedulingInUse{"SCHED_FIFO", driver_priority_.load()};
  }
  r.memory_locked = memory_locked_.load();
  return r;
}

}  // namespace headingd::daemon
