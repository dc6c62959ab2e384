// Real-time by default: headingd with no [realtime] table runs its estimator thread and its
// source threads under SCHED_FIFO and locks its memory where the system permits it, and says
// once and runs on where it does not. Checked from outside: the kernel's view of each thread
// (/proc/<pid>/task/*/stat) and STATUS over real LCM.
#include <gtest/gtest.h>

#include <pthread.h>
#include <sched.h>
#include <unistd.h>
#include <algorithm>
#include <map>
#include <sstream>

#include "daemon_test_support.hpp"
#include "lcm_collector.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

// The daemon's defaults, an IMU file played at real time (its thread reads at real-time pace,
// so it gets the driver priority) and STATUS five times a second. Short: a few seconds.
std::string defaultsConfig(const std::string& url) {
  return "[lcm]\nurl = \"" + url + "\"\n[daemon]\nstatus_period_s = 0.2\n[imu_csv]\nenabled = true\npath = \"" +
         kDemoImuCsv + "\"\n";
}

struct ThreadScheduling {
  int policy = -1;
  int rt_priority = -1;
};

// Each thread of `pid` by name (comm), with its policy and real-time priority: fields 40
// and 41 of /proc/<pid>/task/<tid>/stat (proc(5)), counted after the comm's closing ')'.
std::map<std::string, ThreadScheduling> threadsOf(pid_t pid) {
  std::map<std::string, ThreadScheduling> threads;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task", ec)) {
    const std::string stat = test::readFile(task.path().string() + "/stat");
    const auto open = stat.find('('), close = stat.rfind(')');
    if (open == std::string::npos || close == std::string::npos) continue;
    std::istringstream rest(stat.substr(close + 2));  // field 3 onwards
    std::string field;
    ThreadScheduling s;
    for (int n = 3; rest >> field; ++n) {
      if (n == 40) s.rt_priority = std::stoi(field);
      if (n == 41) s.policy = std::stoi(field);
    }
    threads[stat.substr(open + 1, close - open - 1)] = s;
  }
  return threads;
}

// Whether this process may use SCHED_FIFO: asked on a thread of its own, which then ends.
bool fifoPermittedHere() {
  int rc = -1;
  std::thread probe([&] {
    sched_param p{};
    p.sched_priority = 1;
    rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
  });
  probe.join();
  return rc == 0;
}

TEST(DaemonRealtime, DefaultsRunTheEstimatorAndDriverThreadsUnderFifoWithMemoryLocked) {
  // A user without CAP_SYS_NICE or an RLIMIT_RTPRIO cannot be granted SCHED_FIFO at all (the
  // refusal itself is checked by RefusedSchedulingIsSaidOnce... below, which runs anywhere).
  if (!fifoPermittedHere()) GTEST_SKIP() << "no CAP_SYS_NICE or RLIMIT_RTPRIO here: nothing to grant";
  TempDir dir;
  const std::string url = lcmUrl(20);
  const std::string config = dir.write("defaults.toml", defaultsConfig(url));
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  ASSERT_TRUE(waitUntil([&] { return lcm.status().size() >= 3; }, 5s)) << test::readFile(dir.file("err"));
  const auto threads = threadsOf(daemon.pid());
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(2s), 0);
  lcm.stop();

  // The kernel's view.
  ASSERT_EQ(threads.count("estimator"), 1u) << "the estimator thread names itself";
  EXPECT_EQ(threads.at("estimator").policy, SCHED_FIFO);
  EXPECT_EQ(threads.at("estimator").rt_priority, 50);
  ASSERT_EQ(threads.count("src:imu_csv"), 1u);
  EXPECT_EQ(threads.at("src:imu_csv").policy, SCHED_FIFO);
  EXPECT_EQ(threads.at("src:imu_csv").rt_priority, 55);
  ASSERT_EQ(threads.count("lcm-send"), 1u) << "the LCM sender, at the estimator's priority";
  EXPECT_EQ(threads.at("lcm-send").policy, SCHED_FIFO);
  EXPECT_EQ(threads.at("lcm-send").rt_priority, 50);
  for (const auto& [name, s] : threads) {
    if (name != "estimator" && name != "src:imu_csv" && name != "lcm-send") {
      EXPECT_EQ(s.policy, SCHED_OTHER) << name;
    }
  }
  // STATUS says the same.
  const headingd::status_t s = lcm.status().back().message;  // a copy: status() returns one
  EXPECT_EQ(s.estimator_policy, "SCHED_FIFO");
  EXPECT_EQ(s.estimator_priority, 50);
  EXPECT_EQ(s.driver_policy, "SCHED_FIFO");
  EXPECT_EQ(s.driver_priority, 55);
  EXPECT_TRUE(s.memory_locked);
  const std::string err = test::readFile(dir.file("err"));
  EXPECT_EQ(err.find("refused"), std::string::npos) << err;
}

// A file played faster than real time decodes as fast as it can: its thread keeps normal
// scheduling, so that it cannot hold a CPU; STATUS says there is no driver thread.
TEST(DaemonRealtime, FileSourcePlayedFasterThanRealTimeKeepsNormalScheduling) {
  // Only where SCHED_FIFO can be granted is it meaningful that this thread does not get it.
  if (!fifoPermittedHere()) GTEST_SKIP() << "no CAP_SYS_NICE or RLIMIT_RTPRIO here";
  TempDir dir;
  const std::string url = lcmUrl(21);
  const std::string config = dir.write("fast.toml", defaultsConfig(url) + "speed = 4.0\n");
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  ASSERT_TRUE(waitUntil([&] { return lcm.status().size() >= 2; }, 5s)) << test::readFile(dir.file("err"));
  const auto threads = threadsOf(daemon.pid());
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(2s), 0);
  lcm.stop();
  ASSERT_EQ(threads.count("src:imu_csv"), 1u);
  EXPECT_EQ(threads.at("src:imu_csv").policy, SCHED_OTHER);
  EXPECT_EQ(threads.at("estimator").policy, SCHED_FIFO);
  const headingd::status_t s = lcm.status().back().message;  // a copy: status() returns one
  EXPECT_EQ(s.estimator_policy, "SCHED_FIFO");
  EXPECT_EQ(s.driver_policy, "");
  EXPECT_EQ(s.driver_priority, 0);
}

// Without the privileges (root without capabilities and with RLIMIT_RTPRIO 0 and a small
// RLIMIT_MEMLOCK, or any user who is not root), the refusal is said once for every thread
// and the daemon runs on with normal scheduling, which STATUS reports.
TEST(DaemonRealtime, RefusedSchedulingIsSaidOnceAndTheDaemonRunsOnWithNormalScheduling) {
  TempDir dir;
  const std::string url = lcmUrl(22);
  const std::string config = dir.write("defaults.toml", defaultsConfig(url));
  std::vector<std::string> argv = {"/usr/bin/prlimit", "--rtprio=0:0", "--memlock=65536:65536", "--"};
  if (geteuid() == 0) {
    for (const char* a : {"/usr/bin/setpriv", "--inh-caps=-all", "--bounding-set=-all", "--"}) argv.emplace_back(a);
  }
  for (const std::string& a : {std::string(HEADINGD_BIN), std::string("--config"), config}) argv.push_back(a);
  LcmCollector lcm(url);
  ChildProcess daemon(argv, dir.file("out"), dir.file("err"));
  ASSERT_TRUE(waitUntil([&] { return lcm.status().size() >= 3; }, 5s)) << test::readFile(dir.file("err"));
  const auto threads = threadsOf(daemon.pid());
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(2s), 0);
  lcm.stop();

  for (const auto& [name, s] : threads) EXPECT_EQ(s.policy, SCHED_OTHER) << name;
  const headingd::status_t s = lcm.status().back().message;  // a copy: status() returns one
  EXPECT_EQ(s.estimator_policy, "SCHED_OTHER");
  EXPECT_EQ(s.estimator_priority, 0);
  EXPECT_EQ(s.driver_policy, "SCHED_OTHER");
#ifndef __SANITIZE_ADDRESS__
  // Under AddressSanitizer mlockall is intercepted: a no-op that succeeds (locking the shadow
  // memory would take terabytes), so the refusal cannot be seen there.
  EXPECT_FALSE(s.memory_locked);
#endif
  EXPECT_EQ(s.state, "ok");
  EXPECT_FALSE(lcm.heading().empty());
  const std::string err = test::readFile(dir.file("err"));
  const auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (auto at = err.find(what); at != std::string::npos; at = err.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("real-time scheduling refused"), 1u) << err;
  EXPECT_EQ(count("continuing with normal scheduling"), 1u) << err;
#ifndef __SANITIZE_ADDRESS__
  EXPECT_EQ(count("mlockall refused"), 1u) << err;
#endif
}

// [daemon] publish = "imu": besides the tick's, HEADING goes out as each IMU sample arrives,
// so there is about one HEADING per IMU sample on top of the ticks', and the newest sample
// is much younger at publish than a tick period.
TEST(DaemonRealtime, PublishOnImuSendsAHeadingForEachSampleAsItArrives) {
  TempDir dir;
  const std::string url = lcmUrl(23);
  const std::string config = dir.write(
      "imu.toml", "[lcm]\nurl = \"" + url + "\"\n[daemon]\npublish = \"imu\"\n[imu_csv]\nenabled = true\npath = \"" +
                      kDemoImuCsv + "\"\n");
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  ASSERT_TRUE(waitUntil([&] { return lcm.imu().size() >= 500; }, 5s)) << test::readFile(dir.file("err"));
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(2s), 0);
  lcm.stop();
  const auto headings = lcm.heading();
  const auto imu = lcm.imu();
  // 286 samples/s and 100 ticks/s: about 386 HEADING a second for 286 IMU.
  EXPECT_GT(static_cast<double>(headings.size()), 1.2 * static_cast<double>(imu.size()))
      << headings.size() << " HEADING, " << imu.size() << " IMU";
  std::vector<std::int64_t> ages;
  for (const auto& h : headings) {
    if (h.message.validity == headingd::heading_t::VALIDITY_FRESH) ages.push_back(h.message.sample_age_us);
  }
  ASSERT_FALSE(ages.empty());
  std::sort(ages.begin(), ages.end());
  // Each sample's HEADING is published at once, so most are far younger than the IMU
  // period (3.5 ms) the tick's phase alone would give (median 1.8 ms there).
  EXPECT_LT(ages[ages.size() / 2], 1000) << "median sample age, us";
}

}  // namespace
}  // namespace headingd::daemon
