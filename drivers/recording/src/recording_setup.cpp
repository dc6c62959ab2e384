#include "headingd/recording/recording_setup.hpp"

#include <toml++/toml.h>
#include <filesystem>

#include "headingd/can/can_config_toml.hpp"
#include "headingd/core/config_error.hpp"
#include "headingd/core/params_toml.hpp"
#include "headingd/core/toml_document.hpp"
#include "headingd/core/toml_table_reader.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/recording/recording_format.hpp"

namespace headingd::recording {
namespace {

std::string inFolder(const std::string& folder, std::string_view name) { return folder + "/" + std::string(name); }

toml::table readToml(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw core::ConfigError(path +
                            ": not found; expected a black-box recording folder (daemon/README.md, \"Black box\")");
  }
  return core::parseTomlDocument(files::readMaybeGzipFile(path, files::kConfigFileLimit), path);
}

}  // namespace

RecordingSetup loadRecordingSetup(const std::string& folder_in) {
  RecordingSetup s;
  s.folder = folder_in;
  while (s.folder.size() > 1 && s.folder.back() == '/') s.folder.pop_back();

  const std::string header_path = inFolder(s.folder, kHeaderFile);
  const toml::table header = readToml(header_path);
  core::TomlTableReader h(&header, header_path, "");
  if (h.string("format", "") != kFormatName) h.fail("format", "\"" + std::string(kFormatName) + "\"");
  h.integer("format_version", 0, kFormatVersion, kFormatVersion);
  s.program_version = h.string("program_version", "");
  s.start_utc = h.string("start_utc", "");
  s.can_time_offset_ns = h.integer("can_time_offset_ns", 0, INT64_MIN, INT64_MAX);
  // The rest of the header (start clocks, host, file list) is for people.

  const std::string config_path = inFolder(s.folder, kConfigFile);
  const toml::table config = readToml(config_path);
  if (const toml::table* can = core::tableOf(config, "can", config_path)) {
    s.can = can::parseCanTable(*can, config_path, s.folder);
  }
  if (const toml::table* gps = core::tableOf(config, "gps", config_path)) {
    s.gps = nmea::parseGpsTable(gps, config_path);
  }
  s.estimator = core::parseEstimatorTable(core::tableOf(config, "estimator", config_path), config_path);
  s.place = core::parsePlaceTable(core::tableOf(config, "place", config_path), config_path);
  if (const toml::table* daemon = core::tableOf(config, "daemon", config_path)) {
    core::TomlTableReader d(daemon, config_path, "daemon");
    if (const std::string wmm = d.string("wmm", ""); !wmm.empty()) s.wmm_path = inFolder(s.folder, wmm);
    if (const std::string cal = d.string("calibration", ""); !cal.empty()) s.calibration_path = inFolder(s.folder, cal);
    if (d.has("gps_date_seed")) s.gps_date_seed = d.number("gps_date_seed", 0.0, 1900.0, 2200.0, "year");
  }
  return s;
}

}  // namespace headingd::recording
