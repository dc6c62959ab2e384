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

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/sources/playback_clock.hpp"
#include "headingd/daemon/sources/source.hpp"
#include "headingd/daemon/sources/source_config.hpp"
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

// The rings the sources fill, owned by the daemon: each source gets rings of its own (it is
// their single producer), the estimator thread drains them all.
struct SourceRings {
  std::size_t imu_capacity = 0;
  std::size_t gps_capacity = 0;
  std::vector<std::unique_ptr<SampleRing<ImuRingEntry>>> imu;
  std::vector<std::unique_ptr<SampleRing<GpsRingEntry>>> gps;
};

// What a source's factory (SourceConfig::createSource) gets from the daemon: rings of its own,
// its index on STATUS, the black box's streams and the log clock for the log sources; and where
// a log source says where its log starts and ends, from which the daemon sets that clock.
struct SourceContext {
  SourceContext(SourceRings& rings, const PlaybackConfig& playback, const PlaybackClock* playback_clock,
                const RecorderSinks* recorder)
      : rings(rings), playback(playback), playback_clock(playback_clock), recorder(recorder) {}

  SourceRings& rings;
  const PlaybackConfig& playback;
  const PlaybackClock* playback_clock;      // filled by the daemon before it starts the sources
  const RecorderSinks* recorder;            // null: the live sources record nothing
  std::uint16_t source_index = 0;           // of the source being made
  std::optional<std::int64_t> log_t0_ns;    // earliest first timestamp of the log sources made so far
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

// One row of the registry: a source kind, by the table that configures it.
struct SourceKind {
  std::string_view table;  // "can": the table [can], and the source's name
  TimeAxis time_axis;      // the clock its samples are on (see SourceConfig::onMonotonicClock)
  // Reads the table (core::TomlTableReader, rejecting unknown keys) into settings that make the
  // source (SourceConfig::createSource); throws core::ConfigError.
  std::unique_ptr<SourceConfig> (*parse)(const SourceTable& table);
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

// Whether an enabled source reads a device (its kind's samples are on CLOCK_MONOTONIC): a run
// that the black box records, and not a replay. Files moved onto that clock do not count.
bool hasLiveSource(const SourceConfigs& configs);

// The tables of the kinds that read a device ("can", "gps"): a recording's replay drops them.
std::vector<std::string> liveSourceTableNames();

}  // namespace headingd::daemon
