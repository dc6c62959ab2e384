#include "headingd/gpsd/gpsd_config.hpp"

#include <algorithm>
#include <cctype>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/nmea/gps_table_keys.hpp"

namespace headingd::gpsd {

bool isPlausibleHost(const std::string& host) {
  // Letters, digits, '-', '.' (names, IPv4) and ':' (IPv6); at most a DNS name's 253.
  if (host.empty() || host.size() > 253) return false;
  return std::all_of(host.begin(), host.end(),
                     [](unsigned char c) { return std::isalnum(c) != 0 || c == '-' || c == '.' || c == ':'; });
}

GpsdConfig parseGpsdTable(const toml::table* gps, const std::string& source) {
  GpsdConfig c;
  core::TomlTableReader r(gps, source, "gps");
  c.enabled = r.boolean("enabled", c.enabled);
  r.choice("source", "gpsd", {"gpsd"});
  c.host = r.string("host", c.host);
  if (!isPlausibleHost(c.host)) {
    r.fail("host", "expected an IP address or host name such as \"127.0.0.1\", got \"" + c.host + "\"");
  }
  c.port = static_cast<unsigned>(r.integer("port", c.port, 1, 65535));
  nmea::readSharedGpsKeys(r, c.reopen_backoff_initial_s, c.reopen_backoff_max_s, c.epoch_idle_s,
                          "config/gps.toml documents them; device and baud are for source = \"serial\"");
  return c;
}

}  // namespace headingd::gpsd
