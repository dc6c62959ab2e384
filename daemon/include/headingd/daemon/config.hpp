#pragma once
// The daemon's configuration: one TOML file, validated completely at start-up. Every key,
// its default and its range are documented in config/headingd.toml; daemon/README.md says
// what each does. Relative paths are taken from the folder of the configuration file.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/estimator_params.hpp"
#include "headingd/core/params_toml.hpp"  // core::ConfigError
#ifdef HEADINGD_WITH_CAN
#include "headingd/can/can_config.hpp"
#include "headingd/can/can_config_toml.hpp"
#endif
#ifdef HEADINGD_WITH_GPS_SERIAL
#include "headingd/nmea/serial_gps_config.hpp"
#endif

namespace headingd::daemon {

// What a file source does when its file is played to the end.
enum class AtEnd {
  kStay,  // keep running without data (STATUS goes degraded after imu_timeout_s)
  kExit,  // stop the daemon (exit status 0), after publishing the last estimate
  kLoop,  // play again, later on the time axis by the file's length plus one sample period
};

struct ImuCsvSourceConfig {
  bool enabled = false;
  std::string imu_csv_path;  // BROAD format, plain or gzip (drivers/files imu_csv.hpp)
  std::string nmea_path;     // optional GPS capture on the IMU time axis ("" = none)
  double nmea_first_epoch_t_s = 0.0;
  double speed = 1.0;        // play speed, 1 = real time
  double start_delay_s = 0.0;
  AtEnd at_end = AtEnd::kStay;
  // false: samples keep the file's own time column (what headingd-replay sees, any speed).
  // true: the file's times moved by one constant onto CLOCK_MONOTONIC (speed 1 only), the
  // axis of the live sources, so a recording can run beside a live GPS ([gps]).
  bool monotonic_time = false;
};

// [playback]: the pace shared by the log file sources [candump_log] and [nmea_log], so that
// both play on one clock: log time t is played at start + (t - t0) / speed, where t0 is the
// earliest first timestamp of the logs.
struct PlaybackConfig {
  double speed = 1.0;          // 1 = real time; the estimator sees the logs' own timestamps at any speed
  double start_delay_s = 0.0;  // wait this long after start before the first frame or sentence
  AtEnd at_end = AtEnd::kStay;  // kStay or kExit ("loop" is for [imu_csv] only)
};

// [candump_log]: a `candump -l` log (plain or gzip) decoded like the live [can] source.
struct CandumpLogSourceConfig {
  bool enabled = false;
  std::string path;             // the log
  std::string can_config_path;  // a TOML file with a [can] table (DBC, signal mapping, counters, epoch window)
};

// [nmea_log]: an NMEA 0183 log (plain text) played by drivers/nmea's NmeaLogPlayer.
struct NmeaLogSourceConfig {
  bool enabled = false;
  std::string path;
  // Added to the sentences' UTC to put the epochs on the candump log's clock (a recorder
  // whose wall clock was off by this much).
  double time_offset_s = 0.0;
};

struct RealtimeConfig {
  int sched_fifo_priority = 0;     // 0 = normal scheduling; 1..99 = SCHED_FIFO for the estimator thread
  std::vector<int> cpu_affinity;   // empty = any CPU
  bool lock_memory = false;        // mlockall(MCL_CURRENT | MCL_FUTURE)
};

struct LcmConfig {
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  std::string heading_channel = "HEADING";
  std::string attitude_channel = "ATTITUDE";
  std::string imu_channel = "IMU";
  std::string gps_channel = "GPS";
  std::string status_channel = "STATUS";
  bool publish_imu = true;
  bool publish_gps = true;
};

struct LogConfig {
  std::string level = "info";  // trace, debug, info, warn, error, critical, off
  std::string file;            // "" = stderr only; else also this file (reopened on SIGHUP)
  int repeat_burst = 5;        // messages of one kind logged before suppression starts
  double repeat_interval_s = 10.0;  // ... per this interval; the suppressed count is logged
};

struct DaemonConfig {
  std::string source;  // the file it came from
  // [daemon]
  double rate_hz = 100.0;
  double imu_timeout_s = 0.5;
  double status_period_s = 1.0;
  bool console_status = false;  // one status line per status period on stdout
  std::string wmm_path;         // World Magnetic Model coefficients ("" = none)
  std::string calibration_path; // IMU calibration (headingd-calibrate --out; "" = none), re-read on SIGHUP
  // [rings]
  std::size_t imu_ring_capacity = 4096;
  std::size_t gps_ring_capacity = 64;

  RealtimeConfig realtime;
  LcmConfig lcm;
  LogConfig log;
  core::EstimatorParams estimator;
  ImuCsvSourceConfig imu_csv;
  PlaybackConfig playback;
  CandumpLogSourceConfig candump_log;
  NmeaLogSourceConfig nmea_log;

  // [can] and [gps], read by the drivers' own loaders (drivers/can can_config.hpp,
  // drivers/nmea serial_gps_config.hpp); whether they were present.
  bool has_can_table = false;
  bool has_gps_table = false;
#ifdef HEADINGD_WITH_CAN
  std::optional<can::CanConfig> can;
#endif
#ifdef HEADINGD_WITH_GPS_SERIAL
  std::optional<nmea::SerialGpsConfig> gps;  // absent, or present with enabled = false: no GPS source
#endif
#ifdef HEADINGD_WITH_CAN
  std::optional<can::CanConfig> candump_log_can;  // [candump_log] can_config, when enabled
#endif
};

// Parses `toml_text` (named `source` in messages); relative paths are taken from `base_dir`
// (no trailing slash; "" = as written). Throws core::ConfigError naming file:line, the key
// and what was expected for unknown tables and keys, wrong types and out-of-range values.
DaemonConfig parseDaemonConfig(std::string_view toml_text, const std::string& source, const std::string& base_dir);

// Reads and parses a file; relative paths in it are taken from its folder.
DaemonConfig loadDaemonConfig(const std::string& path);

const char* atEndName(AtEnd a);

}  // namespace headingd::daemon
