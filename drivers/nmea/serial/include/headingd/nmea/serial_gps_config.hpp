#pragma once
// Settings of the serial GPS driver, and their loader from the [gps] table of the daemon's
// TOML file (config/gps.toml documents every key), read with core::TomlTableReader: errors
// name the file, the line, the key and what was expected.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include <toml++/toml.h>

#include "headingd/nmea/parser.hpp"

namespace headingd::nmea {

struct SerialGpsConfig {
  bool enabled = true;
  std::string device = "/dev/ttyUSB0";  // a udev symlink such as /dev/gps0 survives replugging
  unsigned baud = 9600;                 // one of standardBaudRates(); 8N1, raw, no flow control
  // A device that cannot be opened is retried after initial, then after twice as long each
  // time, up to max; a successful open resets it. Bounded both ways: no busy loop, and a
  // replugged receiver is back within max.
  double reopen_backoff_initial_s = 0.5;
  double reopen_backoff_max_s = 5.0;
  // The line quiet this long after a sentence ends the epoch in progress, so a fix goes out
  // at the end of its burst instead of when the next epoch starts (0: wait for the next
  // epoch). A 1 Hz receiver at 9600 baud sends its burst in well under half a second and is
  // then silent; bytes inside a burst are milliseconds apart.
  double epoch_idle_s = 0.15;
  // While open, the path is checked this often: if it is gone or now names another device
  // (a udev symlink re-pointed), the port is closed and the path reopened. Not in the TOML.
  double path_check_s = 1.0;
  ParserConfig parser;
};

// The rates termios can set by name (B1200 ... B921600).
std::span<const std::uint32_t> standardBaudRates();
bool isStandardBaudRate(std::int64_t baud);

// Reads a [gps] table (null: absent, the defaults). Unknown keys, wrong types and
// out-of-range values throw core::ConfigError.
SerialGpsConfig parseGpsTable(const toml::table* gps_table, const std::string& source_name);
// The [gps] table of doc (other tables are not looked at).
SerialGpsConfig parseGpsConfig(const toml::table& doc, const std::string& source_name);
// The same from TOML text; syntax errors throw core::ConfigError with file:line.
SerialGpsConfig parseGpsConfigText(std::string_view toml_text, const std::string& source_name);

}  // namespace headingd::nmea
