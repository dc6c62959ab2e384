// Configuration errors name file:line, the key and what was expected; shipped files parse.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "config_errors.hpp"
#include "daemon_test_support.hpp"
#include "headingd/daemon/config/config.hpp"
#include "headingd/daemon/sources/candump_log_source.hpp"
#include "headingd/daemon/sources/imu_csv_source.hpp"
#include "headingd/daemon/sources/nmea_log_source.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::daemon {
namespace {

using test::TempDir;

// The settings of a source table of kind T: as parsed when the file has the table, else the
// compiled-in defaults (what an absent table means).
template <class T>
T tableOr(const DaemonConfig& c) {
  const T* found = c.sources.find<T>();
  return found != nullptr ? *found : T{};
}

using DaemonConfigErrors = test::ConfigErrors;

TEST_F(DaemonConfigErrors, UnknownKeyNamesLineTableAndTheKnownKeys) {
  const std::string e = errorOf("[daemon]\nrate_hz = 50\nrate = 10\n");
  EXPECT_NE(e.find(at(3) + "[daemon] rate: unknown key"), std::string::npos) << e;
  EXPECT_NE(e.find("rate_hz"), std::string::npos) << e;
}

TEST_F(DaemonConfigErrors, UnknownTable) {
  const std::string e = errorOf("[daemon]\n\n[deamon]\nrate_hz = 5\n");
  EXPECT_NE(e.find(at(3) + "unknown table or key 'deamon'"), std::string::npos) << e;
}

TEST_F(DaemonConfigErrors, TopLevelKeyIsNotATable) {
  const std::string e = errorOf("lcm = 3\n");
  EXPECT_NE(e.find(at(1) + "'lcm' must be a table"), std::string::npos) << e;
}

TEST_F(DaemonConfigErrors, WrongType) {
  EXPECT_NE(errorOf("[daemon]\nrate_hz = \"fast\"\n").find(at(2) + "[daemon] rate_hz: expected a number in Hz"),
            std::string::npos);
  EXPECT_NE(errorOf("[rings]\nimu_capacity = 10.5\n").find(at(2) + "[rings] imu_capacity: expected an integer"),
            std::string::npos);
  EXPECT_NE(errorOf("[lcm]\npublish_imu = 1\n").find(at(2) + "[lcm] publish_imu: expected true or false"),
            std::string::npos);
  EXPECT_NE(errorOf("[realtime]\ncpu_affinity = 1\n").find(at(2) + "[realtime] cpu_affinity: expected an array"),
            std::string::npos);
}

TEST_F(DaemonConfigErrors, OutOfRange) {
  const std::string e = errorOf("[daemon]\nrate_hz = 5000\n");
  EXPECT_NE(e.find(at(2) + "[daemon] rate_hz: 5000 is out of range, expected 1 .. 2000 Hz"), std::string::npos) << e;
  const std::string p = errorOf("\n[realtime]\nsched_fifo_priority = 100\n");
  EXPECT_NE(p.find(at(3) + "[realtime] sched_fifo_priority: 100 is out of range"), std::string::npos) << p;
  const std::string d = errorOf("[realtime]\ndriver_fifo_priority = -1\n");
  const std::string expected = "[realtime] driver_fifo_priority: -1 is out of range, expected an integer 0 .. 99";
  EXPECT_NE(d.find(at(2) + expected), std::string::npos) << d;
}

// Real time by default: the estimator and the driver threads under SCHED_FIFO, the drivers
// above the estimator (config/headingd.toml says why), memory locked; 0 and false turn them off.
TEST(DaemonConfig, RealtimeIsTheDefaultAndCanBeTurnedOff) {
  const DaemonConfig d;
  EXPECT_EQ(d.realtime.sched_fifo_priority, 50);
  EXPECT_EQ(d.realtime.driver_fifo_priority, 55);
  EXPECT_TRUE(d.realtime.lock_memory);
  const DaemonConfig demo = loadDaemonConfig(HEADINGD_CONFIG_DIR "/demo.toml");
  EXPECT_EQ(demo.realtime.sched_fifo_priority, 50);
  EXPECT_EQ(demo.realtime.driver_fifo_priority, 55);
  EXPECT_TRUE(demo.realtime.lock_memory);
  const DaemonConfig off = parseDaemonConfig(
      "[realtime]\nsched_fifo_priority = 0\ndriver_fifo_priority = 0\nlock_memory = false\n", "off.toml", "");
  EXPECT_EQ(off.realtime.sched_fifo_priority, 0);
  EXPECT_EQ(off.realtime.driver_fifo_priority, 0);
  EXPECT_FALSE(off.realtime.lock_memory);
}

TEST_F(DaemonConfigErrors, NotOneOfTheChoices) {
  const std::string p = errorOf("[daemon]\npublish = \"sample\"\n");
  EXPECT_NE(p.find(at(2) + "[daemon] publish: 'sample' is not one of \"tick\", \"imu\""), std::string::npos) << p;
  const std::string e = errorOf("[imu_csv]\nat_end = \"bounce\"\n");
  EXPECT_NE(e.find(at(2) + "[imu_csv] at_end: 'bounce' is not one of \"stay\", \"exit\", \"loop\""), std::string::npos)
      << e;
}

TEST_F(DaemonConfigErrors, SyntaxError) {
  const std::string e = errorOf("[daemon]\nrate_hz = = 3\n");
  EXPECT_NE(e.find(at(2) + "TOML syntax error"), std::string::npos) << e;
}

TEST_F(DaemonConfigErrors, EstimatorTableKeepsItsLineNumbers) {
  const std::string head = "# comment\n[daemon]\nrate_hz = 100\n\n[estimator]\ngyro_noise_rad_s = 0.05\n";
  const std::string unknown = errorOf(head + "gyro_noize = 1\n");
  EXPECT_NE(unknown.find(at(7) + "[estimator] gyro_noize: unknown key"), std::string::npos) << unknown;
  const std::string range = errorOf(head + "\n\ngravity_m_s2 = 3\n");
  EXPECT_NE(range.find(at(9) + "[estimator] gravity_m_s2: 3 is out of range"), std::string::npos) << range;
  const std::string type = errorOf(head + "gravity_m_s2 = \"g\"\n[lcm]\n");
  EXPECT_NE(type.find(at(7) + "[estimator] gravity_m_s2: expected a number"), std::string::npos) << type;
  // Cross-checks between two keys name the later one's line.
  const std::string pair = errorOf(head + "redefine_heading_enter = 0.9\nredefine_heading_leave = 0.8\n");
  EXPECT_NE(pair.find(at(8) + "[estimator] redefine_heading_enter must be below"), std::string::npos) << pair;
}

TEST_F(DaemonConfigErrors, MissingFileNamesThePath) {
  const std::string e = errorOf("[imu_csv]\nenabled = true\npath = \"nope.csv\"\n");
  EXPECT_NE(e.find(at(3) + "[imu_csv] path: " + dir.file("nope.csv") + ": cannot open: No such file or directory"),
            std::string::npos)
      << e;
  const std::string none = errorOf("[imu_csv]\nenabled = true\n");
  EXPECT_NE(none.find("[imu_csv] path: expected the IMU CSV file"), std::string::npos) << none;
  const std::string wmm = errorOf("[daemon]\nwmm = \"/nonexistent/WMM.COF\"\n");
  EXPECT_NE(wmm.find(at(2) + "[daemon] wmm: /nonexistent/WMM.COF: cannot open"), std::string::npos) << wmm;
}

TEST_F(DaemonConfigErrors, WhatIsNoRegularFileOrTooLargeIsRefusedNamingTheKey) {
  // Each was accepted: /dev/zero was then read until the OOM killer acted, a FIFO hung.
  const std::string zero = errorOf("[daemon]\nwmm = \"/dev/zero\"\n");
  EXPECT_NE(zero.find(at(2) + "[daemon] wmm: /dev/zero: is a character device, not a regular file"), std::string::npos)
      << zero;
  ASSERT_EQ(::mkfifo(dir.file("fifo.log").c_str(), 0600), 0);
  const std::string fifo = errorOf("[candump_log]\nenabled = true\npath = \"fifo.log\"\ncan_config = \"x\"\n");
  EXPECT_NE(fifo.find(at(3) + "[candump_log] path: " + dir.file("fifo.log") + ": is a FIFO"), std::string::npos)
      << fifo;
  const std::string folder = errorOf("[imu_csv]\nenabled = true\npath = \".\"\n");
  EXPECT_NE(folder.find("[imu_csv] path: " + dir.file(".") + ": is a directory, not a file"), std::string::npos)
      << folder;
  dir.write("huge.toml", std::string(files::kConfigFileLimit + 1, '#'));
  const std::string huge = errorOf("[daemon]\ncalibration = \"huge.toml\"\n");
  EXPECT_NE(huge.find(at(2) + "[daemon] calibration: " + dir.file("huge.toml") +
                      ": is 1048577 bytes, more than the 1 MiB such a file may have"),
            std::string::npos)
      << huge;
}

TEST_F(DaemonConfigErrors, ChannelsMustDifferAndBeNames) {
  const std::string same = errorOf("[lcm]\nimu_channel = \"HEADING\"\n");
  EXPECT_NE(same.find(at(2) + "[lcm] imu_channel: 'HEADING' is already the heading_channel"), std::string::npos)
      << same;
  const std::string space = errorOf("[lcm]\nstatus_channel = \"MY STATUS\"\n");
  EXPECT_NE(space.find(at(2) + "[lcm] status_channel"), std::string::npos) << space;
  const std::string url = errorOf("[lcm]\nurl = \"http://x\"\n");
  EXPECT_NE(url.find(at(2) + "[lcm] url: 'http://x': expected an LCM URL"), std::string::npos) << url;
  const std::string queue = errorOf("[lcm]\nsend_queue_bytes = 1000\n");
  EXPECT_NE(queue.find(at(2) + "[lcm] send_queue_bytes"), std::string::npos) << queue;
}

TEST_F(DaemonConfigErrors, MonotonicTimeNeedsRealTimeSpeed) {
  const std::string e = errorOf("[imu_csv]\nspeed = 2.0\ntime_axis = \"monotonic\"\n");
  EXPECT_NE(e.find(at(3) + "[imu_csv] time_axis: \"monotonic\" needs speed = 1.0"), std::string::npos) << e;
}

TEST_F(DaemonConfigErrors, FileTimeCannotMixWithLiveSources) {
  dir.write("imu.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,9.81\n");
  const std::string e = errorOf("[imu_csv]\nenabled = true\npath = \"imu.csv\"\n[gps]\ndevice = \"/dev/null\"\n");
  EXPECT_NE(e.find(at(2) + "[imu_csv] enabled: a file source on its own time axis cannot run together"),
            std::string::npos)
      << e;
  EXPECT_EQ(errorOf("[imu_csv]\nenabled = true\npath = \"imu.csv\"\ntime_axis = \"monotonic\"\n"
                    "[gps]\ndevice = \"/dev/null\"\n"),
            "");
}

TEST(DaemonConfig, RelativePathsAreTakenFromTheConfigFolder) {
  TempDir dir;
  dir.write("imu.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,9.81\n");
  const DaemonConfig c = loadDaemonConfig(dir.write("ok.toml", "[imu_csv]\nenabled = true\npath = \"imu.csv\"\n"));
  EXPECT_EQ(tableOr<ImuCsvSourceConfig>(c).imu_csv_path, dir.path() + "/imu.csv");
  EXPECT_TRUE(tableOr<ImuCsvSourceConfig>(c).enabled);
  EXPECT_FALSE(tableOr<ImuCsvSourceConfig>(c).no_mag);  // a file without mag_* is refused at start
  const DaemonConfig six = loadDaemonConfig(dir.write(
      "six.toml", "[imu_csv]\nenabled = true\npath = \"imu.csv\"\nno_mag = true\n[daemon]\ngps_date_seed = 2026.5\n"));
  EXPECT_TRUE(tableOr<ImuCsvSourceConfig>(six).no_mag);
  EXPECT_EQ(six.gps_date_seed, 2026.5);
}

TEST(DaemonConfig, EmptyFileGivesTheDocumentedDefaults) {
  TempDir dir;
  const DaemonConfig c = loadDaemonConfig(dir.write("empty.toml", ""));
  EXPECT_EQ(c.rate_hz, 100.0);
  EXPECT_EQ(c.lcm.url, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(c.status_period_s, 1.0);
  EXPECT_FALSE(tableOr<ImuCsvSourceConfig>(c).enabled);
}

// config/headingd.toml documents every key with its default: loading it must give exactly
// the compiled-in defaults.
TEST(DaemonConfig, ShippedDefaultsFileMatchesTheCompiledDefaults) {
  const DaemonConfig shipped = loadDaemonConfig(HEADINGD_CONFIG_DIR "/headingd.toml");
  const DaemonConfig d;
  const ImuCsvSourceConfig shipped_csv = tableOr<ImuCsvSourceConfig>(shipped), d_csv;
  EXPECT_EQ(shipped.rate_hz, d.rate_hz);
  EXPECT_EQ(shipped.imu_timeout_s, d.imu_timeout_s);
  EXPECT_EQ(shipped.status_period_s, d.status_period_s);
  EXPECT_EQ(shipped.console_status, d.console_status);
  EXPECT_EQ(shipped.publish_on_imu, d.publish_on_imu);
  EXPECT_EQ(shipped.imu_ring_capacity, d.imu_ring_capacity);
  EXPECT_EQ(shipped.gps_ring_capacity, d.gps_ring_capacity);
  EXPECT_EQ(shipped.realtime.sched_fifo_priority, d.realtime.sched_fifo_priority);
  EXPECT_EQ(shipped.realtime.driver_fifo_priority, d.realtime.driver_fifo_priority);
  EXPECT_EQ(shipped.realtime.cpu_affinity, d.realtime.cpu_affinity);
  EXPECT_EQ(shipped.realtime.lock_memory, d.realtime.lock_memory);
  EXPECT_EQ(shipped.lcm.url, d.lcm.url);
  EXPECT_EQ(shipped.lcm.heading_channel, d.lcm.heading_channel);
  EXPECT_EQ(shipped.lcm.attitude_channel, d.lcm.attitude_channel);
  EXPECT_EQ(shipped.lcm.imu_channel, d.lcm.imu_channel);
  EXPECT_EQ(shipped.lcm.gps_channel, d.lcm.gps_channel);
  EXPECT_EQ(shipped.lcm.status_channel, d.lcm.status_channel);
  EXPECT_EQ(shipped.lcm.publish_imu, d.lcm.publish_imu);
  EXPECT_EQ(shipped.lcm.publish_gps, d.lcm.publish_gps);
  EXPECT_EQ(shipped.lcm.send_queue_bytes, d.lcm.send_queue_bytes);
  EXPECT_EQ(shipped.log.level, d.log.level);
  EXPECT_EQ(shipped.log.file, d.log.file);
  EXPECT_EQ(shipped.log.repeat_burst, d.log.repeat_burst);
  EXPECT_EQ(shipped.log.repeat_interval_s, d.log.repeat_interval_s);
  EXPECT_EQ(shipped_csv.enabled, d_csv.enabled);
  EXPECT_EQ(shipped_csv.speed, d_csv.speed);
  EXPECT_EQ(shipped_csv.at_end, d_csv.at_end);
  EXPECT_EQ(shipped_csv.monotonic_time, d_csv.monotonic_time);
  EXPECT_EQ(shipped_csv.start_delay_s, d_csv.start_delay_s);
  EXPECT_EQ(shipped_csv.nmea_first_epoch_t_s, d_csv.nmea_first_epoch_t_s);
  EXPECT_FALSE(shipped.wmm_path.empty());  // the shipped file names the bundled model
}

TEST_F(DaemonConfigErrors, LogSourcesNameTheirKeys) {
  EXPECT_NE(errorOf("[candump_log]\nenabled = true\n")
                .find(dir.file("bad.toml") + ": [candump_log] path: expected the candump -l log"),
            std::string::npos);
  dir.write("can.log", "(1.000000) can0 120#00\n");
  const std::string no_can = errorOf("[candump_log]\nenabled = true\npath = \"can.log\"\n");
  EXPECT_NE(no_can.find("[candump_log] can_config: expected a file with the [can] table"), std::string::npos) << no_can;
  const std::string missing = errorOf("[nmea_log]\nenabled = true\npath = \"none.nmea\"\n");
  EXPECT_NE(missing.find(at(3) + "[nmea_log] path: " + dir.file("none.nmea") + ": cannot open"), std::string::npos)
      << missing;
  EXPECT_NE(errorOf("[playback]\nspeed = 0\n").find(at(2) + "[playback] speed: 0 is out of range"), std::string::npos);
  EXPECT_NE(errorOf("[playback]\nat_end = \"rewind\"\n").find(at(2) + "[playback] at_end: 'rewind' is not one of"),
            std::string::npos);
  EXPECT_NE(errorOf("[nmea_log]\ntime_offset = 1\n").find(at(2) + "[nmea_log] time_offset: unknown key"),
            std::string::npos);
  dir.write("gps.nmea", "$GPGGA,120000.00,,,,,0,00,99.99,,M,,M,,*65\n");
  const std::string mixed = errorOf("[nmea_log]\nenabled = true\npath = \"gps.nmea\"\n[gps]\ndevice = \"/dev/null\"\n");
  EXPECT_NE(mixed.find(at(2) + "[nmea_log] enabled: the log sources [candump_log], [nmea_log] and [recording] play on "
                               "the logs' own clock and cannot run together"),
            std::string::npos)
      << mixed;
}

TEST(DaemonConfig, ShippedDefaultsFileHasTheLogSourceDefaults) {
  const DaemonConfig shipped = loadDaemonConfig(HEADINGD_CONFIG_DIR "/headingd.toml");
  const DaemonConfig d;
  const CandumpLogSourceConfig shipped_candump = tableOr<CandumpLogSourceConfig>(shipped), d_candump;
  const NmeaLogSourceConfig shipped_nmea = tableOr<NmeaLogSourceConfig>(shipped), d_nmea;
  EXPECT_EQ(shipped.sources.playback.speed, d.sources.playback.speed);
  EXPECT_EQ(shipped.sources.playback.start_delay_s, d.sources.playback.start_delay_s);
  EXPECT_EQ(shipped.sources.playback.at_end, d.sources.playback.at_end);
  EXPECT_EQ(shipped_candump.enabled, d_candump.enabled);
  EXPECT_EQ(shipped_candump.path, d_candump.path);
  EXPECT_EQ(shipped_candump.can_config_path, d_candump.can_config_path);
  EXPECT_EQ(shipped_nmea.enabled, d_nmea.enabled);
  EXPECT_EQ(shipped_nmea.path, d_nmea.path);
  EXPECT_EQ(shipped_nmea.time_offset_s, d_nmea.time_offset_s);
}

TEST(DaemonConfig, DemoConfigLoads) {
  const DaemonConfig demo = loadDaemonConfig(HEADINGD_CONFIG_DIR "/demo.toml");
  const CandumpLogSourceConfig demo_candump = tableOr<CandumpLogSourceConfig>(demo);
  const NmeaLogSourceConfig demo_nmea = tableOr<NmeaLogSourceConfig>(demo);
  EXPECT_TRUE(demo_candump.enabled);
  EXPECT_TRUE(demo_nmea.enabled);
  EXPECT_EQ(demo_candump.path, HEADINGD_CONFIG_DIR "/demo/sim-urban-walk-can.log.gz");
  EXPECT_EQ(demo.sources.playback.at_end, AtEnd::kExit);
  EXPECT_TRUE(demo.console_status);
  EXPECT_NE(demo.lcm.url.find("ttl=0"), std::string::npos);
}

}  // namespace
}  // namespace headingd::daemon
