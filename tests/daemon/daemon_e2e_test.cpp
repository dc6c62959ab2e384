// The headingd binary run end to end: real files in, real LCM (udpm, ttl=0) out, a real
// subscriber using the generated types, signals, and the sd_notify protocol on a real
// unix socket.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

#include "daemon_test_support.hpp"
#include "headingd/core/angles.hpp"
#include "lcm_collector.hpp"

namespace headingd::daemon {
namespace {

using namespace std::chrono_literals;
using namespace test;

// lcm-gen declares its constants without a definition: copies that EXPECT_EQ may bind to.
constexpr std::int8_t kNone = headingd::heading_t::VALIDITY_NONE;
constexpr std::int8_t kFresh = headingd::heading_t::VALIDITY_FRESH;
constexpr std::int8_t kStale = headingd::heading_t::VALIDITY_STALE;

// The demo trial (kDemoImuCsv): its samples and its length.
constexpr std::size_t kTrialSamples = 59212;
constexpr double kTrialSeconds = 207.2385;

std::string configText(const std::string& url, const std::string& body) {
  return "[lcm]\nurl = \"" + url + "\"\n" + body;
}

double steadyNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

template <class R>
double rateHz(const std::vector<R>& v) {
  if (v.size() < 2) return 0.0;
  return static_cast<double>(v.size() - 1) / (v.back().receive_s - v.front().receive_s);
}

struct ReplayRow {
  double q[4];
  double yaw_deg;
};

// headingd-replay's output for the same file, by sample time in µs.
std::map<std::int64_t, ReplayRow> runReplay(const TempDir& dir) {
  const std::string out = dir.file("replay.csv");
  const std::string cmd =
      std::string(HEADINGD_REPLAY_BIN) + " --imu-csv " + kDemoImuCsv + " --out " + out + " 2>" + dir.file("replay.err");
  EXPECT_EQ(std::system(cmd.c_str()), 0) << test::readFile(dir.file("replay.err"));
  std::map<std::int64_t, ReplayRow> rows;
  std::istringstream in(test::readFile(out));
  std::string line;
  std::getline(in, line);  // header t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg
  while (std::getline(in, line)) {
    double t = 0, roll = 0, pitch = 0;
    ReplayRow r{};
    char comma;
    std::istringstream fields(line);
    fields >> t >> comma >> r.q[0] >> comma >> r.q[1] >> comma >> r.q[2] >> comma >> r.q[3] >> comma >> roll >> comma >>
        pitch >> comma >> r.yaw_deg;
    if (fields && std::isfinite(r.q[0])) rows[std::llround(t * 1e6)] = r;
  }
  return rows;
}

TEST(DaemonEndToEnd, BroadTrialAtTenTimesRealTimeMatchesTheOfflineReplay) {
  TempDir dir;
  const std::string url = lcmUrl(0);
  const std::string config =
      dir.write("e2e.toml", configText(url, "[imu_csv]\nenabled = true\npath = \"" + std::string(kDemoImuCsv) +
                                                "\"\nspeed = 10.0\nat_end = \"exit\"\n"));
  LcmCollector lcm(url);
  const double start = steadyNow();
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  const int status = daemon.waitFor(60s);
  const double run_s = steadyNow() - start;
  std::this_thread::sleep_for(200ms);  // the last datagrams
  const std::uint64_t subscriber_drops = LcmCollector::kernelReceiveDrops();
  lcm.stop();
  ASSERT_EQ(status, 0) << test::readFile(dir.file("err"));
  EXPECT_NEAR(run_s, kTrialSeconds / 10.0, 2.0) << "played at 10x real time";

  const auto heading = lcm.heading();
  const auto attitude = lcm.attitude();
  const auto imu = lcm.imu();
  const auto status_msgs = lcm.status();
  // Rates: HEADING and ATTITUDE at the estimator rate, less the ticks the daemon counted as
  // missed (it skips them rather than burst; a busy machine makes some), IMU at 10x the
  // sensor's 285.7 Hz, STATUS at 1 Hz.
  ASSERT_FALSE(status_msgs.empty());
  const double missed_per_s = static_cast<double>(status_msgs.back().message.deadline_misses) / run_s;
  EXPECT_NEAR(rateHz(heading), 100.0 - missed_per_s, 3.0);
  EXPECT_NEAR(rateHz(attitude), 100.0 - missed_per_s, 3.0);
  EXPECT_NEAR(rateHz(imu), 2857.0, 100.0);
  EXPECT_NEAR(static_cast<double>(status_msgs.size()), kTrialSeconds / 10.0, 2.5);
  // ~2,900 datagrams a second: on a loaded machine this subscriber's thread can miss its turn
  // for longer than its socket buffer lasts, and the kernel counts what it drops there. What
  // the kernel dropped at the subscriber is the test's loss, not the daemon's: the daemon
  // must have sent every sample as an IMU message, and the subscriber must have seen them.
  EXPECT_GE(imu.size() + subscriber_drops, kTrialSamples)
      << "IMU messages lost between daemon and subscriber (" << subscriber_drops
      << " datagrams dropped by the kernel at the subscriber's full receive buffer)";
  std::fprintf(stderr,
               "rates: HEADING %.2f Hz, ATTITUDE %.2f Hz (%.2f deadline misses a second), IMU %.1f Hz (%zu of %zu; "
               "%llu datagrams dropped at the subscriber's receive buffer), STATUS %zu in %.1f s\n",
               rateHz(heading), rateHz(attitude), missed_per_s, rateHz(imu), imu.size(), kTrialSamples,
               static_cast<unsigned long long>(subscriber_drops), status_msgs.size(), run_s);

  // The daemon's own accounting: every sample through the ring, none dropped.
  const headingd::status_t& last = status_msgs.back().message;
  EXPECT_EQ(last.state, "ok");
  ASSERT_EQ(last.num_rings, 1);
  EXPECT_EQ(last.rings[0].dropped, 0);
  EXPECT_GT(last.rings[0].high_water, 0);
  // Each STATUS's window mark lies within the mark since start, and samples waited in some.
  std::int32_t most_in_a_window = 0;
  for (const auto& s : status_msgs) {
    EXPECT_LE(s.message.rings[0].window_high_water, s.message.rings[0].high_water);
    most_in_a_window = std::max(most_in_a_window, s.message.rings[0].window_high_water);
  }
  EXPECT_GT(most_in_a_window, 0);
  EXPECT_NEAR(last.heading_rate_hz, 100.0, 5.0);
  ASSERT_EQ(last.num_sources, 1);
  EXPECT_EQ(last.sources[0].kind, "imu_csv");
  // The counters' names and order, as subscribers read them (status_builder.hpp).
  std::vector<std::string> counter_names;
  for (const auto& c : last.counters) counter_names.push_back(c.name);
  EXPECT_EQ(counter_names, (std::vector<std::string>{"samples_accepted",
                                                     "gaps",
                                                     "clock_jumps",
                                                     "duplicate_time",
                                                     "backwards_time",
                                                     "non_finite",
                                                     "non_finite_mag",
                                                     "out_of_range",
                                                     "out_of_range_mag",
                                                     "imu_rejected",
                                                     "bias_still_blocks",
                                                     "mag_no_heading",
                                                     "mag_disturbed",
                                                     "mag_heading_restores",
                                                     "mag_calibration_set_aside",
                                                     "mag_calibration_taken_back",
                                                     "state_recoveries",
                                                     "accel_clipped",
                                                     "qsf_mag_periods",
                                                     "qsf_mag_ms",
                                                     "qsf_accel_periods",
                                                     "qsf_accel_ms",
                                                     "qsf_mag_updates",
                                                     "qsf_mag_updates_rejected",
                                                     "mau_updates",
                                                     "mau_updates_rejected",
                                                     "mau_updates_unverified",
                                                     "maru_updates",
                                                     "maru_updates_rejected",
                                                     "agu_updates",
                                                     "agu_updates_rejected",
                                                     "gps_epochs",
                                                     "gps_epochs_used_for_declination",
                                                     "gps_epochs_forced_out",
                                                     "gps_values_ignored",
                                                     "gps_dates_not_believed",
                                                     "units_suspect_accel",
                                                     "units_suspect_gyro",
                                                     "units_suspect_mag",
                                                     "log_write_errors"}));
  EXPECT_EQ(last.num_counters, static_cast<std::int32_t>(last.counters.size()));
  const std::string summary = test::readFile(dir.file("err"));
  EXPECT_NE(summary.find("\"imu_published\":" + std::to_string(kTrialSamples)), std::string::npos) << summary;

  // The published attitude is the offline replay's at the same sample.
  const auto replay = runReplay(dir);
  ASSERT_GT(replay.size(), kTrialSamples / 2);
  double max_angle_rad = 0.0, max_yaw_deg = 0.0;
  std::size_t compared = 0;
  for (const auto& r : attitude) {
    if (r.message.validity != kFresh) continue;
    const auto it = replay.find(r.message.sample_utime);
    if (it == replay.end()) continue;
    // Rotation angle between the two from the chord between the quaternions (q and -q are
    // one rotation); unlike acos of the dot product it stays accurate for tiny angles.
    double minus = 0.0, plus = 0.0;
    for (int i = 0; i < 4; ++i) {
      minus += std::pow(r.message.q_nb[i] - it->second.q[i], 2);
      plus += std::pow(r.message.q_nb[i] + it->second.q[i], 2);
    }
    const double chord = std::sqrt(std::min(minus, plus));
    max_angle_rad = std::max(max_angle_rad, 4.0 * std::asin(std::min(1.0, chord / 2.0)));
    double yaw_diff = std::remainder(r.message.yaw_rad * core::kDegPerRad - it->second.yaw_deg, 360.0);
    max_yaw_deg = std::max(max_yaw_deg, std::abs(yaw_diff));
    ++compared;
  }
  std::fprintf(stderr, "compared %zu ATTITUDE messages with headingd-replay: max angle %.3g deg, max yaw %.3g deg\n",
               compared, max_angle_rad * core::kDegPerRad, max_yaw_deg);
  EXPECT_GT(compared, attitude.size() * 9 / 10);
  EXPECT_LT(max_angle_rad * core::kDegPerRad, 1e-4);
  EXPECT_LT(max_yaw_deg, 1e-4);
  // HEADING carries the same magnetic heading.
  for (const auto& h : heading) {
    if (h.message.validity != kFresh) continue;
    const auto it = replay.find(h.message.sample_utime);
    if (it == replay.end()) continue;
    EXPECT_NEAR(std::remainder(h.message.heading_mag_rad * core::kDegPerRad - it->second.yaw_deg, 360.0), 0.0, 1e-4);
  }
}

TEST(DaemonEndToEnd, NoImuDataGivesDegradedStatusAndStaleEstimates) {
  TempDir dir;
  // One second of a device lying still, then nothing.
  std::string csv = "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n";
  for (int i = 0; i < 100; ++i) csv += std::to_string(i * 0.01) + ",0.001,-0.002,0.0005,0.05,-0.03,9.81,20,1,45\n";
  dir.write("still.csv", csv);
  const std::string url = lcmUrl(1);
  const std::string config =
      dir.write("degraded.toml", configText(url,
                                            "[daemon]\nimu_timeout_s = 0.3\nstatus_period_s = 0.2\n"
                                            "[imu_csv]\nenabled = true\npath = \"still.csv\"\nat_end = \"stay\"\n"));
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  const bool degraded = waitUntil(
      [&] {
        const auto s = lcm.status();
        return !s.empty() && s.back().message.state == "degraded";
      },
      5s);
  EXPECT_TRUE(degraded) << test::readFile(dir.file("err"));
  std::this_thread::sleep_for(300ms);
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(1s), 0) << "SIGTERM: clean exit within 1 s";
  lcm.stop();

  const auto status = lcm.status();
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.front().message.state, "ok");  // while the file played
  EXPECT_EQ(status.back().message.state, "degraded");
  EXPECT_NE(status.back().message.reason.find("no IMU data for"), std::string::npos) << status.back().message.reason;
  // Fresh while data came, stale afterwards: never a stale heading published as fresh.
  const auto heading = lcm.heading();
  ASSERT_FALSE(heading.empty());
  EXPECT_EQ(heading.back().message.validity, kStale);
  EXPECT_GT(heading.back().message.sample_age_us, 300'000);
  bool saw_fresh = false;
  for (const auto& h : heading) {
    saw_fresh = saw_fresh || h.message.validity == kFresh;
    if (h.message.validity == kFresh) {
      EXPECT_LE(h.message.sample_age_us, 300'000);
    }
  }
  EXPECT_TRUE(saw_fresh);
  for (const auto& a : lcm.attitude()) {
    if (a.message.validity == kFresh) {
      EXPECT_LE(a.message.sample_age_us, 300'000);
    }
  }
}

TEST(DaemonEndToEnd, WithoutAnySourceStatusIsDegradedAndNothingIsValid) {
  TempDir dir;
  const std::string url = lcmUrl(2);
  const std::string config =
      dir.write("none.toml", configText(url, "[daemon]\nimu_timeout_s = 0.2\nstatus_period_s = 0.2\n"));
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  EXPECT_TRUE(waitUntil([&] { return lcm.status().size() >= 3; }, 5s)) << test::readFile(dir.file("err"));
  daemon.signal(SIGINT);
  EXPECT_EQ(daemon.waitFor(1s), 0) << "SIGINT: clean exit within 1 s";
  lcm.stop();
  const auto status = lcm.status();
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.back().message.state, "degraded");
  EXPECT_EQ(status.back().message.reason, "no IMU data since start");
  for (const auto& h : lcm.heading()) EXPECT_EQ(h.message.validity, kNone);
}

// systemd's side of Type=notify, on a real unix datagram socket.
class NotifySocket {
 public:
  explicit NotifySocket(const std::string& path) : path_(path) {
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path.c_str());
    if (bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) throw std::runtime_error("bind " + path);
  }
  ~NotifySocket() { close(fd_); }
  // Every datagram received so far, appended to messages().
  const std::vector<std::pair<double, std::string>>& poll() {
    char buffer[4096];
    for (;;) {
      const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      messages_.emplace_back(steadyNow(), std::string(buffer, static_cast<std::size_t>(n)));
    }
    return messages_;
  }
  std::size_t count(const std::string& text) {
    std::size_t n = 0;
    for (const auto& m : poll()) n += m.second.find(text) != std::string::npos;
    return n;
  }

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<std::pair<double, std::string>> messages_;
};

TEST(DaemonEndToEnd, NotifiesSystemdPingsTheWatchdogAndStopsWithinOneSecondOnSigterm) {
  TempDir dir;
  NotifySocket notify(dir.file("notify"));
  const std::string url = lcmUrl(3);
  const std::string config = dir.write(
      "notify.toml", configText(url, "[imu_csv]\nenabled = true\npath = \"" + std::string(kDemoImuCsv) + "\"\n"));
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"),
                      {"NOTIFY_SOCKET=" + dir.file("notify"), "WATCHDOG_USEC=200000"});
  EXPECT_TRUE(waitUntil([&] { return notify.count("READY=1") == 1; }, 3s)) << test::readFile(dir.file("err"));
  const std::size_t pings_before = notify.count("WATCHDOG=1");
  std::this_thread::sleep_for(1200ms);
  const std::size_t pings = notify.count("WATCHDOG=1") - pings_before;
  EXPECT_GE(pings, 8u) << "a ping every 100 ms (half of WatchdogSec=200 ms)";
  EXPECT_GE(notify.count("STATUS=ok"), 1u);

  // SIGHUP: logs reopened, calibration hook called, still running.
  daemon.signal(SIGHUP);
  EXPECT_EQ(daemon.waitFor(300ms), -1) << "SIGHUP must not stop the daemon";

  const double sent = steadyNow();
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(1s), 0);
  const double stop_s = steadyNow() - sent;
  std::fprintf(stderr, "SIGTERM to exit: %.0f ms\n", stop_s * 1e3);
  EXPECT_LT(stop_s, 1.0);
  EXPECT_EQ(notify.count("STOPPING=1"), 1u);
  const std::string err = test::readFile(dir.file("err"));
  EXPECT_NE(err.find("SIGHUP: no [daemon] calibration configured"), std::string::npos) << err;
}

// Without the privileges (a user namespace: CAP_SYS_NICE only there, RLIMIT_MEMLOCK as it
// is), every [realtime] setting is refused with a message that says what would permit it,
// and the daemon runs on.
TEST(DaemonEndToEnd, RealtimeSettingsRefusedAreReportedAndTheDaemonContinues) {
  // The refusal is produced by running unprivileged in a user namespace; a host that forbids
  // user namespaces cannot stage it (here and in CI it can, so the test runs).
  if (std::system("unshare -r -n true 2>/dev/null") != 0) GTEST_SKIP() << "no user namespaces here";
  TempDir dir;
  const std::string config = dir.write(
      "rt.toml",
      configText(lcmUrl(4), "[realtime]\nsched_fifo_priority = 50\ncpu_affinity = [1000]\nlock_memory = true\n"));
  ChildProcess daemon(
      {"/usr/bin/unshare", "-r", "-n", "sh", "-c",
       "ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec \"$0\" --config \"$1\"", HEADINGD_BIN, config},
      dir.file("out"), dir.file("err"));
  std::this_thread::sleep_for(1s);
  EXPECT_EQ(daemon.waitFor(0ms), -1) << "still running: " << test::readFile(dir.file("err"));
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(1s), 0);
  const std::string err = test::readFile(dir.file("err"));
  // Said once, by whichever of the two threads at priority 50 asked first.
  EXPECT_TRUE(err.find("SCHED_FIFO priority 50 for the estimator thread not permitted") != std::string::npos ||
              err.find("SCHED_FIFO priority 50 for the LCM sender thread not permitted") != std::string::npos)
      << err;
  EXPECT_NE(err.find("continuing with normal scheduling"), std::string::npos) << err;
  EXPECT_NE(err.find("CPU affinity 1000 refused"), std::string::npos) << err;
  // Root's RLIMIT_MEMLOCK may be unlimited on some machines: then mlockall succeeds.
  EXPECT_TRUE(err.find("mlockall refused") != std::string::npos || err.find("memory locked") != std::string::npos)
      << err;
  EXPECT_NE(err.find("\"ticks\":"), std::string::npos) << "the loop ran: " << err;
}

// SIGHUP reopens the log file: after logrotate moved it away, a new one is written.
TEST(DaemonEndToEnd, SighupReopensTheLogFile) {
  TempDir dir;
  const std::string config =
      dir.write("log.toml", configText(lcmUrl(5), "[log]\nfile = \"headingd.log\"\n[daemon]\nimu_timeout_s = 0.1\n"));
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  ASSERT_TRUE(
      waitUntil([&] { return test::readFile(dir.file("headingd.log")).find("running:") != std::string::npos; }, 3s));
  std::filesystem::rename(dir.file("headingd.log"), dir.file("headingd.log.1"));
  daemon.signal(SIGHUP);
  EXPECT_TRUE(waitUntil([&] { return std::filesystem::exists(dir.file("headingd.log")); }, 2s));
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(1s), 0);
  EXPECT_NE(test::readFile(dir.file("headingd.log")).find("summary"), std::string::npos)
      << "the new file gets the later lines";
  EXPECT_EQ(test::readFile(dir.file("headingd.log.1")).find("summary"), std::string::npos);
}

// [daemon] calibration: the sample the estimator sees and IMU publishes is the calibrated
// one (here a gyro bias and a magnetometer offset); SIGHUP re-reads the file and keeps the
// calibration in use when the new file does not read.
TEST(DaemonEndToEnd, CalibrationIsAppliedAndABadReloadKeepsIt) {
  TempDir dir;
  const std::string url = lcmUrl(7);
  dir.write("calib.toml",
            "[magnetometer]\noffset_uT = [1.0, -2.0, 3.0]\n[gyroscope]\nbias_rad_s = [0.01, 0.02, -0.03]\n");
  const std::string source = "[imu_csv]\nenabled = true\npath = \"" + std::string(kDemoImuCsv) + "\"\nspeed = 2.0\n";
  const std::string plain = dir.write("plain.toml", configText(url, source));
  const std::string calibrated =
      dir.write("calibrated.toml", configText(url, "[daemon]\ncalibration = \"calib.toml\"\n" + source));

  // The first samples of the trial, as published without and with the calibration.
  const auto firstImu = [&](const std::string& config, const char* name, bool bad_reload) {
    LcmCollector lcm(url);
    ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file(std::string(name) + ".out"),
                        dir.file(std::string(name) + ".err"));
    EXPECT_TRUE(waitUntil([&] { return lcm.imu().size() >= 200; }, 10s));
    if (bad_reload) {
      dir.write("calib.toml", "[magnetometer]\noffset_uT = [1.0, -2.0]\n");  // two numbers: does not read
      daemon.signal(SIGHUP);
      EXPECT_TRUE(waitUntil(
          [&] { return test::readFile(dir.file(std::string(name) + ".err")).find("keeping") != std::string::npos; },
          3s));
      EXPECT_TRUE(waitUntil([&] { return lcm.imu().size() >= 400; }, 10s));
    }
    daemon.signal(SIGTERM);
    EXPECT_EQ(daemon.waitFor(2s), 0) << test::readFile(dir.file(std::string(name) + ".err"));
    lcm.stop();
    std::map<std::int64_t, headingd::imu_t> by_time;
    for (const auto& r : lcm.imu()) by_time.emplace(r.message.sample_utime, r.message);
    return by_time;
  };
  const auto raw = firstImu(plain, "plain", false);
  const auto corrected = firstImu(calibrated, "calibrated", true);
  const double bias[3] = {0.01, 0.02, -0.03}, offset[3] = {1.0, -2.0, 3.0};
  std::size_t compared = 0;
  for (const auto& [t, c] : corrected) {
    const auto it = raw.find(t);
    if (it == raw.end()) continue;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(c.gyro_rad_s[i], it->second.gyro_rad_s[i] - bias[i], 1e-12);
      EXPECT_NEAR(c.accel_m_s2[i], it->second.accel_m_s2[i], 1e-12);
      if (c.has_mag) {
        EXPECT_NEAR(c.mag_uT[i], it->second.mag_uT[i] - offset[i], 1e-9);
      }
    }
    ++compared;
  }
  EXPECT_GE(compared, 150u) << "samples published by both runs";
}

// The demo configuration's log sources ([candump_log] + [nmea_log], the bundled simulated
// walk) at 20 times real time: everything is played through the CAN and NMEA decoders, both
// sources say "finished", the daemon exits by itself (at_end = "exit"), and the true heading
// follows the simulator's truth (config/demo/sim-urban-walk-truth.csv.gz, 10 Hz).
TEST(DaemonEndToEnd, DemoCaptureFromCandumpAndNmeaLogsIsPlayedToTheEndAndFollowsTheTruth) {
  TempDir dir;
  std::string demo = test::readFile(HEADINGD_CONFIG_DIR "/demo.toml");
  for (const std::string key : {"wmm = \"", "path = \"", "can_config = \""}) {
    for (std::size_t at = demo.find(key); at != std::string::npos; at = demo.find(key, at + 1)) {
      demo.insert(at + key.size(), HEADINGD_CONFIG_DIR "/");
    }
  }
  const std::string url = lcmUrl(6);
  demo.replace(demo.find("udpm://239.255.76.67:7667?ttl=0"), 31, url);
  demo.replace(demo.find("speed = 1.0"), 11, "speed = 20.0");
  const std::string config = dir.write("demo.toml", demo);
  LcmCollector lcm(url);
  ChildProcess daemon({HEADINGD_BIN, "--config", config}, dir.file("out"), dir.file("err"));
  EXPECT_EQ(daemon.waitFor(60s), 0) << test::readFile(dir.file("err"));
  std::this_thread::sleep_for(200ms);
  lcm.stop();

  const auto status = lcm.status();
  ASSERT_FALSE(status.empty()) << test::readFile(dir.file("err"));
  std::map<std::string, const headingd::source_status_t*> by_kind;
  for (const auto& s : status.back().message.sources) by_kind[s.kind] = &s;
  ASSERT_EQ(by_kind.count("candump_log"), 1u);
  ASSERT_EQ(by_kind.count("nmea_log"), 1u);
  auto counter = [](const headingd::source_status_t* s, const std::string& name) -> std::int64_t {
    for (const auto& c : s->counters) {
      if (c.name == name) return c.value;
    }
    return -1;
  };
  const auto* can = by_kind["candump_log"];
  const auto* gps = by_kind["nmea_log"];
  EXPECT_EQ(can->state, "finished");
  EXPECT_EQ(gps->state, "finished");
  EXPECT_EQ(counter(can, "frames_played"), 180003);
  EXPECT_EQ(counter(can, "samples"), 60001);
  EXPECT_EQ(counter(can, "incomplete_epochs"), 0);
  EXPECT_EQ(counter(can, "log_bad_lines"), 0);
  EXPECT_EQ(counter(gps, "epochs"), 601);
  EXPECT_EQ(status.back().message.rings[0].dropped, 0);
  // The subscriber may miss a few of 2000 IMU messages a second (UDP); the daemon sent all.
  EXPECT_GE(lcm.imu().size(), 60001u * 98 / 100);
  EXPECT_GE(lcm.gps().size(), 601u * 98 / 100);
  EXPECT_NE(test::readFile(dir.file("out")).find("| heading "), std::string::npos);  // the console line

  // True heading against the truth, by the sample's log time (UNIX time of sim time 0:
  // 1780315200 s, config/demo/README.md), interpolated between the truth's 10 Hz rows, after
  // the first minute.
  std::vector<double> truth_deg;
  {
    const std::string cmd = "zcat " HEADINGD_CONFIG_DIR "/demo/sim-urban-walk-truth.csv.gz > " + dir.file("truth.csv");
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    std::istringstream rows(test::readFile(dir.file("truth.csv")));
    std::string line;
    std::getline(rows, line);
    while (std::getline(rows, line)) truth_deg.push_back(std::strtod(line.c_str() + line.find(',') + 1, nullptr));
  }
  std::vector<double> errors;
  for (const auto& h : lcm.heading()) {
    if (h.message.validity != kFresh) continue;
    const std::int64_t since_us = h.message.sample_utime - 1'780'315'200'000'000;
    if (since_us < 60'000'000) continue;
    const auto row = static_cast<std::size_t>(since_us / 100'000);
    if (row + 1 >= truth_deg.size()) continue;
    const double f = static_cast<double>(since_us % 100'000) / 100'000.0;
    const double want = truth_deg[row] + f * std::remainder(truth_deg[row + 1] - truth_deg[row], 360.0);
    errors.push_back(std::abs(std::remainder(h.message.heading_true_rad * core::kDegPerRad - want, 360.0)));
  }
  ASSERT_GT(errors.size(), 1000u);
  double sum_sq = 0.0;
  for (const double e : errors) sum_sq += e * e;
  std::sort(errors.begin(), errors.end());
  const double rms = std::sqrt(sum_sq / static_cast<double>(errors.size()));
  std::fprintf(stderr, "demo capture at 20x: %zu estimates, true heading error RMS %.2f deg, p95 %.2f deg\n",
               errors.size(), rms, errors[errors.size() * 95 / 100]);
  EXPECT_LT(rms, 15.0);
}

TEST(DaemonCommandLine, BadConfigurationStopsWithFileLineAndKey) {
  TempDir dir;
  const std::string bad = dir.write("bad.toml", "[daemon]\nrate_hz = 0\n");
  ChildProcess check({HEADINGD_BIN, "--check-config", "--config", bad}, dir.file("out"), dir.file("err"));
  EXPECT_EQ(check.waitFor(10s), 2);
  const std::string err = test::readFile(dir.file("err"));
  EXPECT_NE(err.find(bad + ":2: [daemon] rate_hz: 0 is out of range"), std::string::npos) << err;

  // Starting for real with it fails the same way, before anything is published.
  ChildProcess run({HEADINGD_BIN, "--config", bad}, dir.file("out2"), dir.file("err2"));
  EXPECT_EQ(run.waitFor(10s), 2);
}

TEST(DaemonCommandLine, CheckConfigAcceptsTheShippedFilesAndVersionPrints) {
  TempDir dir;
  for (const char* name : {"/headingd.toml", "/demo.toml"}) {
    ChildProcess check({HEADINGD_BIN, "--check-config", "--config", std::string(HEADINGD_CONFIG_DIR) + name},
                       dir.file("out"), dir.file("err"));
    EXPECT_EQ(check.waitFor(20s), 0) << name << ": " << test::readFile(dir.file("err"));
    EXPECT_NE(test::readFile(dir.file("out")).find("configuration good"), std::string::npos);
  }
  ChildProcess version({HEADINGD_BIN, "--version"}, dir.file("out"), dir.file("err"));
  EXPECT_EQ(version.waitFor(5s), 0);
  EXPECT_EQ(test::readFile(dir.file("out")).rfind("headingd ", 0), 0u);
}

}  // namespace
}  // namespace headingd::daemon
