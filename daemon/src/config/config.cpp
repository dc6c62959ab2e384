#include "headingd/daemon/config/config.hpp"
#include "headingd/core/toml_document.hpp"

#include <toml++/toml.h>
#include <filesystem>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/daemon/sources/readable_path.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::daemon {
namespace {

using core::TomlTableReader;

// LCM channel names: non-empty, printable, no spaces (they are typed on command lines).
void checkChannel(TomlTableReader& r, std::string_view key, const std::string& channel) {
  if (channel.empty() || channel.size() > 63) r.fail(key, "expected a channel name of 1 to 63 characters");
  for (const char c : channel) {
    if (c <= ' ' || c > '~') r.fail(key, "'" + channel + "': a channel name has no spaces or control characters");
  }
}

}  // namespace

DaemonConfig parseDaemonConfig(std::string_view text, const std::string& source, const std::string& base_dir) {
  toml::table doc = core::parseTomlDocument(text, source);

  // The daemon's own tables; the sources' are the registry's.
  std::vector<std::string> tables = {"daemon",    "log",   "realtime", "rings",   "lcm",
                                     "estimator", "place", "recorder", "nmea_out"};
  for (std::string& t : sourceTableNames()) tables.push_back(std::move(t));
  core::rejectUnknownTables(doc, source, tables);

  DaemonConfig c;
  c.source = source;
  c.text = text;

  TomlTableReader daemon(doc["daemon"].as_table(), source, "daemon");
  c.rate_hz = daemon.number("rate_hz", c.rate_hz, 1.0, 2000.0, "Hz");
  c.imu_timeout_s = daemon.number("imu_timeout_s", c.imu_timeout_s, 0.01, 60.0, "s");
  c.status_period_s = daemon.number("status_period_s", c.status_period_s, 0.1, 60.0, "s");
  c.console_status = daemon.boolean("console_status", c.console_status);
  c.publish_on_imu = daemon.choice("publish", c.publish_on_imu ? "imu" : "tick", {"tick", "imu"}) == "imu";
  c.wmm_path = readablePath(daemon, "wmm", c.wmm_path, base_dir, true, files::kWmmFileLimit);
  c.calibration_path = readablePath(daemon, "calibration", c.calibration_path, base_dir, true, files::kConfigFileLimit);
  if (daemon.has("gps_date_seed")) c.gps_date_seed = daemon.number("gps_date_seed", 0.0, 1900.0, 2200.0, "year");
  daemon.rejectUnknownKeys();

  TomlTableReader log(doc["log"].as_table(), source, "log");
  c.log.level = log.choice("level", c.log.level, {"trace", "debug", "info", "warn", "error", "critical", "off"});
  c.log.file = log.path("file", c.log.file, base_dir);
  c.log.repeat_burst = static_cast<int>(log.integer("repeat_burst", c.log.repeat_burst, 1, 1000));
  c.log.repeat_interval_s = log.number("repeat_interval_s", c.log.repeat_interval_s, 0.1, 3600.0, "s");
  log.rejectUnknownKeys();

  TomlTableReader realtime(doc["realtime"].as_table(), source, "realtime");
  c.realtime.sched_fifo_priority =
      static_cast<int>(realtime.integer("sched_fifo_priority", c.realtime.sched_fifo_priority, 0, 99));
  c.realtime.driver_fifo_priority =
      static_cast<int>(realtime.integer("driver_fifo_priority", c.realtime.driver_fifo_priority, 0, 99));
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
  std::string* channels[] = {&c.lcm.heading_channel, &c.lcm.attitude_channel, &c.lcm.imu_channel, &c.lcm.gps_channel,
                             &c.lcm.status_channel};
  const char* channel_keys[] = {"heading_channel", "attitude_channel", "imu_channel", "gps_channel", "status_channel"};
  for (int i = 0; i < 5; ++i) {
    *channels[i] = lcm.string(channel_keys[i], *channels[i]);
    checkChannel(lcm, channel_keys[i], *channels[i]);
    for (int j = 0; j < i; ++j) {
      if (*channels[j] == *channels[i]) {
        lcm.fail(channel_keys[i],
                 "'" + *channels[i] + "' is already the " + channel_keys[j] + "; expected a channel of its own");
      }
    }
  }
  c.lcm.publish_imu = lcm.boolean("publish_imu", c.lcm.publish_imu);
  c.lcm.publish_gps = lcm.boolean("publish_gps", c.lcm.publish_gps);
  c.lcm.send_queue_bytes = static_cast<std::size_t>(
      lcm.integer("send_queue_bytes", static_cast<std::int64_t>(c.lcm.send_queue_bytes), 64 << 10, 1 << 30));
  lcm.rejectUnknownKeys();

  c.estimator = core::parseEstimatorTable(doc["estimator"].as_table(), source);
  c.place = core::parsePlaceTable(doc["place"].as_table(), source);
  if (c.place && c.wmm_path.empty()) {
    throw core::ConfigError(source + ": [place] needs the World Magnetic Model; [daemon] wmm is \"\"");
  }
  c.recorder = parseRecorderTable(doc["recorder"].as_table(), source, base_dir);
  c.nmea_out = parseNmeaOutTable(doc["nmea_out"].as_table(), source, c.rate_hz);

  c.sources = parseSourceTables(doc, source, base_dir);
  return c;
}

DaemonConfig loadDaemonConfig(const std::string& path) {
  std::string text;
  try {
    text = files::readWholeFile(path, files::kConfigFileLimit);
  } catch (const files::FileError& e) {
    throw core::ConfigError(std::string(e.what()) + " (the configuration file)");
  }
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  const std::string base_dir = ec ? std::string() : absolute.parent_path().string();
  return parseDaemonConfig(text, path, base_dir);
}

}  // namespace headingd::daemon
