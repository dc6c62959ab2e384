#include "headingd/daemon/config.hpp"
#include "headingd/core/toml_document.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "headingd/core/toml_table_reader.hpp"

namespace headingd::daemon {
namespace {

using core::rejectUnknownTables;
using core::sourceLine;
using core::TomlTableReader;

// A path key whose file must be readable at start-up (when `required`).
std::string readablePath(TomlTableReader& r, std::string_view key, const std::string& fallback,
                         const std::string& base_dir, bool required) {
  std::string path = r.path(key, fallback, base_dir);
  if (required && !path.empty() && !std::ifstream(path).good()) r.fail(key, "cannot open '" + path + "' for reading");
  return path;
}


// LCM channel names: non-empty, printable, no spaces (they are typed on command lines).
void checkChannel(TomlTableReader& r, std::string_view key, const std::string& channel) {
  if (channel.empty() || channel.size() > 63) r.fail(key, "expected a channel name of 1 to 63 characters");
  for (const char c : channel) {
    if (c <= ' ' || c > '~') r.fail(key, "'" + channel + "': a channel name has no spaces or control characters");
  }
}

}  // namespace

const char* atEndName(AtEnd a) {
  switch (a) {
    case AtEnd::kStay: return "stay";
    case AtEnd::kExit: return "exit";
    case AtEnd::kLoop: return "loop";
  }
  return "?";
}

DaemonConfig parseDaemonConfig(std::string_view text, const std::string& source, const std::string& base_dir) {
  toml::table doc = core::parseTomlDocument(text, source);

  rejectUnknownTables(doc, source, {"daemon", "log", "realtime", "rings", "lcm", "estimator", "imu_csv", "playback",
                                    "candump_log", "nmea_log", "can", "gps"});

  DaemonConfig c;
  c.source = source;

  TomlTableReader daemon(doc["daemon"].as_table(), source, "daemon");
  c.rate_hz = daemon.number("rate_hz", c.rate_hz, 1.0, 2000.0, "Hz");
  c.imu_timeout_s = daemon.number("imu_timeout_s", c.imu_timeout_s, 0.01, 60.0, "s");
  c.status_period_s = daemon.number("status_period_s", c.status_period_s, 0.1, 60.0, "s");
  c.console_status = daemon.boolean("console_status", c.console_status);
  c.wmm_path = readablePath(daemon, "wmm", c.wmm_path, base_dir, true);
  c.calibration_path = readablePath(daemon, "calibration", c.calibration_path, base_dir, true);
  daemon.rejectUnknownKeys();

  TomlTableReader log(doc["log"].as_table(), source, "log");
  c.log.level = log.choice("level", c.log.level, {"trace", "debug", "info", "warn", "error", "critical", "off"});
  c.log.file = log.path("file", c.log.file, base_dir);
  c.log.repeat_burst = static_cast<int>(log.integer("repeat_burst", c.log.repeat_burst, 1, 1000));
  c.log.repeat_interval_s = log.number("repeat_interval_s", c.log.repeat_interval_s, 0.1, 3600.0, "s");
  log.rejectUnknownKeys();

  TomlTableReader realtime(doc["realtime"].as_table(), source, "realtime");
  c.realtime.sched_fifo_priority = static_cast<int>(realtime.integer("sched_fifo_priority", 0, 0, 99));
  for (const std::int64_t cpu : realtime.integerArray("cpu_affinity", 0, 1023)) {
    c.realtime.cpu_affinity.push_back(static_cast<int>(cpu));
  }
  c.realtime.lock_memory = realtime.boolean("lock_memory", c.realtime.lock_memory);
  realtime.rejectUnknownKeys();

  TomlTableReader rings(doc["rings"].as_table(), source, "rings");
  c.imu_ring_capacity = static_cast<std::size_t>(rings.integer("imu_capacity", 4096, 16, 1 << 20));
  c.gps_ring_capacity = static_cast<std::size_t>(rings.integer("gps_capacity", 64, 4, 1 << 16));
  rings.rejectUnknownKeys();

  TomlTableReader lcm(doc["lcm"].as_table(), source, "lcm");
  c.lcm.url = lcm.string("url", c.lcm.url);
  {
    const std::string& url = c.lcm.url;
    const bool known_scheme = url.rfind("udpm://", 0) == 0 || url.rfind("file://", 0) == 0 ||
                              url.rfind("memq://", 0) == 0 || url.rfind("tcpq://", 0) == 0;
    if (!known_scheme) lcm.fail("url", "'" + url + "': expected an LCM URL (udpm://, file://, memq://, tcpq://)");
  }
  std::string* channels[] = {&c.lcm.heading_channel, &c.lcm.attitude_channel, &c.lcm.imu_channel,
                             &c.lcm.gps_channel, &c.lcm.status_channel};
  const char* channel_keys[] = {"heading_channel", "attitude_channel", "imu_channel", "gps_channel",
                                "status_channel"};
  for (int i = 0; i < 5; ++i) {
    *channels[i] = lcm.string(channel_keys[i], *channels[i]);
    checkChannel(lcm, channel_keys[i], *channels[i]);
    for (int j = 0; j < i; ++j) {
      if (*channels[j] == *channels[i]) {
        lcm.fail(channel_keys[i], "'" + *channels[i] + "' is already the " + channel_keys[j] + "; expected a channel of its own");
      }
    }
  }
  c.lcm.publish_imu = lcm.boolean("publish_imu", c.lcm.publish_imu);
  c.lcm.publish_gps = lcm.boolean("publish_gps", c.lcm.publish_gps);
  lcm.rejectUnknownKeys();

  c.estimator = core::parseEstimatorTable(doc["estimator"].as_table(), source);

  TomlTableReader csv(doc["imu_csv"].as_table(), source, "imu_csv");
  c.imu_csv.enabled = csv.boolean("enabled", c.imu_csv.enabled);
  c.imu_csv.imu_csv_path = readablePath(csv, "path", "", base_dir, c.imu_csv.enabled);
  if (c.imu_csv.enabled && c.imu_csv.imu_csv_path.empty()) {
    csv.fail("path", "expected the IMU CSV file to play (the source is enabled)");
  }
  c.imu_csv.nmea_path = readablePath(csv, "nmea", "", base_dir, c.imu_csv.enabled);
  c.imu_csv.nmea_first_epoch_t_s = csv.number("nmea_first_epoch_t_s", 0.0, -1e9, 1e9, "s");
  c.imu_csv.speed = csv.number("speed", c.imu_csv.speed, 0.01, 1000.0, "x real time");
  c.imu_csv.start_delay_s = csv.number("start_delay_s", c.imu_csv.start_delay_s, 0.0, 3600.0, "s");
  const std::string at_end = csv.choice("at_end", "stay", {"stay", "exit", "loop"});
  c.imu_csv.at_end = at_end == "exit" ? AtEnd::kExit : at_end == "loop" ? AtEnd::kLoop : AtEnd::kStay;
  c.imu_csv.monotonic_time = csv.choice("time_axis", "file", {"file", "monotonic"}) == "monotonic";
  if (c.imu_csv.monotonic_time && c.imu_csv.speed != 1.0) {
    csv.fail("time_axis", "\"monotonic\" needs speed = 1.0 (at another speed the file's time steps would not be the clock's)");
  }
  csv.rejectUnknownKeys();

  TomlTableReader playback(doc["playback"].as_table(), source, "playback");
  c.playback.speed = playback.number("speed", c.playback.speed, 0.01, 1000.0, "x real time");
  c.playback.start_delay_s = playback.number("start_delay_s", c.playback.start_delay_s, 0.0, 3600.0, "s");
  c.playback.at_end = playback.choice("at_end", "stay", {"stay", "exit"}) == "exit" ? AtEnd::kExit : AtEnd::kStay;
  playback.rejectUnknownKeys();

  TomlTableReader candump(doc["candump_log"].as_table(), source, "candump_log");
  c.candump_log.enabled = candump.boolean("enabled", false);
  c.candump_log.path = readablePath(candump, "path", "", base_dir, c.candump_log.enabled);
  c.candump_log.can_config_path = readablePath(candump, "can_config", "", base_dir, c.candump_log.enabled);
  if (c.candump_log.enabled) {
    if (c.candump_log.path.empty()) candump.fail("path", "expected the candump -l log to play (the source is enabled)");
    if (c.candump_log.can_config_path.empty()) {
      candump.fail("can_config", "expected a file with the [can] table that decodes the log (e.g. can-headingd.toml)");
    }
#ifdef HEADINGD_WITH_CAN
    c.candump_log_can = can::loadCanConfigFile(c.candump_log.can_config_path);
#else
    candump.fail("enabled", "this headingd was built without the CAN driver, which decodes candump logs");
#endif
  }
  candump.rejectUnknownKeys();

  TomlTableReader nmea_log(doc["nmea_log"].as_table(), source, "nmea_log");
  c.nmea_log.enabled = nmea_log.boolean("enabled", false);
  c.nmea_log.path = readablePath(nmea_log, "path", "", base_dir, c.nmea_log.enabled);
  if (c.nmea_log.enabled && c.nmea_log.path.empty()) {
    nmea_log.fail("path", "expected the NMEA log to play (the source is enabled)");
  }
  c.nmea_log.time_offset_s = nmea_log.number("time_offset_s", 0.0, -1e9, 1e9, "s");
#ifndef HEADINGD_WITH_GPS_SERIAL
  if (c.nmea_log.enabled) nmea_log.fail("enabled", "this headingd was built without the NMEA log player");
#endif
  nmea_log.rejectUnknownKeys();

  c.has_can_table = doc["can"].is_table();
  c.has_gps_table = doc["gps"].is_table();
  bool live_source = false;
#ifdef HEADINGD_WITH_CAN
  if (c.has_can_table) {
    c.can = can::parseCanTable(*doc["can"].as_table(), source, base_dir);
    live_source = true;
  }
#else
  if (c.has_can_table) throw core::ConfigError(sourceLine(source, *doc["can"].node()) + ": [can]: this headingd was built without the CAN driver");
#endif
#ifdef HEADINGD_WITH_GPS_SERIAL
  if (c.has_gps_table) {
    c.gps = nmea::parseGpsConfig(doc, source);
    live_source = live_source || c.gps->enabled;
  }
#else
  if (c.has_gps_table) throw core::ConfigError(sourceLine(source, *doc["gps"].node()) + ": [gps]: this headingd was built without the serial GPS driver");
#endif
  // A file plays on its own time axis, live sources on the monotonic clock: mixed, the
  // estimator would see samples hours apart.
  if (c.imu_csv.enabled && live_source && !c.imu_csv.monotonic_time) {
    csv.fail("enabled", "a file source on its own time axis cannot run together with the live sources "
                        "[can] / [gps]; set time_axis = \"monotonic\" (speed 1) or disable one of them");
  }
  // The logs play on their own clock (the candump log's UNIX time, the NMEA UTC).
  const bool log_source = c.candump_log.enabled || c.nmea_log.enabled;
  if (log_source && (live_source || c.imu_csv.enabled)) {
    TomlTableReader& r = c.candump_log.enabled ? candump : nmea_log;
    r.fail("enabled", "the log sources [candump_log] / [nmea_log] play on the logs' own clock and cannot run "
                      "together with [can], [gps] or [imu_csv]; disable one of them");
  }
  return c;
}

DaemonConfig loadDaemonConfig(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::ConfigError(path + ": cannot open the configuration file");
  std::ostringstream text;
  text << in.rdbuf();
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  const std::string base_dir = ec ? std::string() : absolute.parent_path().string();
  return parseDaemonConfig(text.str(), path, base_dir);
}

}  // namespace headingd::daemon
