#pragma once
// A recording folder back into the calls the live estimator got, in the order it got them:
// each IMU sample as the CAN receiver assembled it (the same frames, timer flushes and ring
// drops), each GPS epoch as the serial reader assembled it (the same bytes, read times and
// idle completions), and each epoch placed after exactly as many IMU samples as it went in
// after live. Fed to core::HeadingPipeline in this order, the estimates are those of the
// live run, bit for bit (daemon/README.md, "Black box", states the contract).
//
// Streams the folder: memory does not grow with the recording's length.
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "headingd/can/dbc.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/can/imu_frame_codec.hpp"
#include "headingd/core/gps_observation.hpp"
#include "headingd/core/imu_sample.hpp"
#include "headingd/nmea/serial_epoch_assembler.hpp"
#include "headingd/recording/recording_setup.hpp"
#include "headingd/recording/stream_lines.hpp"

namespace headingd::recording {

struct RecordingStep {
  enum class Kind {
    kImu,                  // `imu` went into the estimator (before calibration)
    kGps,                  // `gps` went into the estimator
    kCalibrationReloaded,  // the live run re-read its calibration here (SIGHUP)
  };
  Kind kind = Kind::kImu;
  core::ImuSample imu;
  core::GpsObservation gps;
};

struct RecordingCounters {
  std::uint64_t can_frames = 0;
  std::uint64_t can_flushes = 0;            // epochs the live receiver's timer closed
  std::uint64_t imu_samples = 0;            // handed out
  std::uint64_t imu_dropped_live = 0;       // assembled live but never reached the estimator
  std::uint64_t gps_epochs = 0;             // handed out
  std::uint64_t gps_epochs_not_placed = 0;  // assembled live but never reached the estimator
  std::uint64_t calibration_reloads = 0;
  std::uint64_t lost_lines = 0;  // the recorder's "# lost N lines" notes, summed
  std::uint64_t bad_lines = 0;   // lines that do not read (skipped; e.g. cut by a power loss)
  std::string first_bad_line;    // "file:line: what was expected"
  bool start_missing = false;    // the oldest segments were deleted by the recorder's cap
};

class RecordingReader {
 public:
  explicit RecordingReader(const RecordingSetup& setup);
  ~RecordingReader();

  // The next call, or false at the end. Throws std::runtime_error (naming file:line) when
  // the streams contradict each other.
  bool next(RecordingStep& step);
  // The sensor time of the first step (IMU sample or GPS epoch), nullopt for an empty recording.
  std::optional<std::int64_t> firstTimeNs();

  const RecordingCounters& counters() const { return counters_; }
  // True when nothing is known to differ from the live run: no lines lost or unreadable,
  // the start present, no calibration reload.
  bool complete() const;

 private:
  bool readStep(RecordingStep& step);
  bool fillImu();
  bool fillGps();
  void loadPlacement();
  void onCanLine(std::string_view line);
  void onGpsLine(std::string_view line);
  void badLine(const StreamLines& stream, const std::string& what);

  const RecordingSetup& setup_;
  StreamLines can_lines_, gps_lines_, estimator_lines_;
  std::optional<can::DbcDatabase> dbc_;
  std::unique_ptr<can::ImuFrameCodec> codec_;
  std::unique_ptr<can::EpochAssembler> can_assembler_;
  std::int64_t flush_age_ns_ = 0;
  std::unique_ptr<nmea::EpochAssembler> gps_assembler_;
  std::deque<core::ImuSample> imu_queue_;
  std::deque<core::GpsObservation> gps_queue_;
  bool placement_loaded_ = false;
  bool placements_done_ = false;
  std::int64_t placement_t_ns_ = 0;
  bool placement_is_reload_ = false;
  std::uint64_t placement_after_ = 0;
  std::uint64_t imu_handed_out_ = 0;
  std::optional<RecordingStep> peeked_;
  std::string parse_error_;
  RecordingCounters counters_;
};

}  // namespace headingd::recording
