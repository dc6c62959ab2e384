#pragma once
// The [can] table of the daemon's configuration: interface, DBC file, which DBC signals feed
// the gyro/accelerometer/magnetometer axes, epoch assembly and reconnection settings. Every
// key is documented in config/can-headingd.toml. Errors are core::ConfigError naming
// file:line, the key and what was expected (the style of core/params_toml.hpp).
#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/params_toml.hpp"

namespace headingd::can {

using core::ConfigError;

// "Message.Signal" in the DBC, optionally negated ("-Message.Signal") to flip an axis.
struct SignalRef {
  std::string message;
  std::string signal;
  bool negate = false;
  int line = 0;  // line of the key in the configuration file

  std::string text() const { return (negate ? "-" : "") + message + "." + signal; }
};

struct CanConfig {
  std::string source;  // configuration file name, for messages
  std::string interface = "can0";
  std::string dbc_path;  // as resolved: relative paths are taken from the configuration file's folder
  bool j1939 = false;    // match messages by PGN, ignoring priority and source address
  std::array<SignalRef, 3> gyro;
  std::array<SignalRef, 3> accel;
  std::optional<std::array<SignalRef, 3>> mag;  // without it every sample has has_mag = false
  std::vector<SignalRef> sequence;              // optional epoch counters, one per message
  std::optional<double> gyro_unit_factor;       // overrides the DBC unit: value * factor = rad/s
  std::optional<double> accel_unit_factor;      // ... = m/s^2
  std::optional<double> mag_unit_factor;        // ... = uT
  double epoch_window_s = 0.002;                // frames of one epoch arrive within this time of its first frame
  bool epoch_waits_for_mag = true;              // false: release on gyro+accel, a later mag goes to the next sample
  double reconnect_initial_s = 0.1;
  double reconnect_max_s = 5.0;
  int receive_buffer_bytes = 1 << 20;
  std::map<std::string, int> key_lines;  // key -> line, for errors found after parsing

  int lineOf(const std::string& key) const;
  std::string where(const std::string& key) const;  // "file:line: [can] key"
};

// Parses the [can] table of `toml_text` (other tables are left to their owners; a missing
// [can] table is an error). `config_dir` resolves a relative `dbc` path.
CanConfig parseCanConfig(std::string_view toml_text, const std::string& source_name, const std::string& config_dir);

// Reads the file and parses its [can] table; throws ConfigError (also if the file is unreadable).
CanConfig loadCanConfigFile(const std::string& path);

}  // namespace headingd::can
