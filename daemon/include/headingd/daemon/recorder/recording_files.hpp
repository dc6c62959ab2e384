#pragma once
// The files a black-box recording starts with (drivers/recording's recording_format.hpp):
// header.toml, the configuration as it was and as rewritten to point at the copies, the
// replay configuration, and copies of the DBC, WMM and calibration files in use.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "headingd/daemon/config/config.hpp"

namespace headingd::daemon {

struct RecordingStart {
  std::int64_t realtime_ns = 0;
  std::int64_t monotonic_ns = 0;
  std::int64_t can_time_offset_ns = 0;  // candump time minus estimator time, whole µs
  std::string program_version;
};

// The clocks now, and the program's version.
RecordingStart recordingStartNow(std::string program_version);

// (name in the folder, content) for each file. Reads the files the configuration names;
// throws std::runtime_error if one cannot be read.
std::vector<std::pair<std::string, std::string>> recordingFiles(const DaemonConfig& config,
                                                                const RecordingStart& start);

}  // namespace headingd::daemon
