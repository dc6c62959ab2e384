#pragma once
// headingd-replay --recording DIR: a black-box recording through the estimator as fast as
// the CPU allows, in the live run's order (drivers/recording), with the recording's own
// configuration, calibration and World Magnetic Model.
#include <string>

namespace headingd::replay {

struct RecordingReplayOptions {
  std::string dir;      // the recording folder
  std::string out_csv;  // one row per IMU sample ("" = none)
  std::string lcm_log;  // HEADING and ATTITUDE after every IMU sample and GPS epoch ("" = none)
};

// Returns the exit status; prints the counters as JSON lines on stderr.
int replayRecording(const RecordingReplayOptions& options);

}  // namespace headingd::replay
