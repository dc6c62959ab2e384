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

#include "headingd/core/configured_place.hpp"
#include "headingd/core/estimator_params.hpp"
#include "headingd/core/params_toml.hpp"  // core::ConfigError
#include "headingd/daemon/outputs/lcm_config.hpp"
#include "headingd/daemon/outputs/nmea_out_config.hpp"
#include "headingd/daemon/recorder/recorder_config.hpp"
#include "headingd/daemon/sources/source_config.hpp"

namespace headingd::daemon {

// [realtime]: real-time by default; each setting the system refuses is said once and the
// daemon runs on without it (realtime.hpp).
struct RealtimeConfig {
  int sched_fifo_priority = 50;   // 0 = normal scheduling; 1..99 = SCHED_FIFO for the estimator thread
  int driver_fifo_priority = 55;  // the same for the threads of the sources that read at real-time pace
  std::vector<int> cpu_affinity;  // empty = any CPU (the estimator thread)
  bool lock_memory = true;        // mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT)
};

struct LogConfig {
  std::string level = "info";       // trace, debug, info, warn, error, critical, off
  std::string file;                 // "" = stderr only; else also this file (reopened on SIGHUP)
  int repeat_burst = 5;             // messages of one kind logged before suppression starts
  double repeat_interval_s = 10.0;  // ... per this interval; the suppressed count is logged
};

struct DaemonConfig {
  std::string source;  // the file it came from
  std::string text;    // its text, as read (the black box keeps a copy)
  // [daemon]
  double rate_hz = 100.0;
  double imu_timeout_s = 0.5;
  double status_period_s = 1.0;
  bool console_status = false;   // one status line per status period on stdout
  bool publish_on_imu = false;   // [daemon] publish = "imu": also publish as each IMU sample arrives
  std::string wmm_path;          // World Magnetic Model coefficients ("" = none)
  std::string calibration_path;  // IMU calibration (headingd-calibrate --out; "" = none), re-read on SIGHUP
  // [daemon] gps_date_seed: the date GPS dates are checked against until one is believed
  // (core/gps_date_check.hpp). The daemon fills it in at start-up from the system clock when a
  // source is live and [place] gives no date, so a recording replays it exactly.
  std::optional<double> gps_date_seed;
  // [place]: where the WMM is evaluated until a GPS fix. The daemon fills in the date at
  // start-up when the table gives none (Daemon::Daemon), so a recording replays it exactly.
  std::optional<core::ConfiguredPlace> place;
  // [rings]
  std::size_t imu_ring_capacity = 4096;
  std::size_t gps_ring_capacity = 64;

  RealtimeConfig realtime;
  LcmConfig lcm;
  LogConfig log;
  core::EstimatorParams estimator;
  RecorderConfig recorder;  // [recorder]: the black box
  NmeaOutConfig nmea_out;   // [nmea_out]: the heading as NMEA over TCP/UDP
  // [playback] and the source tables, each read by its kind (source_registry.hpp).
  SourceConfigs sources;
};

// Parses `toml_text` (named `source` in messages); relative paths are taken from `base_dir`
// (no trailing slash; "" = as written). Throws core::ConfigError naming file:line, the key
// and what was expected for unknown tables and keys, wrong types and out-of-range values.
DaemonConfig parseDaemonConfig(std::string_view toml_text, const std::string& source, const std::string& base_dir);

// Reads and parses a file; relative paths in it are taken from its folder.
DaemonConfig loadDaemonConfig(const std::string& path);

}  // namespace headingd::daemon
