#pragma once
// What a recording folder says about the run it holds (recording_format.hpp): the clocks,
// the CAN and GPS settings its streams are decoded with, and the estimator's settings and
// files, all read from the folder alone (the copies, never the paths of the original run).
#include <cstdint>
#include <optional>
#include <string>

#include "headingd/can/can_config.hpp"
#include "headingd/core/configured_place.hpp"
#include "headingd/core/estimator_params.hpp"
#include "headingd/nmea/serial_gps_config.hpp"

namespace headingd::recording {

struct RecordingSetup {
  std::string folder;
  std::string program_version;  // of the daemon that recorded
  std::string start_utc;
  std::int64_t can_time_offset_ns = 0;       // candump time minus estimator time
  std::optional<can::CanConfig> can;         // the [can] table, if the run had one
  std::optional<nmea::SerialGpsConfig> gps;  // the [gps] table, if the run had one
  core::EstimatorParams estimator;
  std::optional<core::ConfiguredPlace> place;  // the [place] table, with the date the run took
  std::string wmm_path;                        // in the folder; "" = the run had none
  std::string calibration_path;                // in the folder; "" = none
  std::optional<double> gps_date_seed;         // [daemon] gps_date_seed as the run used it
};

// Reads header.toml and config.toml of `folder`. Throws core::ConfigError (file:line, key)
// for a folder that is not a recording of this format version or whose files do not read.
RecordingSetup loadRecordingSetup(const std::string& folder);

}  // namespace headingd::recording
