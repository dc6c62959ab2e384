#pragma once
// The source kinds the daemon knows, one row each in source_registry.cpp: the TOML table a
// kind is configured by, the function that parses that table, the clock its samples are on,
// and the factory that makes the source. The daemon's configuration reader hands each source
// table to its row, and the daemon makes the enabled sources by walking the rows; neither
// names a kind. daemon/README.md ("Adding a source") shows how a kind is added.
#include <toml++/toml.h>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/daemon/playback_clock.hpp"
#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/sample_ring.hpp"
#include "headingd/daemon/source.hpp"
#include "headingd/daemon/source_config.hpp"
#include "headingd/recording/stream_recorders.hpp"

namespace headingd::daemon {

// A source table present in the configuration file, for its kind's parse function.
struct SourceTable {
  const toml::table& table;
  const std::string& source;    // the configuration file, for messages
  const std::string& base_dir;  // relative paths are taken from here
};

// The black box's streams for the live sources (daemon/README.md, "Black box"); a null sink:
// that stream is not recorded.
struct RecorderSinks {
  recording::LineSink* can = nullptr;
  recording::LineSink* gps = nullptr;
  std::int64_t can_time_offset_ns = 0;  // candump time minus estimator time (recording_format.hpp)
};

// What a factory gets from the daemon: rings of its own (the source is their single
// producer), its index on STATUS, and the log clock for the log sources.
struct SourceContext {
  std::size_t imu_ring_capacity;
  std::size_t gps_ring_capacity;
  std::vector<std::unique_ptr<SampleRing<ImuRingEntry>>>& imu_rings;  // owned by the daemon
  std::vector<std::unique_ptr<SampleRing<GpsRingEntry>>>& gps_rings;
  const PlaybackConfig& playback;
  const PlaybackClock* playback_clock;      // filled by the daemon before it starts the sources
  std::uint16_t source_index = 0;           // of the source being made
  std::optional<std::int64_t> log_t0_ns;    // earliest first timestamp of the log sources made so far
  const RecorderSinks* recorder = nullptr;  // null: the live sources record nothing
  std::optional<std::int64_t> log_end_ns;   // latest last timestamp of the log sources made so far
  std::optional<std::int64_t> log_step_ns;  // shortest sample period of the log sources made so far

  // A new ring named "<source_name>.imu" / "<source_name>.gps".
  SampleRing<ImuRingEntry>* addImuRing(const std::string& source_name);
  SampleRing<GpsRingEntry>* addGpsRing(const std::string& source_name);
  // A log source's first timestamp on the log clock (nullopt: it has none).
  void logStartsAt(std::optional<std::int64_t> log_ns);
  // A log source's last timestamp and its usual step between samples (epochs), for the loop
  // length of [playback] at_end = "loop" (playback_clock.hpp); nullopt: it has none.
  void logEndsAt(std::optional<std::int64_t> last_log_ns, std::optional<std::int64_t> sample_step_ns);
  // One loop's length on the log axis from the spans reported so far (0: no log has times).
  std::int64_t loopLengthNs() const;
};

struct SourceKind {
  std::string_view table;  // "can": the table [can], and the source's name
  TimeAxis time_axis;      // the clock its samples are on (see SourceConfig::onMonotonicClock)
  // Reads the table (core::TomlTableReader, rejecting unknown keys); throws core::ConfigError.
  std::unique_ptr<SourceConfig> (*parse)(const SourceTable& table);
  // Makes the source of an enabled table (reading its files) and logs one line saying what
  // it plays; throws on any problem. Starts nothing.
  std::unique_ptr<Source> (*create)(const SourceConfig& config, SourceContext& context);
};

// The rows, in the order the sources are made.
const std::vector<SourceKind>& sourceKinds();

// The source tables of `doc` and [playback]: each parsed by its kind, then checked against
// each other (the time axes must agree). Throws core::ConfigError.
SourceConfigs parseSourceTables(const toml::table& doc, const std::string& source, const std::string& base_dir);

// The names of the tables parseSourceTables reads ("playback" and every kind's).
std::vector<std::string> sourceTableNames();

// Makes the enabled sources, in the rows' order.
std::vector<std::unique_ptr<Source>> makeSources(const SourceConfigs& configs, SourceContext& context);

// Whether an enabled source plays on the log clock.
bool usesLogClock(const SourceConfigs& configs);

}  // namespace headingd::daemon
