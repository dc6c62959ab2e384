#include "headingd/daemon/recorder/recording_files.hpp"

#include <toml++/toml.h>
#include <unistd.h>
#include <ctime>
#include <sstream>

#include "headingd/core/toml_document.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/live/clocks.hpp"
#include "headingd/recording/recording_format.hpp"

namespace headingd::daemon {
namespace {

std::string utcText(std::int64_t realtime_ns) {
  const std::time_t seconds = static_cast<std::time_t>(realtime_ns / 1'000'000'000);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char text[64];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  std::snprintf(text + n, sizeof text - n, ".%06lldZ", static_cast<long long>((realtime_ns % 1'000'000'000) / 1000));
  return text;
}

std::string toText(const toml::table& doc) {
  std::ostringstream out;
  out << doc << '\n';
  return out.str();
}

// Sets `key` of table `name` in `doc` (creating the table).
void set(toml::table& doc, std::string_view name, std::string_view key, std::string_view value) {
  if (!doc.contains(name)) doc.insert(name, toml::table{});
  doc[name].as_table()->insert_or_assign(key, std::string(value));
}

}  // namespace

RecordingStart recordingStartNow(std::string program_version) {
  RecordingStart s;
  s.monotonic_ns = live::monotonicNs();
  s.realtime_ns = live::realtimeNs();
  const std::int64_t offset = s.realtime_ns - s.monotonic_ns;
  s.can_time_offset_ns = offset - offset % 1000;
  s.program_version = std::move(program_version);
  return s;
}

std::vector<std::pair<std::string, std::string>> recordingFiles(const DaemonConfig& config,
                                                                const RecordingStart& start) {
  using namespace recording;
  std::vector<std::pair<std::string, std::string>> files;
  toml::table doc = core::parseTomlDocument(config.text, config.source);
  std::string copies;  // for the header: which copies there are
  const auto copy = [&](std::string_view name, const std::string& path, std::uint64_t limit) {
    files.emplace_back(std::string(name), files::readMaybeGzipFile(path, limit));
    copies += "\"" + std::string(name) + "\" = \"" + path + "\"\n";
  };
  if (config.place && config.place->decimal_year) {
    // The date the run took (the table may have given none: then it was the day it started).
    if (auto* place = doc["place"].as_table()) {
      place->erase("date");
      place->insert_or_assign("decimal_year", *config.place->decimal_year);
    }
  }
  if (config.gps_date_seed) {
    // The date the run's GPS dates were checked against (the system's, when it gave it).
    if (!doc.contains("daemon")) doc.insert("daemon", toml::table{});
    doc["daemon"].as_table()->insert_or_assign("gps_date_seed", *config.gps_date_seed);
  }
  if (!config.wmm_path.empty()) {
    copy(kWmmFile, config.wmm_path, files::kWmmFileLimit);
    set(doc, "daemon", "wmm", kWmmFile);
  }
  if (!config.calibration_path.empty()) {
    copy(kCalibrationFile, config.calibration_path, files::kConfigFileLimit);
    set(doc, "daemon", "calibration", kCalibrationFile);
  }
  for (const auto& source : config.sources.tables) {
    if (!source->enabled) continue;
    for (const RecordedInputFile& f : source->recordedInputFiles()) {
      copy(f.copy_name, f.path, f.limit);
      set(doc, source->table, f.key, f.copy_name);
    }
  }
  files.emplace_back(std::string(kOriginalConfigFile), config.text);
  files.emplace_back(std::string(kConfigFile), toText(doc));

  // replay.toml: the same run with the live sources replaced by this folder, ended when played.
  toml::table replay = doc;
  for (const std::string& live : liveSourceTableNames()) replay.erase(live);
  for (const char* table : {"recorder", "playback"}) replay.erase(table);
  if (auto* log = replay["log"].as_table()) log->erase("file");  // never append to the live run's log
  replay.insert("recording", toml::table{{"enabled", true}, {"dir", "."}});
  replay.insert("playback", toml::table{{"speed", 1.0}, {"at_end", "exit"}});
  files.emplace_back(std::string(kReplayConfigFile),
                     "# Replays this recording through the daemon: headingd --config replay.toml\n"
                     "# [playback] speed sets the pace (the estimates do not depend on it). It publishes on the\n"
                     "# live run's LCM URL and channels: change [lcm] if a live headingd runs on this machine.\n" +
                         toText(replay));

  char host[256] = "";
  gethostname(host, sizeof host - 1);
  std::ostringstream header;
  header << "# A headingd black-box recording: daemon/README.md, \"Black box\", describes every file.\n"
         << "format = \"" << kFormatName << "\"\n"
         << "format_version = " << kFormatVersion << "\n"
         << "program_version = \"" << start.program_version << "\"\n"
         << "start_utc = \"" << utcText(start.realtime_ns) << "\"\n"
         << "# CLOCK_REALTIME and CLOCK_MONOTONIC at the start [ns]; the streams' times are monotonic.\n"
         << "start_realtime_ns = " << start.realtime_ns << "\n"
         << "start_monotonic_ns = " << start.monotonic_ns << "\n"
         << "# candump time in can.*.log minus the estimator's (monotonic) time [ns, whole µs]\n"
         << "can_time_offset_ns = " << start.can_time_offset_ns << "\n"
         << "hostname = \"" << host << "\"\n"
         << "config_path = \"" << config.source << "\"\n"
         << "\n# Copies in this folder, and the files they were copied from.\n[copied_from]\n"
         << copies;
  files.insert(files.begin(), {std::string(kHeaderFile), header.str()});
  return files;
}

}  // namespace headingd::daemon
