#include "headingd/daemon/recorder/recorder_config.hpp"

#include <cstdlib>

#include "headingd/core/toml_table_reader.hpp"

namespace headingd::daemon {
namespace {

// systemd's StateDirectory= sets STATE_DIRECTORY to the absolute path(s), ':'-separated when
// the unit names several; the first is this service's own.
std::string stateDirectory() {
  const char* value = std::getenv("STATE_DIRECTORY");
  if (value == nullptr) return "";
  const std::string all(value);
  return all.substr(0, all.find(':'));
}

}  // namespace

RecorderConfig parseRecorderTable(const toml::table* table, const std::string& source, const std::string& base_dir) {
  RecorderConfig c;
  core::TomlTableReader r(table, source, "recorder");
  c.enabled = r.boolean("enabled", c.enabled);
  c.dir = r.path("dir", c.dir, base_dir);
  c.segment_max_bytes = static_cast<std::uint64_t>(r.integer("segment_max_bytes", 16 << 20, 4096, 1ll << 40));
  c.segment_max_age_s = r.number("segment_max_age_s", c.segment_max_age_s, 1.0, 7 * 86400.0, "s");
  c.total_max_bytes = static_cast<std::uint64_t>(r.integer("total_max_bytes", 1 << 30, 65536, 1ll << 50));
  c.ring_lines =
      static_cast<std::size_t>(r.integer("ring_lines", static_cast<std::int64_t>(c.ring_lines), 64, 1 << 20));
  r.rejectUnknownKeys();
  // Room for a few streams' open segments, which the cap never deletes.
  if (c.total_max_bytes < 4 * c.segment_max_bytes) {
    r.failBetween("total_max_bytes", "segment_max_bytes",
                  "total_max_bytes (" + std::to_string(c.total_max_bytes) +
                      ") must be at least 4 x segment_max_bytes (" + std::to_string(c.segment_max_bytes) + ")");
  }

  if (!c.enabled) {
    c.off_reason = "[recorder] enabled = false";
  } else if (c.dir.empty()) {
    const std::string state = stateDirectory();
    if (!state.empty()) {
      c.dir = state + "/recordings";
    } else {
      c.enabled = false;
      c.off_reason =
          "[recorder] dir is \"\" and STATE_DIRECTORY is not set (the systemd unit sets it): nothing is "
          "recorded; set [recorder] dir to record";
    }
  }
  return c;
}

}  // namespace headingd::daemon
