#include "headingd/daemon/sources/source_registry.hpp"

#include <algorithm>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/daemon/sources/can_imu_source.hpp"
#include "headingd/daemon/sources/candump_log_source.hpp"
#include "headingd/daemon/sources/gpsd_gps_source.hpp"
#include "headingd/daemon/sources/imu_csv_source.hpp"
#include "headingd/daemon/sources/nmea_log_source.hpp"
#include "headingd/daemon/sources/recording_source.hpp"
#include "headingd/daemon/sources/serial_gps_source.hpp"
#include "headingd/gpsd/gpsd_config.hpp"
#include "headingd/nmea/serial_gps_config.hpp"

namespace headingd::daemon {

const char* atEndName(AtEnd a) {
  switch (a) {
    case AtEnd::kStay: return "stay";
    case AtEnd::kExit: return "exit";
    case AtEnd::kLoop: return "loop";
  }
  return "?";
}

namespace {

// [gps] holds two kinds: source = "serial" (the default, the receiver's port read by the
// daemon) or "gpsd" (gpsd's JSON socket); each kind's settings make its own source.
std::unique_ptr<SourceConfig> parseGpsSource(const SourceTable& table) {
  core::TomlTableReader r(&table.table, table.source, "gps");
  if (r.choice("source", "serial", {"serial", "gpsd"}) == "gpsd") {
    return std::make_unique<GpsdGpsSourceConfig>(gpsd::parseGpsdTable(&table.table, table.source));
  }
  return std::make_unique<SerialGpsSourceConfig>(nmea::parseGpsTable(&table.table, table.source));
}

}  // namespace

const std::vector<SourceKind>& sourceKinds() {
  // One row per kind: table, clock of its samples, parse. The order is the order the sources
  // are made in (their index on STATUS, the order of their rings).
  static const std::vector<SourceKind> kinds = {
      {"can", TimeAxis::kMonotonic, &parseCanSource},
      {"gps", TimeAxis::kMonotonic, &parseGpsSource},  // serial or gpsd
      {"imu_csv", TimeAxis::kOwnFile, &parseImuCsvSource},
      {"candump_log", TimeAxis::kLogClock, &parseCandumpLogSource},
      {"nmea_log", TimeAxis::kLogClock, &parseNmeaLogSource},
      {"recording", TimeAxis::kLogClock, &parseRecordingSource},
  };
  return kinds;
}

namespace {

// [playback] belongs to no one source: it paces the log clock all kLogClock sources share.
PlaybackConfig parsePlaybackTable(const toml::table& doc, const std::string& source) {
  PlaybackConfig p;
  core::TomlTableReader playback(core::tableOf(doc, "playback", source), source, "playback");
  p.speed = playback.number("speed", p.speed, 0.01, 1000.0, "x real time");
  p.start_delay_s = playback.number("start_delay_s", p.start_delay_s, 0.0, 3600.0, "s");
  const std::string at_end = playback.choice("at_end", "stay", {"stay", "exit", "loop"});
  p.at_end = at_end == "exit" ? AtEnd::kExit : at_end == "loop" ? AtEnd::kLoop : AtEnd::kStay;
  playback.rejectUnknownKeys();
  return p;
}

const SourceKind& kindOf(const SourceConfig& config) {
  const auto& kinds = sourceKinds();
  return *std::find_if(kinds.begin(), kinds.end(), [&](const SourceKind& k) { return k.table == config.table; });
}

TimeAxis timeAxisOf(const SourceConfig& config) {
  const TimeAxis axis = kindOf(config).time_axis;
  return axis == TimeAxis::kOwnFile && config.onMonotonicClock() ? TimeAxis::kMonotonic : axis;
}

// "[a] / [b]" or "[a], [b] or [c]" of the kinds whose class `pick` accepts.
template <class Pick>
std::string tableList(Pick pick, const char* last_separator) {
  std::vector<std::string> names;
  for (const SourceKind& k : sourceKinds()) {
    if (pick(k.time_axis)) names.push_back("[" + std::string(k.table) + "]");
  }
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) list += i + 1 == names.size() ? last_separator : ", ";
    list += names[i];
  }
  return list;
}

// The estimator needs all samples on one time axis: a file on its own axis cannot run with
// the live sources (samples hours apart), and the logs' recorded clock with nothing else.
void checkTimeAxes(const SourceConfigs& configs, const toml::table& doc, const std::string& source) {
  std::vector<const SourceConfig*> enabled;
  for (const auto& c : configs.tables) {
    if (c->enabled) enabled.push_back(c.get());
  }
  auto any = [&](auto pred) { return std::any_of(enabled.begin(), enabled.end(), pred); };
  auto failAtEnabled = [&](const SourceConfig& c, const std::string& what) {
    core::TomlTableReader(core::tableOf(doc, c.table, source), source, c.table).fail("enabled", what);
  };
  const bool live = any([](const SourceConfig* c) { return timeAxisOf(*c) == TimeAxis::kMonotonic; });
  for (const SourceConfig* c : enabled) {
    if (timeAxisOf(*c) == TimeAxis::kOwnFile && live) {
      failAtEnabled(*c, "a file source on its own time axis cannot run together with the live sources " +
                            tableList([](TimeAxis a) { return a == TimeAxis::kMonotonic; }, " / ") +
                            "; set time_axis = \"monotonic\" (speed 1) or disable one of them");
    }
  }
  const bool not_log = any([](const SourceConfig* c) { return timeAxisOf(*c) != TimeAxis::kLogClock; });
  for (const SourceConfig* c : enabled) {
    if (timeAxisOf(*c) == TimeAxis::kLogClock && not_log) {
      failAtEnabled(*c, "the log sources " + tableList([](TimeAxis a) { return a == TimeAxis::kLogClock; }, " and ") +
                            " play on the logs' own clock and cannot run together with " +
                            tableList([](TimeAxis a) { return a != TimeAxis::kLogClock; }, " or ") +
                            "; disable one of them");
    }
  }
}

}  // namespace

SourceConfigs parseSourceTables(const toml::table& doc, const std::string& source, const std::string& base_dir) {
  SourceConfigs configs;
  configs.playback = parsePlaybackTable(doc, source);
  for (const SourceKind& kind : sourceKinds()) {
    const toml::table* table = core::tableOf(doc, kind.table, source);
    if (table == nullptr) continue;
    std::unique_ptr<SourceConfig> config = kind.parse(SourceTable{*table, source, base_dir});
    config->table = kind.table;
    configs.tables.push_back(std::move(config));
  }
  checkTimeAxes(configs, doc, source);
  // A recording is a run to be replayed as it ran (bit for bit, daemon/README.md): once.
  const auto* recording = configs.find<RecordingSourceConfig>();
  if (configs.playback.at_end == AtEnd::kLoop && recording != nullptr && recording->enabled) {
    core::TomlTableReader(core::tableOf(doc, "playback", source), source, "playback")
        .fail("at_end",
              "\"loop\" plays [candump_log] and [nmea_log] again and again; a [recording] is replayed "
              "once, as it ran: use \"stay\" or \"exit\"");
  }
  return configs;
}

std::vector<std::string> sourceTableNames() {
  std::vector<std::string> names = {"playback"};
  for (const SourceKind& kind : sourceKinds()) names.emplace_back(kind.table);
  return names;
}

std::vector<std::unique_ptr<Source>> makeSources(const SourceConfigs& configs, SourceContext& context) {
  std::vector<std::unique_ptr<Source>> sources;
  for (const auto& config : configs.tables) {
    if (!config->enabled) continue;
    context.source_index = static_cast<std::uint16_t>(sources.size());
    sources.push_back(config->createSource(context));
  }
  return sources;
}

bool usesLogClock(const SourceConfigs& configs) {
  return std::any_of(configs.tables.begin(), configs.tables.end(),
                     [](const auto& c) { return c->enabled && timeAxisOf(*c) == TimeAxis::kLogClock; });
}

bool hasLiveSource(const SourceConfigs& configs) {
  return std::any_of(configs.tables.begin(), configs.tables.end(),
                     [](const auto& c) { return c->enabled && kindOf(*c).time_axis == TimeAxis::kMonotonic; });
}

std::vector<std::string> liveSourceTableNames() {
  std::vector<std::string> names;
  for (const SourceKind& kind : sourceKinds()) {
    if (kind.time_axis == TimeAxis::kMonotonic) names.emplace_back(kind.table);
  }
  return names;
}

SampleRing<ImuRingEntry>* SourceContext::addImuRing(const std::string& source_name) {
  rings.imu.push_back(std::make_unique<SampleRing<ImuRingEntry>>(source_name + ".imu", rings.imu_capacity));
  return rings.imu.back().get();
}

SampleRing<GpsRingEntry>* SourceContext::addGpsRing(const std::string& source_name) {
  rings.gps.push_back(std::make_unique<SampleRing<GpsRingEntry>>(source_name + ".gps", rings.gps_capacity));
  return rings.gps.back().get();
}

void SourceContext::logStartsAt(std::optional<std::int64_t> log_ns) {
  if (log_ns && (!log_t0_ns || *log_ns < *log_t0_ns)) log_t0_ns = log_ns;
}

void SourceContext::logEndsAt(std::optional<std::int64_t> last_log_ns, std::optional<std::int64_t> sample_step_ns) {
  if (last_log_ns && (!log_end_ns || *last_log_ns > *log_end_ns)) log_end_ns = last_log_ns;
  if (sample_step_ns && *sample_step_ns > 0 && (!log_step_ns || *sample_step_ns < *log_step_ns)) {
    log_step_ns = sample_step_ns;
  }
}

std::int64_t SourceContext::loopLengthNs() const {
  if (!log_t0_ns || !log_end_ns) return 0;
  // A log of one sample (no step) still moves on: by a millisecond a loop.
  return std::max<std::int64_t>(*log_end_ns - *log_t0_ns, 0) + log_step_ns.value_or(1'000'000);
}

}  // namespace headingd::daemon
