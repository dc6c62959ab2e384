#pragma once
// What the configuration says about the sources: one SourceConfig per source table present
// in the file ([can], [gps], [imu_csv], ...), each parsed by its own kind (source_registry.hpp),
// and [playback], the pace shared by the sources that play on the log clock.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace headingd::daemon {

class Source;
struct SourceContext;

// What a file source does when its file is played to the end.
enum class AtEnd {
  kStay,  // keep running without data (STATUS goes degraded after imu_timeout_s)
  kExit,  // stop the daemon (exit status 0), after publishing the last estimate
  kLoop,  // play again, later on the time axis by the file's length plus one sample period
};
const char* atEndName(AtEnd a);

// The clock a source's sample times are on. The estimator needs one axis for all its
// samples, so only sources of compatible axes can run together (source_registry.cpp).
enum class TimeAxis {
  kMonotonic,  // CLOCK_MONOTONIC: the live sources, and a file moved onto it (time_axis = "monotonic")
  kOwnFile,    // a file's own time column (time_axis = "file"): alone, or with other files of its kind only
  kLogClock,   // the logs' recorded clock (playback_clock.hpp): only with other log sources
};

// A file a source reads that a black-box recording keeps a copy of (the CAN source's DBC): the
// recording's configuration then names the copy instead (recording_files.hpp).
struct RecordedInputFile {
  std::string_view key;        // in the source's table, e.g. "dbc"
  std::string path;            // the file the live run reads
  std::string_view copy_name;  // the copy's name in the recording's folder
  std::uint64_t limit = 0;     // largest size read, in bytes
};

// One source table as parsed. Each kind derives its own settings from it, and those settings
// make their source: the daemon never needs to know which kind it holds.
struct SourceConfig {
  virtual ~SourceConfig() = default;
  std::string table;     // the TOML table it came from, also the source's name ("can")
  bool enabled = false;  // false: the table is present but the source does not run
  // For a kind on its own file axis: true when this configuration puts the file's times on
  // CLOCK_MONOTONIC instead, so that it can run beside the live sources.
  virtual bool onMonotonicClock() const { return false; }
  // Makes the source of an enabled table (reading its files) and logs one line saying what it
  // plays; throws on any problem. Starts nothing.
  virtual std::unique_ptr<Source> createSource(SourceContext& context) const = 0;
  // The files a black-box recording of this source copies (none by default).
  virtual std::vector<RecordedInputFile> recordedInputFiles() const { return {}; }
};

// [playback]: the pace shared by the log file sources ([candump_log], [nmea_log]), so that
// all of them play on one clock: log time t is played at start + (t - t0) / speed, where t0
// is the earliest first timestamp of the logs.
struct PlaybackConfig {
  double speed = 1.0;           // 1 = real time; the estimator sees the logs' own timestamps at any speed
  double start_delay_s = 0.0;   // wait this long after start before the first frame or sentence
  AtEnd at_end = AtEnd::kStay;  // kStay, kExit or kLoop (not with [recording]: a run replays once)
};

struct SourceConfigs {
  PlaybackConfig playback;
  // The source tables present in the file, in the registry's order (which is the order the
  // sources are made in, their index on STATUS).
  std::vector<std::shared_ptr<const SourceConfig>> tables;

  // The settings of the table of kind `T`, null if the file has no such table.
  template <class T>
  const T* find() const {
    for (const auto& t : tables) {
      if (const auto* found = dynamic_cast<const T*>(t.get())) return found;
    }
    return nullptr;
  }
};

}  // namespace headingd::daemon
