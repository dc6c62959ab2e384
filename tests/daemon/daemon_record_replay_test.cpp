// The black box's contract, end to end on real parts (daemon/README.md, "Black box"): the
// headingd binary runs live with its IMU on vcan0 (canplayer) and its GPS on a real pty at
// line rate, with the recorder on and lcm-logger recording what it publishes; the recording
// is then replayed twice, by headingd-replay --recording (every state, as fast as the CPU
// allows) and by the daemon itself on the recording's replay.toml at 4x speed (lcm-logger
// again). Every HEADING and ATTITUDE message with an estimate, live and replayed, must equal
// the replay's state of the same sample, bit for bit, in every field but utime,
// sample_age_us and validity. The live run has a [place] without a date, which the recording
// must carry as the date the run took. Run through tools/scripts/vm-run.sh (vcan0 in a VM or a
// private namespace). HEADINGD_KEEP_RECORDING=DIR copies the recording there.
#include <gtest/gtest.h>

#include <net/if.h>
#include <filesystem>
#include <regex>
#include <sstream>

#include "daemon_test_support.hpp"
#include "estimate_log_compare.hpp"
#include "lcm_collector.hpp"
#include "pty_fixture.hpp"
#include "vcan_test_support.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using test::ChildProcess;

constexpr int kSeconds = 30;  // standing 10 s, then walking north (headingd-sim thesis-declination)
constexpr int kRows = kSeconds * 100 + 1;

void run(const std::string& command) { ASSERT_EQ(std::system(command.c_str()), 0) << command; }

std::string onlySubfolder(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.is_directory()) found.push_back(e.path().string());
  }
  return found.size() == 1 ? found.front() : std::string();
}

void expectAllEqual(const char* what, const test::EstimateMessages& published, const test::EstimateMessages& states,
                    std::size_t at_least) {
  const test::Comparison c = test::compareWithStates(published, states);
  std::fprintf(stderr, "%s: %zu messages, %zu with an estimate compared, %zu equal bit for bit\n", what,
               published.messages, c.compared, c.equal);
  EXPECT_GE(c.compared, at_least) << what;
  EXPECT_EQ(c.equal, c.compared) << what << ": first difference at sample_utime " << c.first_unequal_sample_utime;
}

using DaemonRecordReplay = test::OnVcan;

TEST_F(DaemonRecordReplay, ALiveRunReplaysBitForBitBothWays) {
  // Inputs: the start of a simulated walk as CAN frames and NMEA epochs.
  const auto [can_table, epochs] = test::simulatedWalkOnVcan(dir_, HEADINGD_SIM_BIN, HEADINGD_CANDUMP_FROM_CSV_BIN,
                                                             HEADINGD_CONFIG_DIR, kRows, kSeconds);
  ASSERT_GE(epochs.size(), static_cast<std::size_t>(kSeconds));

  // Live, recorded twice: by the black box (inputs) and by lcm-logger (outputs).
  headingd::test::PtyPair gps;
  const std::string url = "udpm://239.255.76.67:7667?ttl=0";  // alone in the VM's namespace
  const std::string config =
      dir_.write("live.toml", "[daemon]\nwmm = \"" HEADINGD_CONFIG_DIR "/wmm/WMM2025.COF\"\n[lcm]\nurl = \"" + url +
                                  "\"\n" + can_table + "\n[gps]\nenabled = true\ndevice = \"" + gps.slavePath() +
                                  "\"\nbaud = 9600\n[recorder]\ndir = \"" + dir_.file("recordings") + "\"\n" +
                                  // A place without a date: the daemon takes the system's, and the recording must
                                  // carry the one it took for the replays to be bit-exact.
                                  "[place]\nlatitude_deg = 59.33\nlongitude_deg = 18.07\n");
  ChildProcess logger({"/usr/bin/lcm-logger", "--lcm-url=" + url, "--quiet", dir_.file("live.lcm")},
                      dir_.file("logger.out"), dir_.file("logger.err"));
  test::LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir_.file("out"), dir_.file("err"));
  ASSERT_TRUE(test::waitUntil([&] { return !lcm.status().empty(); }, 10s)) << test::readFile(dir_.file("err"));
  ChildProcess player({"/usr/bin/canplayer", "-I", dir_.file("imu.log"), "vcan0=vcan0"}, dir_.file("player.out"),
                      dir_.file("player.err"));
  ASSERT_TRUE(test::waitUntil([&] { return !lcm.imu().empty(); }, 10s)) << test::readFile(dir_.file("err"));
  test::writeOneEpochPerSecond(gps, epochs, kSeconds, headingd::test::lineBytesPerSecond(9600));
  EXPECT_EQ(player.waitFor(60s), 0) << test::readFile(dir_.file("player.err"));
  test::finishVcanRun(dir_, daemon, lcm, 3s);
  std::this_thread::sleep_for(500ms);
  logger.signal(SIGINT);
  EXPECT_EQ(logger.waitFor(5s), 0) << test::readFile(dir_.file("logger.err"));

  const std::string recording = onlySubfolder(dir_.file("recordings"));
  ASSERT_FALSE(recording.empty()) << "no recording folder: " << test::readFile(dir_.file("err"));
  if (const char* keep = std::getenv("HEADINGD_KEEP_RECORDING")) {
    std::filesystem::copy(recording, keep, std::filesystem::copy_options::recursive);
  }

  EXPECT_NE(test::readFile(recording + "/config.toml").find("decimal_year = 20"), std::string::npos)
      << "the recording does not carry the place's date";

  // Replay 1: every state the estimator went through.
  run(std::string(HEADINGD_REPLAY_BIN) + " --recording " + recording + " --lcm-log " + dir_.file("states.lcm") +
      " --out " + dir_.file("states.csv") + " 2> " + dir_.file("replay.err"));
  std::fprintf(stderr, "%s", test::readFile(dir_.file("replay.err")).c_str());
  EXPECT_NE(test::readFile(dir_.file("replay.err")).find("\"recording_complete\":true"), std::string::npos);

  // Replay 2: the daemon on the recording's own replay configuration, at 4x.
  {
    std::string replay_toml = test::readFile(recording + "/replay.toml");
    replay_toml = std::regex_replace(replay_toml, std::regex("speed = 1\\.0"), "speed = 4.0");
    std::ofstream(recording + "/replay-4x.toml") << replay_toml;
  }
  ChildProcess replay_logger({"/usr/bin/lcm-logger", "--lcm-url=" + url, "--quiet", dir_.file("replay.lcm")},
                             dir_.file("rlogger.out"), dir_.file("rlogger.err"));
  std::this_thread::sleep_for(300ms);
  ChildProcess replay_daemon({HEADINGD_BIN, "--config", recording + "/replay-4x.toml"}, dir_.file("rout"),
                             dir_.file("rerr"));
  EXPECT_EQ(replay_daemon.waitFor(60s), 0) << test::readFile(dir_.file("rerr"));
  std::this_thread::sleep_for(500ms);
  replay_logger.signal(SIGINT);
  EXPECT_EQ(replay_logger.waitFor(5s), 0) << test::readFile(dir_.file("rlogger.err"));

  const auto states_heading = test::readEstimates<headingd::heading_t>(dir_.file("states.lcm"), "HEADING");
  const auto states_attitude = test::readEstimates<headingd::attitude_t>(dir_.file("states.lcm"), "ATTITUDE");
  // Every state: one after each IMU sample and each GPS epoch.
  EXPECT_GE(states_heading.messages, static_cast<std::size_t>(kRows + kSeconds));
  // Live: 100 Hz for about kSeconds, less the ticks a slow VM misses (plain emulation under
  // load missed half of them); the floor only makes sure that there was something to compare.
  const std::size_t live_at_least = static_cast<std::size_t>(kSeconds) * 10;
  expectAllEqual("live HEADING", test::readEstimates<headingd::heading_t>(dir_.file("live.lcm"), "HEADING"),
                 states_heading, live_at_least);
  expectAllEqual("live ATTITUDE", test::readEstimates<headingd::attitude_t>(dir_.file("live.lcm"), "ATTITUDE"),
                 states_attitude, live_at_least);
  // The daemon's replay at 4x publishes at 100 Hz too: about a quarter as many messages.
  const std::size_t replay_at_least = live_at_least / 4;
  expectAllEqual("daemon replay HEADING", test::readEstimates<headingd::heading_t>(dir_.file("replay.lcm"), "HEADING"),
                 states_heading, replay_at_least);
  expectAllEqual("daemon replay ATTITUDE",
                 test::readEstimates<headingd::attitude_t>(dir_.file("replay.lcm"), "ATTITUDE"), states_attitude,
                 replay_at_least);
}

}  // namespace
}  // namespace headingd::daemon
