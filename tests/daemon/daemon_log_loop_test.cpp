// at_end = "loop": the daemon's log sources ([candump_log] and [nmea_log]), and [imu_csv], play
// the first 10 s of the demo capture again and again, later on the log axis by one loop each
// time. The estimator must see one unbroken time line (no gap, no time going back, no
// duplicate at the seams), the GPS epochs must keep their place among the IMU samples, and
// STATUS must count the loops. (tools/scripts/soak.sh runs the whole demo capture this way
// for hours.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "daemon_test_support.hpp"
#include "lcm_collector.hpp"
#include "status_lookup.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

// The demo capture's first 10 s: 1000 IMU epochs of 3 frames (0 .. 9.9904 s) and the NMEA
// epochs of 0 .. 9 s (3 sentences each). One loop is then 10.0004 s of log time (the latest
// last time, the CAN log's, plus one 10 ms sample period).
std::string loopConfig(const TempDir& dir, const std::string& url, double speed) {
  const std::string cut = std::string("zcat ") + kDemoCan + " | head -n 3000 > " + dir.file("can.log") +
                          " && head -n 30 " + kDemoNmea + " > " + dir.file("gps.nmea");
  EXPECT_EQ(std::system(cut.c_str()), 0);
  return dir.write("headingd.toml",
                   "[lcm]\nurl = \"" + url +
                       "\"\n[daemon]\nstatus_period_s = 0.2\n[playback]\nspeed = " + std::to_string(speed) +
                       "\nat_end = \"loop\"\n[candump_log]\nenabled = "
                       "true\npath = \"" +
                       dir.file("can.log") + "\"\ncan_config = \"" +
                       HEADINGD_CONFIG_DIR
                       "/can-headingd.toml\"\n[nmea_log]\nenabled = true\n"
                       "path = \"" +
                       dir.file("gps.nmea") + "\"\n");
}

// What a looping daemon published in its first 2.5 s, then stopped by SIGTERM (exit 0).
struct LoopRun {
  headingd::status_t last_status;  // received while it still played
  std::vector<test::Received<headingd::heading_t>> heading;
  std::vector<test::Received<headingd::gps_t>> gps;
  std::string err;
};

LoopRun runLooping(const TempDir& dir, const std::string& url, const std::string& config) {
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  std::this_thread::sleep_for(2500ms);
  LoopRun run;
  const auto status_list = lcm.status();
  if (!status_list.empty()) run.last_status = status_list.back().message;
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(5s), 0) << test::readFile(dir.file("err"));
  lcm.stop();
  run.heading = lcm.heading();
  run.gps = lcm.gps();
  run.err = test::readFile(dir.file("err"));
  EXPECT_FALSE(status_list.empty()) << run.err;
  return run;
}

// The largest step between consecutive HEADING sample times, and how many went back.
struct TimeLine {
  std::int64_t largest_step_us = 0;
  std::int64_t went_back = 0;
  double span_s = 0.0;
};

TimeLine headingTimeLine(const std::vector<test::Received<headingd::heading_t>>& heading) {
  TimeLine t;
  for (std::size_t i = 1; i < heading.size(); ++i) {
    const std::int64_t step = heading[i].message.sample_utime - heading[i - 1].message.sample_utime;
    t.largest_step_us = std::max(t.largest_step_us, step);
    t.went_back += step < 0;
  }
  if (!heading.empty()) {
    t.span_s = static_cast<double>(heading.back().message.sample_utime - heading.front().message.sample_utime) * 1e-6;
  }
  return t;
}

TEST(DaemonLogLoop, CandumpAndNmeaLogsLoopOnOneUnbrokenTimeLine) {
  TempDir dir;
  const std::string url = lcmUrl(0);
  const std::string config = loopConfig(dir, url, 20.0);  // a loop every 0.5 s
  const LoopRun run = runLooping(dir, url, config);       // four loops and more
  const headingd::status_t& last = run.last_status;
  const std::string& err = run.err;
  EXPECT_NE(err.find("at end: loop (a loop is 10.000 s of log time)"), std::string::npos) << err;

  const auto* can = findSource(last, "candump_log");
  const auto* gps = findSource(last, "nmea_log");
  ASSERT_NE(can, nullptr);
  ASSERT_NE(gps, nullptr);
  const std::int64_t can_loops = counter(*can, "loops_played");
  const std::int64_t gps_loops = counter(*gps, "loops_played");
  std::fprintf(stderr,
               "after 2.5 s at 20x: candump_log %lld loops (%lld frames played), nmea_log %lld loops (%lld "
               "epochs); estimator: samples accepted %lld, gaps %lld, backwards %lld, duplicates %lld\n",
               static_cast<long long>(can_loops), static_cast<long long>(counter(*can, "frames_played")),
               static_cast<long long>(gps_loops), static_cast<long long>(counter(*gps, "epochs")),
               static_cast<long long>(statusCounter(last, "samples_accepted")),
               static_cast<long long>(statusCounter(last, "gaps")),
               static_cast<long long>(statusCounter(last, "backwards_time")),
               static_cast<long long>(statusCounter(last, "duplicate_time")));
  EXPECT_GT(statusCounter(last, "samples_accepted"), 3 * 1000);
  EXPECT_GE(can_loops, 3);
  EXPECT_LE(std::abs(can_loops - gps_loops), 1);
  EXPECT_EQ(can->state, "running");
  EXPECT_EQ(gps->state, "running");
  // The loops are one time line to the estimator: nothing rejected at the seams.
  for (const char* name : {"gaps", "backwards_time", "clock_jumps", "duplicate_time", "imu_rejected"}) {
    EXPECT_EQ(statusCounter(last, name), 0) << name;
  }
  EXPECT_EQ(counter(*can, "ring_full_drops"), 0);
  EXPECT_EQ(counter(*can, "time_steps"), 0);
  EXPECT_EQ(counter(*can, "duplicate_frames"), 0);

  // The published sample times only go forward, by at most a few sample periods (loops
  // included); the GPS epochs too, one a second of log time.
  ASSERT_GT(run.heading.size(), 100u);
  const TimeLine time_line = headingTimeLine(run.heading);
  EXPECT_EQ(time_line.went_back, 0);
  EXPECT_GT(time_line.span_s, 3 * 10.0);  // more than three loops of log time
  const auto& fixes = run.gps;
  ASSERT_GT(fixes.size(), 30u);
  for (std::size_t i = 1; i < fixes.size(); ++i) {
    const std::int64_t step = fixes[i].message.sample_utime - fixes[i - 1].message.sample_utime;
    EXPECT_GT(step, 500'000) << "GPS epoch " << i;  // ~1 s apart, the seam too (9 s -> 10.0004 s)
    EXPECT_LT(step, 1'500'000) << "GPS epoch " << i;
  }
}

// [imu_csv] at_end = "loop": the IMU file source's own loop (not on the [playback] clock),
// which also takes its loop length from the file's median sample step.
TEST(DaemonLogLoop, ImuCsvLoopsOnOneUnbrokenTimeLine) {
  TempDir dir;
  const std::string url = lcmUrl(0);
  // The first 1000 rows of a BROAD trial: 0 .. 3.4965 s at 286 Hz, so a loop is 3.5 s of file
  // time, 0.35 s at 10x.
  const std::string cut = std::string("zcat " HEADINGD_TEST_DATA_DIR
                                      "/broad/05_undisturbed_slow_rotation_with_breaks_B.csv.gz | head -n 1001 > ") +
                          dir.file("imu.csv");
  ASSERT_EQ(std::system(cut.c_str()), 0);
  const std::string config =
      dir.write("headingd.toml", "[lcm]\nurl = \"" + url +
                                     "\"\n[daemon]\nstatus_period_s = 0.2\n[imu_csv]\nenabled = true\npath = \"" +
                                     dir.file("imu.csv") + "\"\nspeed = 10.0\nat_end = \"loop\"\n");
  const LoopRun run = runLooping(dir, url, config);
  const headingd::status_t& last = run.last_status;
  const auto* csv = findSource(last, "imu_csv");
  ASSERT_NE(csv, nullptr);
  const std::int64_t loops = counter(*csv, "loops_played");
  std::fprintf(stderr, "after 2.5 s at 10x: imu_csv %lld loops; samples accepted %lld\n", static_cast<long long>(loops),
               static_cast<long long>(statusCounter(last, "samples_accepted")));
  EXPECT_GE(loops, 3);
  EXPECT_EQ(csv->state, "running");
  EXPECT_GT(statusCounter(last, "samples_accepted"), 3 * 1000);
  for (const char* name : {"gaps", "backwards_time", "clock_jumps", "duplicate_time", "imu_rejected"}) {
    EXPECT_EQ(statusCounter(last, name), 0) << name;
  }
  // One time line: forward only, and at the seams one usual step (3.5 ms), not a gap.
  ASSERT_GT(run.heading.size(), 100u);
  const TimeLine time_line = headingTimeLine(run.heading);
  EXPECT_EQ(time_line.went_back, 0);
  // HEADING goes out at a fixed rate of wall time, so at 10x about 0.1 s of file time apart
  // (more across a stall of this machine); a seam that skipped or repeated a loop would be
  // 3.5 s or more, or go back.
  std::fprintf(stderr, "largest step between HEADING sample times: %.3f s\n", time_line.largest_step_us * 1e-6);
  EXPECT_LT(time_line.largest_step_us, 2'000'000);
  EXPECT_GT(time_line.span_s, 3 * 3.5);
}

TEST(DaemonLogLoop, LoopWithARecordingIsAConfigurationError) {
  TempDir dir;
  const std::string unpack =
      std::string("tar xzf " HEADINGD_TEST_DATA_DIR "/recordings/sim-walk-30s.tar.gz -C ") + dir.path();
  ASSERT_EQ(std::system(unpack.c_str()), 0);
  const std::string config =
      dir.write("headingd.toml", "[playback]\nat_end = \"loop\"\n[recording]\nenabled = true\ndir = \"" +
                                     dir.file("sim-walk-30s") + "\"\n");
  ChildProcess check({HEADINGD_BIN, "--config", config, "--check-config"}, dir.file("out"), dir.file("err"));
  EXPECT_EQ(check.waitFor(10s), 2);
  const std::string err = test::readFile(dir.file("err"));
  EXPECT_NE(err.find("at_end"), std::string::npos) << err;
  EXPECT_NE(err.find("a [recording] is replayed once"), std::string::npos) << err;
}

}  // namespace
}  // namespace headingd::daemon
