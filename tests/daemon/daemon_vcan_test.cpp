// The daemon end to end on a real vcan interface (run through tools/scripts/vm-run.sh, which
// provides vcan0 in a VM or a private namespace): a recording converted to CAN frames by
// headingd-candump-from-csv, played onto vcan0 by can-utils' canplayer at real time, read
// by the daemon's CAN source; a real LCM subscriber checks rates, the CAN source's counters,
// the attitude against the offline replay of the same recording, and prints the latency
// from the frames' kernel timestamps to publish.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <net/if.h>
#include <numbers>
#include <sstream>

#include "daemon_test_support.hpp"
#include "lcm_collector.hpp"
#include "vcan_test_support.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using test::ChildProcess;
using test::LcmCollector;

constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr int kRows = 2857;  // the first 10 s of BROAD trial 05

using test::counter;

TEST(DaemonVcan, RecordingPlayedOntoVcanIsEstimatedAndPublished) {
  // Needs a vcan interface: CTest runs this binary inside tools/scripts/vm-run.sh (this
  // host's kernel has no CAN); run by hand without it, it says so instead of failing.
  if (if_nametoindex("vcan0") == 0) GTEST_SKIP() << "no vcan0: run through tools/scripts/vm-run.sh";
  test::TempDir dir;
  // 10 s of the recording, as CSV and as a candump log of headingd's own frame set.
  {
    const std::string cmd = std::string("zcat ") + HEADINGD_CONFIG_DIR +
                            "/demo/05_undisturbed_slow_rotation_with_breaks_B.csv.gz | head -n " +
                            std::to_string(kRows + 1) + " > " + dir.file("imu.csv");
    ASSERT_EQ(std::system(cmd.c_str()), 0);
  }
  const std::string can_table = test::vcanCanTable(HEADINGD_CONFIG_DIR);
  test::writeCandumpLog(dir, HEADINGD_CANDUMP_FROM_CSV_BIN, can_table, dir.file("imu.csv"));

  const std::string url = "udpm://239.255.76.67:7667?ttl=0";  // vcan runs are alone in their namespace
  const std::string config =
      dir.write("vcan.toml", "[daemon]\nimu_timeout_s = 0.5\n[lcm]\nurl = \"" + url + "\"\n" + can_table);
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  std::this_thread::sleep_for(1500ms);  // up and bound to vcan0
  ChildProcess player({"/usr/bin/canplayer", "-I", dir.file("imu.log"), "vcan0=vcan0"}, dir.file("player.out"),
                      dir.file("player.err"));
  EXPECT_EQ(player.waitFor(60s), 0) << test::readFile(dir.file("player.err"));
  const std::string log = test::finishVcanRun(dir, daemon, lcm, 2s);

  // Every epoch became one sample and one IMU message.
  const auto status = lcm.status();
  ASSERT_FALSE(status.empty()) << log;
  const headingd::source_status_t* can = nullptr;
  for (const auto& s : status.back().message.sources) can = s.kind == "can" ? &s : can;
  ASSERT_NE(can, nullptr);
  EXPECT_EQ(can->state, "running") << can->last_error;
  EXPECT_EQ(counter(*can, "samples"), kRows);
  EXPECT_EQ(counter(*can, "incomplete_epochs"), 0);
  EXPECT_EQ(counter(*can, "sequence_gaps"), 0);
  EXPECT_EQ(counter(*can, "kernel_drops"), 0);
  EXPECT_EQ(status.back().message.rings[0].dropped, 0);
  const auto imu = lcm.imu();
  EXPECT_GE(imu.size(), static_cast<std::size_t>(kRows * 99 / 100));

  // Attitude against the offline replay of the same rows: the i-th IMU sample of the run is
  // the CSV's row i; the frames quantise the values (DBC resolution) and the kernel
  // timestamps carry the player's timing, so agreement is close, not exact.
  ASSERT_EQ(std::system((std::string(HEADINGD_REPLAY_BIN) + " --imu-csv " + dir.file("imu.csv") + " --out " +
                         dir.file("replay.csv") + " 2>/dev/null")
                            .c_str()),
            0);
  std::vector<double> replay_yaw_deg;
  {
    std::istringstream in(test::readFile(dir.file("replay.csv")));
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::vector<double> f;
      std::stringstream fields(line);
      std::string cell;
      while (std::getline(fields, cell, ',')) f.push_back(std::strtod(cell.c_str(), nullptr));
      replay_yaw_deg.push_back(f.size() > 7 ? f[7] : NAN);
    }
  }
  std::map<std::int64_t, std::size_t> index_of_sample;
  for (std::size_t i = 0; i < imu.size(); ++i) index_of_sample[imu[i].message.sample_utime] = i;
  double max_yaw_diff = 0.0;
  std::size_t compared = 0, fresh = 0;
  for (const auto& a : lcm.attitude()) {
    if (a.message.validity != 1) continue;
    ++fresh;
    const auto it = index_of_sample.find(a.message.sample_utime);
    if (imu.size() != static_cast<std::size_t>(kRows) || it == index_of_sample.end()) continue;
    const double want = replay_yaw_deg.at(it->second);
    if (!std::isfinite(want)) continue;
    max_yaw_diff = std::max(max_yaw_diff, std::abs(std::remainder(a.message.yaw_rad * kDeg - want, 360.0)));
    ++compared;
  }
  std::fprintf(stderr, "vcan: %zu IMU messages, %zu fresh ATTITUDE, %zu compared with headingd-replay, max yaw difference %.3f deg\n",
               imu.size(), fresh, compared, max_yaw_diff);
  EXPECT_GT(fresh, 800u);  // ~10 s at 100 Hz
  if (imu.size() == static_cast<std::size_t>(kRows)) {
    EXPECT_GT(compared, 800u);
    EXPECT_LT(max_yaw_diff, 1.0);
  }
}

}  // namespace
}  // namespace headingd::daemon
