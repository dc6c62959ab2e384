// Faults injected while the daemon runs, without a kernel feature this host lacks: the IMU is
// the bundled BROAD trial played on CLOCK_MONOTONIC ([imu_csv] time_axis = "monotonic"), the
// GPS a real pty fed the demo's NMEA. Each ends with the daemon running and its STATUS
// counters saying what happened:
//   - the GPS pty closed (the receiver unplugged) and a new one behind the same path;
//   - the daemon SIGSTOPped for 2 s and continued: it resumes, counts the missed ticks and
//     does not publish them in a burst;
//   - a full disk under the log file and the black box's folder (a small tmpfs that
//     with-small-tmpfs.sh mounts in a private mount namespace; skipped where that is refused).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "daemon_under_fault.hpp"
#include "pty_fixture.hpp"
#include "vcan_test_support.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

void printCounters(const char* when, const headingd::source_status_t& s) {
  std::fprintf(stderr, "%s: %s %s (%s):", when, s.name.c_str(), s.state.c_str(), s.last_error.c_str());
  for (const auto& c : s.counters) {
    if (c.value != 0 && c.name.rfind("nmea_", 0) != 0) {
      std::fprintf(stderr, " %s=%lld", c.name.c_str(), static_cast<long long>(c.value));
    }
  }
  std::fprintf(stderr, "\n");
}

double steadyNowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void writeText(headingd::test::PtyPair& pty, const std::string& text) {
  pty.write({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

// The daemon on the trial and (optionally) a GPS device path, with `extra` TOML.
class DaemonFaults : public test::DaemonUnderFault {
 protected:
  void startDaemon(const std::string& gps_device, const std::string& extra = "") {
    std::string toml = "[daemon]\nimu_timeout_s = 0.5\n[lcm]\nurl = \"" + url_ +
                       "\"\n[imu_csv]\nenabled = true\npath = \"" + kDemoImuCsv + "\"\ntime_axis = \"monotonic\"\n";
    if (!gps_device.empty()) {
      toml += "[gps]\ndevice = \"" + gps_device +
              "\"\nbaud = 9600\nepoch_idle_s = 0.1\nreopen_backoff_initial_s = 0.05\nreopen_backoff_max_s = 0.2\n";
    }
    launch(toml + extra, url_);
    ASSERT_TRUE(waitUntil([&] { return hasStatus() && lastStatus().state == "ok"; }, 10s)) << daemonLog();
  }
  std::optional<headingd::source_status_t> gpsSource() const {
    const auto s = lcm_->status();
    const auto* gps = s.empty() ? nullptr : findSource(s.back().message, "gps_serial");
    if (gps == nullptr) return std::nullopt;
    return *gps;
  }

  std::string url_ = lcmUrl(20);
};

TEST_F(DaemonFaults, GpsPtyClosedAndAnotherBehindTheSamePathIsReconnectedAndCounted) {
  const std::vector<std::string> epochs = test::nmeaEpochs(kDemoNmea, 12);
  ASSERT_GE(epochs.size(), 12u);
  std::optional<headingd::test::PtyPair> pty(std::in_place);
  const std::string link = dir_.file("gps0");
  headingd::test::pointSymlink(link, pty->slavePath());
  startDaemon(link);
  ASSERT_TRUE(waitUntil([&] { return gpsSource() && gpsSource()->state == "running"; }, 5s));
  for (int i = 0; i < 6; ++i) {
    writeText(*pty, epochs[static_cast<std::size_t>(i)]);
    std::this_thread::sleep_for(200ms);
  }
  ASSERT_TRUE(waitUntil([&] { return lcm_->gps().size() >= 6; }, 5s)) << lcm_->gps().size() << " GPS messages";

  // Unplugged: the pty goes away.
  pty.reset();
  ASSERT_TRUE(waitUntil([&] { return gpsSource() && gpsSource()->state != "running"; }, 5s)) << daemonLog();
  const auto unplugged = *gpsSource();
  printCounters("unplugged", unplugged);

  // Plugged in again: another pty, the same path (udev re-points /dev/gps0).
  pty.emplace();
  headingd::test::pointSymlink(link, pty->slavePath());
  ASSERT_TRUE(waitUntil([&] { return gpsSource() && gpsSource()->state == "running"; }, 5s)) << daemonLog();
  for (int i = 6; i < 12; ++i) {
    writeText(*pty, epochs[static_cast<std::size_t>(i)]);
    std::this_thread::sleep_for(200ms);
  }
  EXPECT_TRUE(waitUntil([&] { return lcm_->gps().size() >= 12; }, 5s)) << lcm_->gps().size() << " GPS messages";
  const headingd::status_t after = nextStatus();
  const auto* gps = findSource(after, "gps_serial");
  ASSERT_NE(gps, nullptr);
  printCounters("plugged in again", *gps);

  EXPECT_EQ(unplugged.state, "waiting");
  EXPECT_NE(unplugged.last_error.find(link), std::string::npos) << unplugged.last_error;
  EXPECT_EQ(counter(*gps, "disconnects"), 1);
  EXPECT_EQ(counter(*gps, "reopens"), 1);
  EXPECT_EQ(counter(*gps, "epochs"), 12);
  EXPECT_EQ(counter(*gps, "epochs_pushed"), 12);
  EXPECT_EQ(gps->state, "running");
  EXPECT_EQ(after.state, "ok") << after.reason;
  EXPECT_EQ(statusCounter(after, "gps_epochs"), 12);
  expectRunningThenStop();
}

TEST_F(DaemonFaults, StoppedForTwoSecondsItResumesCountsTheMissedTicksAndDoesNotBurst) {
  startDaemon("");
  std::this_thread::sleep_for(1500ms);
  const headingd::status_t before = nextStatus();
  daemon_->signal(SIGSTOP);
  std::this_thread::sleep_for(2s);
  daemon_->signal(SIGCONT);
  const double continued = steadyNowS();
  std::this_thread::sleep_for(2500ms);
  const headingd::status_t after = nextStatus();

  // HEADING after SIGCONT: at the estimator's rate from the next deadline on, not the 200
  // ticks it missed published at once.
  std::size_t first_half_second = 0, next_second = 0;
  for (const auto& h : lcm_->heading()) {
    const double since = h.receive_s - continued;
    first_half_second += since >= 0.0 && since < 0.5;
    next_second += since >= 0.5 && since < 1.5;
  }
  const auto misses = after.deadline_misses - before.deadline_misses;
  double worst_jitter_us = 0.0;  // the STATUS window that held the stop
  for (const auto& s : lcm_->status()) worst_jitter_us = std::max(worst_jitter_us, s.message.tick_jitter_max_us);
  std::fprintf(stderr,
               "after SIGCONT: %zu HEADING in the first 0.5 s, %zu in the next second; %lld deadlines missed, "
               "tick jitter max %.3f s; ticks %lld -> %lld\n",
               first_half_second, next_second, static_cast<long long>(misses), worst_jitter_us * 1e-6,
               static_cast<long long>(before.ticks), static_cast<long long>(after.ticks));
  EXPECT_LE(first_half_second, 60u) << "missed ticks published in a burst";
  EXPECT_GE(next_second, 70u) << "not back at its rate";
  EXPECT_GE(misses, 190);
  EXPECT_LE(misses, 260);
  EXPECT_GE(worst_jitter_us, 1.9e6);
  // Nothing was lost on the way: the source played on, the ring held the 2 s.
  EXPECT_EQ(after.rings[0].dropped, 0);
  EXPECT_EQ(after.state, "ok") << after.reason;
  EXPECT_EQ(lcm_->heading().back().message.validity, 1);
  expectRunningThenStop();
}

// Fills the file system of `dir` with one file; returns its path.
std::string fillDisk(const std::string& dir) {
  const std::string path = dir + "/filler";
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char> block(4096, 'x');
  while (::write(fd, block.data(), block.size()) > 0) {
  }
  ::close(fd);
  return path;
}

TEST_F(DaemonFaults, FullDiskUnderTheLogFileAndTheRecorderIsCountedAndSurvived) {
  const char* tmpfs = std::getenv("HEADINGD_SMALL_TMPFS");
  if (tmpfs == nullptr) GTEST_SKIP() << "needs a small tmpfs: run through tests/daemon/with-small-tmpfs.sh";
  const std::string disk = tmpfs;
  const std::string log = disk + "/headingd.log";
  const std::vector<std::string> epochs = test::nmeaEpochs(kDemoNmea, 200);
  headingd::test::PtyPair pty;
  startDaemon(pty.slavePath(), "[log]\nfile = \"" + log + "\"\n[recorder]\nenabled = true\ndir = \"" + disk +
                                   "/recordings\"\nsegment_max_bytes = 16384\ntotal_max_bytes = 1048576\n");
  // The GPS talks all along: the black box records its bytes.
  std::atomic<bool> stop_gps{false};
  std::thread gps([&] {
    try {
      for (std::size_t i = 0; !stop_gps.load(); i = (i + 1) % epochs.size()) {
        writeText(pty, epochs[i]);
        std::this_thread::sleep_for(50ms);
      }
    } catch (const std::exception& e) {
      ADD_FAILURE() << "GPS writer: " << e.what();
    }
  });
  std::this_thread::sleep_for(1500ms);
  const headingd::status_t before = nextStatus();
  ASSERT_EQ(statusCounter(before, "log_write_errors"), 0);

  // The disk fills up; each SIGHUP makes the daemon log two lines (and reopen the log file):
  // 40 of them are more than the room left in the log file's last page of the tmpfs.
  const std::string filler = fillDisk(disk);
  for (int i = 0; i < 40; ++i) {
    daemon_->signal(SIGHUP);
    std::this_thread::sleep_for(50ms);
  }
  std::this_thread::sleep_for(1s);
  const headingd::status_t full = nextStatus();
  const std::string log_while_full = test::readFile(log);

  // Room again: the next SIGHUP's lines reach the file, the recorder writes again.
  std::filesystem::remove(filler);
  daemon_->signal(SIGHUP);
  std::this_thread::sleep_for(2s);
  const headingd::status_t freed = nextStatus();
  stop_gps.store(true);
  gps.join();
  const std::string stderr_text = daemonLog();
  const std::string log_after = test::readFile(log);

  const auto recorderCounter = [](const headingd::status_t& m, const char* name) { return statusCounter(m, name); };
  std::fprintf(stderr,
               "full disk: log_write_errors %lld -> %lld -> %lld; recorder_write_errors %lld, "
               "recorder_lines_dropped_io %lld, recorder_lines_written %lld -> %lld -> %lld\n",
               static_cast<long long>(statusCounter(before, "log_write_errors")),
               static_cast<long long>(statusCounter(full, "log_write_errors")),
               static_cast<long long>(statusCounter(freed, "log_write_errors")),
               static_cast<long long>(recorderCounter(freed, "recorder_write_errors")),
               static_cast<long long>(recorderCounter(freed, "recorder_lines_dropped_io")),
               static_cast<long long>(recorderCounter(before, "recorder_lines_written")),
               static_cast<long long>(recorderCounter(full, "recorder_lines_written")),
               static_cast<long long>(recorderCounter(freed, "recorder_lines_written")));
  EXPECT_GT(statusCounter(full, "log_write_errors"), 0);
  EXPECT_GT(recorderCounter(full, "recorder_write_errors"), 0);
  EXPECT_GT(recorderCounter(full, "recorder_lines_dropped_io"), 0);
  // The failure is said once on stderr, which keeps every line.
  const std::string said = "log file: ";
  const std::size_t first = stderr_text.find(said);
  EXPECT_NE(first, std::string::npos) << stderr_text;
  EXPECT_EQ(stderr_text.find("LOG ERROR"), std::string::npos) << "spdlog's own error report: " << stderr_text;
  EXPECT_NE(stderr_text.find("SIGHUP: reopening the log file"), std::string::npos);
  // Once there is room, the file gets lines again and the recorder writes again.
  EXPECT_GT(log_after.size(), log_while_full.size());
  EXPECT_GT(recorderCounter(freed, "recorder_lines_written"), recorderCounter(full, "recorder_lines_written"));
  EXPECT_EQ(freed.state, "ok") << freed.reason;
  EXPECT_EQ(lcm_->heading().back().message.validity, 1);
  expectRunningThenStop();
}

}  // namespace
}  // namespace headingd::daemon
