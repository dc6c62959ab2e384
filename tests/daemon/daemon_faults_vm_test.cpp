// Faults that need the kernel's CAN and the right to set the clock, injected while the daemon
// runs on vcan0 (tools/scripts/vm-run.sh with HEADINGD_VM=force: a throwaway VM, so stepping
// CLOCK_REALTIME never touches the host's clock). Each ends with the daemon running and its
// STATUS counters saying what happened:
//   - vcan0 taken down and up: the CAN source loses the link, waits, reopens, resumes;
//   - a CAN flood beyond the IMU ring's capacity: every dropped frame and sample counted, the
//     estimator keeps its ticks;
//   - CLOCK_REALTIME stepped by +1 h and back: the estimate does not notice, LCM utime follows.
// The bus is a candump log of BROAD trial 05 (headingd's own frame set) played in a loop by
// CanFrameSender, which unlike canplayer survives the interface going down.
#include <gtest/gtest.h>

#include <net/if.h>
#include <sys/stat.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "can_frame_sender.hpp"
#include "daemon_under_fault.hpp"
#include "vcan_test_support.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

constexpr int kRows = 2857;  // the first 10 s of BROAD trial 05 (286 Hz, three frames a sample)
const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0";  // alone in the VM's network

const headingd::source_status_t* canSource(const headingd::status_t& m) { return test::findSource(m, "can"); }

void printCanCounters(const char* when, const headingd::status_t& m) {
  const auto* can = canSource(m);
  if (can == nullptr) return;
  std::fprintf(stderr, "%s: can %s (%s):", when, can->state.c_str(), can->last_error.c_str());
  for (const auto& c : can->counters) {
    if (c.value != 0) std::fprintf(stderr, " %s=%lld", c.name.c_str(), static_cast<long long>(c.value));
  }
  std::fprintf(stderr, " | ring %s capacity %d high_water %d pushed %lld dropped %lld | ticks %lld misses %lld\n",
               m.rings[0].name.c_str(), m.rings[0].capacity, m.rings[0].high_water,
               static_cast<long long>(m.rings[0].pushed), static_cast<long long>(m.rings[0].dropped),
               static_cast<long long>(m.ticks), static_cast<long long>(m.deadline_misses));
}

int ip(const std::string& args) { return std::system(("ip " + args).c_str()); }

class DaemonFaultsVm : public test::DaemonUnderFault {
 protected:
  void SetUp() override {
    if (if_nametoindex("vcan0") == 0) GTEST_SKIP() << "no vcan0: run through tools/scripts/vm-run.sh";
    const std::string cmd = std::string("zcat ") + HEADINGD_CONFIG_DIR +
                            "/demo/05_undisturbed_slow_rotation_with_breaks_B.csv.gz | head -n " +
                            std::to_string(kRows + 1) + " > " + dir_.file("imu.csv");
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    can_table_ = test::vcanCanTable(HEADINGD_CONFIG_DIR);
    test::writeCandumpLog(dir_, HEADINGD_CANDUMP_FROM_CSV_BIN, can_table_, dir_.file("imu.csv"));
  }

  // Starts the daemon on vcan0 (with `extra` TOML) and waits until its CAN source runs.
  void startDaemon(const std::string& extra = "") {
    launch("[daemon]\nimu_timeout_s = 0.5\n[lcm]\nurl = \"" + kUrl + "\"\n" + extra + "\n" + can_table_, kUrl);
    ASSERT_TRUE(waitUntil(
        [&] {
          if (!hasStatus()) return false;
          const headingd::status_t s = lastStatus();
          return canSource(s) != nullptr && canSource(s)->state == "running";
        },
        20s))
        << daemonLog();
  }

  // Starts the daemon (startDaemon, with `extra`) and the bus (imu.log onto vcan0 in a loop);
  // returns the STATUS after 2 s of frames, printed as `label`.
  headingd::status_t startSending(const char* label, const std::string& extra = "") {
    startDaemon(extra);
    bus_.emplace(dir_.file("imu.log"), "vcan0");
    bus_->start();
    std::this_thread::sleep_for(2s);
    const headingd::status_t before = nextStatus();
    printCanCounters(label, before);
    return before;
  }

  std::string can_table_;
  std::optional<test::CanFrameSender> bus_;
};

TEST_F(DaemonFaultsVm, InterfaceDownAndUpIsWaitedOutCountedAndReceivingResumes) {
  const headingd::status_t before = startSending("before down");
  ASSERT_EQ(ip("link set vcan0 down"), 0);
  const bool lost = waitUntil([&] { return canSource(lastStatus())->state != "running"; }, 5s);
  std::this_thread::sleep_for(2s);
  const headingd::status_t down = nextStatus();
  printCanCounters("down", down);
  ASSERT_EQ(ip("link set vcan0 up"), 0);
  const std::int64_t samples_at_up = counter(*canSource(down), "samples_pushed");
  const bool resumed = waitUntil(
      [&] {
        const headingd::status_t now = lastStatus();
        const auto* can = canSource(now);
        return can->state == "running" && counter(*can, "samples_pushed") > samples_at_up + 500;
      },
      20s);
  const headingd::status_t after = nextStatus();
  printCanCounters("after up", after);
  bus_->stop();
  std::fprintf(stderr, "sender: %llu frames sent, %llu refused while down\n",
               static_cast<unsigned long long>(bus_->sent()), static_cast<unsigned long long>(bus_->sendErrors()));

  EXPECT_TRUE(lost) << "the CAN source never left running";
  EXPECT_EQ(canSource(down)->state, "waiting");
  EXPECT_NE(canSource(down)->last_error.find("vcan0"), std::string::npos) << canSource(down)->last_error;
  EXPECT_EQ(down.state, "degraded") << down.reason;
  ASSERT_TRUE(resumed) << daemonLog();
  const auto* can = canSource(after);
  EXPECT_EQ(counter(*can, "times_lost"), 1);
  EXPECT_EQ(counter(*can, "times_up"), 2);
  EXPECT_GE(counter(*can, "read_errors") + counter(*can, "open_failures"), 1);
  EXPECT_GT(bus_->sendErrors(), 0u);
  EXPECT_EQ(after.state, "ok") << after.reason;
  const auto heading = lcm_->heading();
  ASSERT_FALSE(heading.empty());
  EXPECT_EQ(heading.back().message.validity, 1) << "fresh estimates again after the interface came back";
  expectRunningThenStop();
}

TEST_F(DaemonFaultsVm, FloodBeyondTheRingIsDroppedAndCountedAndTheEstimatorKeepsItsTicks) {
  constexpr int kRingCapacity = 64;
  // The estimator thread under SCHED_FIFO, as the shipped unit may run it (root in the VM):
  // the flood's reader thread and the sender must not starve it.
  const headingd::status_t before =
      startSending("before flood", "[rings]\nimu_capacity = " + std::to_string(kRingCapacity) +
                                       "\n[realtime]\nsched_fifo_priority = 50\n");
  // The flood's window on the wall clock, which HEADING's utime (publish time) is on: the count
  // below is of what the daemon published then, not of when this process, starved by the flood
  // on the emulated CPUs, got round to receiving it.
  const auto wallUs = [] {
    return std::chrono::duration<double, std::micro>(std::chrono::system_clock::now().time_since_epoch()).count();
  };
  const double flood_start_us = wallUs();
  bus_->setFlood(true);
  std::this_thread::sleep_for(3s);
  bus_->setFlood(false);
  const double flood_end_us = wallUs();
  const headingd::status_t during = nextStatus();
  printCanCounters("flood", during);
  std::this_thread::sleep_for(2s);
  const headingd::status_t paced_again = nextStatus();
  bus_->stop();
  std::this_thread::sleep_for(500ms);  // the last frames through
  const headingd::status_t after = nextStatus();
  printCanCounters("after flood", after);

  // Every frame the bus carried was either received or counted as dropped by the kernel.
  const auto* can = canSource(after);
  std::fprintf(stderr, "sender: %llu frames sent\n", static_cast<unsigned long long>(bus_->sent()));
  EXPECT_EQ(static_cast<std::uint64_t>(counter(*can, "frames") + counter(*can, "kernel_drops")), bus_->sent());
  // Every sample assembled was either pushed or counted as dropped at the full ring; the ring
  // and the source agree; the ring filled, and no further.
  const auto& ring = after.rings[0];
  EXPECT_GT(ring.dropped, 0) << "the flood did not overflow the ring";
  EXPECT_EQ(ring.dropped, counter(*can, "ring_full_drops"));
  EXPECT_EQ(ring.pushed, counter(*can, "samples_pushed"));
  EXPECT_EQ(counter(*can, "samples_pushed") + counter(*can, "ring_full_drops"), counter(*can, "samples"));
  EXPECT_EQ(ring.high_water, kRingCapacity);
  // Every sample through the ring went to the estimator, used or rejected (and counted), but
  // those still in the ring when STATUS was filled.
  const std::int64_t estimated = statusCounter(after, "samples_accepted") + statusCounter(after, "imu_rejected");
  EXPECT_LE(estimated, ring.pushed);
  EXPECT_GE(estimated, ring.pushed - kRingCapacity);

  // The estimator's rate, by the daemon's own account (STATUS): between the STATUS before the
  // flood and the one after it each period ran a tick or was counted as a missed deadline.
  const double status_span_s = static_cast<double>(during.utime - before.utime) * 1e-6;
  const auto ticks = static_cast<double>(during.ticks - before.ticks);
  const auto misses = static_cast<double>(during.deadline_misses - before.deadline_misses);
  // What reached this process over UDP in the flood's window on the wall clock (HEADING's utime
  // is its publish time). This process shares the two emulated CPUs with the flood and the
  // daemon, so its socket may overflow: that loss is the receiver's, and the bound is looser
  // than the daemon's own rate below (received in the flood, five clean-clone runs: 74, 82,
  // 84, 93 % and a pass; 0.75 failed once at 74 % while STATUS said 100.1 Hz published).
  std::size_t heading_in_flood = 0;
  for (const auto& h : lcm_->heading()) {
    const auto utime = static_cast<double>(h.message.utime);
    heading_in_flood += utime >= flood_start_us && utime < flood_end_us;
  }
  const double flood_s = (flood_end_us - flood_start_us) * 1e-6;
  std::fprintf(
      stderr,
      "STATUS span %.2f s: %.0f ticks, %.0f missed deadlines (rate %.0f Hz); flood %.2f s: %zu HEADING received; "
      "HEADING rate on STATUS %.1f Hz before, %.1f Hz in the flood\n",
      status_span_s, ticks, misses, after.rate_hz, flood_s, heading_in_flood, before.heading_rate_hz,
      during.heading_rate_hz);
  EXPECT_GE(ticks + misses, status_span_s * after.rate_hz * 0.9);
  EXPECT_GE(static_cast<double>(heading_in_flood), flood_s * after.rate_hz * 0.6);
  EXPECT_GE(during.heading_rate_hz, 0.75 * std::min(before.heading_rate_hz, after.rate_hz));
  EXPECT_EQ(paced_again.state, "ok") << paced_again.reason;
  expectRunningThenStop();
}

// Only in the throwaway VM: vm-run.sh's job folder /run/headingd-vm exists nowhere else.
bool inThrowawayVm() {
  struct stat st {};
  return ::stat("/run/headingd-vm/run.sh", &st) == 0;
}

std::int64_t realtimeNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return ts.tv_sec * 1'000'000'000LL + ts.tv_nsec;
}
bool stepRealtime(std::int64_t by_ns) {
  const std::int64_t t = realtimeNowNs() + by_ns;
  const timespec ts{static_cast<time_t>(t / 1'000'000'000), static_cast<long>(t % 1'000'000'000)};
  return clock_settime(CLOCK_REALTIME, &ts) == 0;
}

TEST_F(DaemonFaultsVm, WallClockSteppedAnHourForwardAndBackChangesUtimeButNotTheEstimate) {
  if (!inThrowawayVm()) GTEST_SKIP() << "steps CLOCK_REALTIME: only in the VM of vm-run.sh (HEADINGD_VM=force)";
  constexpr std::int64_t kHourNs = 3600LL * 1'000'000'000;
  const headingd::status_t before = startSending("before the steps");
  ASSERT_TRUE(stepRealtime(kHourNs)) << "clock_settime: " << std::strerror(errno);
  std::this_thread::sleep_for(2500ms);
  ASSERT_TRUE(stepRealtime(-kHourNs)) << "clock_settime: " << std::strerror(errno);
  std::this_thread::sleep_for(2500ms);
  const headingd::status_t still = nextStatus();
  bus_->stop();
  std::this_thread::sleep_for(300ms);
  const headingd::status_t after = nextStatus();
  printCanCounters("after the steps", after);

  // utime follows the wall clock: against the subscriber's monotonic receive time it is
  // shifted by +1 h between the steps, and back after them.
  const auto heading = lcm_->heading();
  ASSERT_GT(heading.size(), 400u);
  const double base_us = static_cast<double>(heading.front().message.utime) - heading.front().receive_s * 1e6;
  std::size_t shifted = 0, back = 0, other = 0;
  bool seen_shift = false;
  std::int64_t max_sample_step_us = 0;
  std::size_t sample_time_went_back = 0;
  for (std::size_t i = 0; i < heading.size(); ++i) {
    const double shift_s =
        (static_cast<double>(heading[i].message.utime) - heading[i].receive_s * 1e6 - base_us) * 1e-6;
    if (std::abs(shift_s - 3600.0) < 0.5) {
      ++shifted;
      seen_shift = true;
    } else if (std::abs(shift_s) < 0.5) {
      back += seen_shift;
    } else {
      ++other;
    }
    // The estimate's own time axis (the samples', CLOCK_MONOTONIC) runs on without a jump.
    if (i > 0 && heading[i].message.validity == 1 && heading[i - 1].message.validity == 1) {
      const std::int64_t step = heading[i].message.sample_utime - heading[i - 1].message.sample_utime;
      max_sample_step_us = std::max(max_sample_step_us, step);
      sample_time_went_back += step < 0;
    }
  }
  std::fprintf(stderr,
               "HEADING: %zu with utime +1 h, %zu back after the second step, %zu neither; largest "
               "sample_utime step between fresh estimates %.3f s\n",
               shifted, back, other, static_cast<double>(max_sample_step_us) * 1e-6);
  EXPECT_GT(shifted, 100u);
  EXPECT_GT(back, 100u);
  // The sample time never goes back, and it advanced as the monotonic clock did (the largest
  // step is the emulated CPU's stalls, up to a few tenths of a second; the estimator's gaps
  // counter below says whether the samples themselves had one).
  EXPECT_EQ(sample_time_went_back, 0u);
  const auto first_fresh =
      std::find_if(heading.begin(), heading.end(), [](const auto& h) { return h.message.validity == 1; });
  ASSERT_NE(first_fresh, heading.end());
  // The last sample's first estimate, not the last message: after the bus stops the daemon
  // goes on publishing the last estimate (stale) while the receive time runs on.
  const auto last_it = std::find_if(heading.begin(), heading.end(), [&](const auto& h) {
    return h.message.sample_utime == heading.back().message.sample_utime;
  });
  const auto& last = *last_it;
  const double sample_span_s =
      static_cast<double>(last.message.sample_utime - first_fresh->message.sample_utime) * 1e-6;
  EXPECT_NEAR(sample_span_s, last.receive_s - first_fresh->receive_s, 1.0);
  // The estimator saw no time going back, no jump and no duplicate; the CAN source saw both steps.
  for (const char* name : {"backwards_time", "clock_jumps", "duplicate_time", "gaps", "imu_rejected"}) {
    EXPECT_EQ(statusCounter(after, name), statusCounter(before, name)) << name;
  }
  const auto* can = canSource(after);
  EXPECT_EQ(counter(*can, "wall_clock_steps"), 2);
  EXPECT_EQ(counter(*can, "future_timestamps"), 0);
  EXPECT_EQ(still.state, "ok") << still.reason;
  EXPECT_NEAR(static_cast<double>(after.utime) * 1e-6, static_cast<double>(realtimeNowNs()) * 1e-9, 5.0);
  expectRunningThenStop();
}

}  // namespace
}  // namespace headingd::daemon
