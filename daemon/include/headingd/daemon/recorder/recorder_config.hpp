#pragma once
// The [recorder] table: where the black box writes its recordings and how much it keeps.
// Every key, its default and range are documented in config/headingd.toml.
#include <toml++/toml.h>
#include <cstddef>
#include <cstdint>
#include <string>

namespace headingd::daemon {

struct RecorderConfig {
  // On by default: a black box is most useful when nobody remembered to turn it on. Where
  // nothing says where to write (dir "" and no STATE_DIRECTORY), it is off all the same.
  bool enabled = true;
  // "" = $STATE_DIRECTORY/recordings when STATE_DIRECTORY is set (systemd StateDirectory=),
  // else recording is off (off_reason says why). Relative paths: from the configuration's folder.
  std::string dir;
  std::uint64_t segment_max_bytes = 16ull << 20;  // a stream's file is closed and the next opened beyond this
  double segment_max_age_s = 3600.0;              // ... or after this long
  std::uint64_t total_max_bytes = 1ull << 30;     // cap over everything under dir: oldest segments deleted first
  std::size_t ring_lines = 8192;                  // per stream: lines held for the writer thread
  // Why recording is off ("" when enabled); the daemon logs it once at info.
  std::string off_reason;
};

// Parses [recorder] (null: absent, every key its default); base_dir for a relative dir.
// Unknown keys, wrong types and out-of-range values throw core::ConfigError naming file:line.
// Reads STATE_DIRECTORY from the environment when dir is "".
RecorderConfig parseRecorderTable(const toml::table* table, const std::string& source, const std::string& base_dir);

}  // namespace headingd::daemon
