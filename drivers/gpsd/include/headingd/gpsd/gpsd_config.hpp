#pragma once
// Settings of the gpsd client ([gps] with source = "gpsd"; config/gps.toml documents every
// key), read with core::TomlTableReader: errors name the file, the line, the key and what was
// expected.
#include <cstddef>
#include <string>

#include <toml++/toml.h>

namespace headingd::gpsd {

struct GpsdConfig {
  bool enabled = true;
  std::string host = "127.0.0.1";  // gpsd's JSON socket; a name is resolved at each connect
  unsigned port = 2947;            // gpsd's registered port
  // A failed connect is retried after initial, then twice as long each time up to max; a
  // connection that gpsd closes (restart) is retried after initial.
  double reopen_backoff_initial_s = 0.5;
  double reopen_backoff_max_s = 5.0;
  // Quiet this long after a report ends the epoch in progress (as for the serial source).
  double epoch_idle_s = 0.15;
  // A line longer than this is skipped and counted (gpsd's longest, a SKY with every
  // satellite of four constellations, is about 10 kB). Not in the TOML.
  std::size_t max_line_bytes = 65536;
};

// Whether `host` can be an IP address or a DNS name (not whether it resolves).
bool isPlausibleHost(const std::string& host);

// Reads a [gps] table whose source is "gpsd". Unknown keys (device, baud: serial only), wrong
// types and out-of-range values throw core::ConfigError.
GpsdConfig parseGpsdTable(const toml::table* gps_table, const std::string& source_name);

}  // namespace headingd::gpsd
