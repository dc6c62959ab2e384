#pragma once
// The fixture of the fault tests (daemon_faults_test.cpp, daemon_faults_vm_test.cpp): the
// daemon binary started on a configuration, a real LCM subscriber, STATUS read back, and the
// check every fault ends with -- the daemon still runs and stops cleanly on SIGTERM.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "daemon_test_support.hpp"
#include "lcm_collector.hpp"
#include "status_lookup.hpp"

namespace headingd::daemon::test {

class DaemonUnderFault : public ::testing::Test {
 protected:
  // Starts the daemon on dir/faults.toml holding `toml`, with a subscriber on `url`.
  void launch(const std::string& toml, const std::string& url) {
    const std::string config = dir_.write("faults.toml", toml);
    lcm_.emplace(url);
    daemon_.emplace(std::vector<std::string>{HEADINGD_BIN, "--config", config}, dir_.file("out"), dir_.file("err"));
  }
  bool hasStatus() const { return !lcm_->status().empty(); }
  headingd::status_t lastStatus() const { return lcm_->status().back().message; }
  // Waits for the next STATUS and returns it.
  headingd::status_t nextStatus() {
    const std::size_t seen = lcm_->status().size();
    EXPECT_TRUE(waitUntil([&] { return lcm_->status().size() > seen; }, std::chrono::seconds(5)));
    return lastStatus();
  }
  std::string daemonLog() const { return readFile(dir_.file("err")); }
  // The daemon must still run; then SIGTERM, exit 0.
  void expectRunningThenStop() {
    EXPECT_EQ(daemon_->waitFor(std::chrono::milliseconds(0)), -1) << "the daemon exited: " << daemonLog();
    daemon_->signal(SIGTERM);
    EXPECT_EQ(daemon_->waitFor(std::chrono::seconds(5)), 0) << daemonLog();
    lcm_->stop();
  }

  TempDir dir_;
  std::optional<LcmCollector> lcm_;
  std::optional<ChildProcess> daemon_;
};

}  // namespace headingd::daemon::test
