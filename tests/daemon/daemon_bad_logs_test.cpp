// The daemon's log sources on damaged copies of the demo logs (config/demo): a candump log
// whose first frame is stamped (0.000000), one with a frame a year ahead, gzip logs cut short,
// and an NMEA log whose first date is 1980. Each is played to its end (the daemon exits by
// itself with at_end = "exit"), and STATUS and the log say what was skipped or missing.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <sstream>

#include "daemon_test_support.hpp"
#include "lcm_collector.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

constexpr int kFrames = 3000;  // the first 10 s of the demo log: 1000 epochs of 3 frames

// The first kFrames lines of the demo candump log.
std::vector<std::string> demoCanLines(const TempDir& dir) {
  const std::string cmd =
      std::string("zcat ") + kDemoCan + " | head -n " + std::to_string(kFrames) + " > " + dir.file("head.log");
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  std::vector<std::string> lines;
  std::istringstream in(test::readFile(dir.file("head.log")));
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}

// "(1780315200.000000) can0 ..." with another time.
std::string withTime(const std::string& line, const std::string& time) {
  return "(" + time + line.substr(line.find(')'));
}

struct DaemonRun {
  int exit_code = -1;
  std::string err;
  std::map<std::string, std::int64_t> counters;  // of the one log source, from the last STATUS
  std::string state;
  std::int64_t counter(const std::string& name) const {
    const auto it = counters.find(name);
    return it == counters.end() ? -1 : it->second;
  }
};

// Runs the daemon on `sources` (TOML tables) at `speed` until it exits by itself.
DaemonRun runDaemon(const TempDir& dir, int port, const std::string& sources, double speed) {
  const std::string url = lcmUrl(port);
  const std::string config =
      dir.write("headingd.toml", "[lcm]\nurl = \"" + url + "\"\n[daemon]\nstatus_period_s = 0.2\n[playback]\nspeed = " +
                                     std::to_string(speed) + "\nat_end = \"exit\"\n" + sources);
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  DaemonRun run;
  run.exit_code = daemon.waitFor(30s);
  std::this_thread::sleep_for(200ms);
  lcm.stop();
  run.err = test::readFile(dir.file("err"));
  const auto status = lcm.status();
  if (!status.empty() && !status.back().message.sources.empty()) {
    const auto& s = status.back().message.sources.front();
    run.state = s.state;
    for (const auto& c : s.counters) run.counters[c.name] = c.value;
  }
  return run;
}

std::string candumpSource(const std::string& path) {
  return "[candump_log]\nenabled = true\npath = \"" + path +
         "\"\ncan_config = \"" HEADINGD_CONFIG_DIR "/can-headingd.toml\"\n";
}

TEST(DaemonBadLogs, CandumpFirstFrameAtZeroIsSkippedAndTheLogPlays) {
  TempDir dir;
  auto lines = demoCanLines(dir);
  lines[0] = withTime(lines[0], "0.000000");
  const DaemonRun run = runDaemon(dir, 30, candumpSource(dir.write("can.log", joined(lines))), 20.0);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.state, "finished") << run.err;
  EXPECT_EQ(run.counter("frames_in_log"), kFrames);
  EXPECT_EQ(run.counter("time_outlier_frames"), 1);
  EXPECT_EQ(run.counter("frames_played"), kFrames - 1);
  EXPECT_EQ(run.counter("samples"), 1000);  // the first epoch lost its magnetometer frame
  EXPECT_EQ(run.counter("samples_with_mag"), 999);
  EXPECT_NE(run.err.find("1 frame(s) whose time lies more than 1 s from the frames around them are skipped; the "
                         "first, line 1: (0.000000)"),
            std::string::npos)
      << run.err;
}

TEST(DaemonBadLogs, CandumpFrameAYearAheadIsSkippedAndTheLogPlays) {
  TempDir dir;
  auto lines = demoCanLines(dir);
  lines[1500] = withTime(lines[1500], "1811851200.000000");  // a year after the log
  const DaemonRun run = runDaemon(dir, 31, candumpSource(dir.write("can.log", joined(lines))), 20.0);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.counter("time_outlier_frames"), 1);
  EXPECT_EQ(run.counter("frames_played"), kFrames - 1);
  EXPECT_EQ(run.counter("time_steps"), 0);
  EXPECT_NE(run.err.find("line 1501: (1811851200.000000)"), std::string::npos) << run.err;
}

TEST(DaemonBadLogs, CandumpGzipCutShortIsPlayedAsFarAsItGoesAndSaidSo) {
  TempDir dir;
  const std::string cut = dir.file("can.log.gz");
  const std::string cmd = std::string("head -c 300000 ") + kDemoCan + " > " + cut;
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const DaemonRun run = runDaemon(dir, 32, candumpSource(cut), 100.0);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.counter("log_end_missing"), 1);
  EXPECT_GT(run.counter("frames_played"), 10000);
  EXPECT_LT(run.counter("frames_played"), 180003);
  EXPECT_EQ(run.counter("frames_played"), run.counter("frames_in_log"));
  EXPECT_NE(run.err.find(cut + ": the gzip log is cut short"), std::string::npos) << run.err;
}

TEST(DaemonBadLogs, NmeaGzipLogIsPlayedAndOneCutShortIsSaidSo) {
  TempDir dir;
  const std::string whole = dir.file("gps.nmea.gz");
  const std::string cut = dir.file("cut.nmea.gz");
  ASSERT_EQ(std::system(("gzip -c " + std::string(kDemoNmea) + " > " + whole).c_str()), 0);
  ASSERT_EQ(std::system(("head -c 10000 " + whole + " > " + cut).c_str()), 0);
  auto source = [](const std::string& path) { return "[nmea_log]\nenabled = true\npath = \"" + path + "\"\n"; };

  const DaemonRun full = runDaemon(dir, 33, source(whole), 1000.0);
  EXPECT_EQ(full.exit_code, 0) << full.err;
  EXPECT_EQ(full.counter("log_end_missing"), 0);
  EXPECT_EQ(full.counter("epochs"), 601);  // as the plain demo log

  const DaemonRun part = runDaemon(dir, 33, source(cut), 1000.0);
  EXPECT_EQ(part.exit_code, 0) << part.err;
  EXPECT_EQ(part.counter("log_end_missing"), 1);
  EXPECT_GT(part.counter("epochs"), 10);
  EXPECT_LT(part.counter("epochs"), 601);
  EXPECT_NE(part.err.find(cut + ": the gzip log is cut short"), std::string::npos) << part.err;
}

// "$BODY*HH" with the checksum of BODY.
std::string nmeaSentence(const std::string& body) {
  unsigned checksum = 0;
  for (const char c : body) checksum ^= static_cast<unsigned char>(c);
  char hex[3];
  std::snprintf(hex, sizeof hex, "%02X", checksum);
  return "$" + body + "*" + hex;
}

// A receiver prints a default date (1980-01-06) before its first fix: that date must not set
// the log's start (the next epoch would then be due 46 years later: the player stalled).
TEST(DaemonBadLogs, NmeaFirstDate1980IsNotBelievedAndTheLogPlays) {
  TempDir dir;
  std::string log = test::readFile(kDemoNmea);
  const std::string first_rmc = "$GPRMC,120000.00,A,5919.80051,N,01804.19625,E,0.000,,010626,7.7,E,A*17";
  const auto at = log.find(first_rmc);
  ASSERT_NE(at, std::string::npos);
  log.replace(at, first_rmc.size(), nmeaSentence("GPRMC,120000.00,A,5919.80051,N,01804.19625,E,0.000,,060180,7.7,E,A"));
  const std::string path = dir.write("gps.nmea", log);
  const DaemonRun run = runDaemon(dir, 34, "[nmea_log]\nenabled = true\npath = \"" + path + "\"\n", 1000.0);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.state, "finished") << run.err;
  EXPECT_EQ(run.counter("epochs"), 601);
  EXPECT_GE(run.counter("dates_not_believed"), 1);  // the fix updates that carried the 1980 date
}

}  // namespace
}  // namespace headingd::daemon
