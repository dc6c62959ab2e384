#pragma once
// The black box as an estimate sink: its estimator stream gets where each GPS epoch and each
// calibration reload went in among the IMU samples (what a replay needs to put them back in the
// same place, recording_format.hpp), and STATUS the recorder's counters.
#include "headingd/daemon/outputs/estimate_sink.hpp"
#include "headingd/daemon/recorder/recorder.hpp"
#include "headingd/recording/stream_recorders.hpp"

namespace headingd::daemon {

// The recorder's counters ("recorder_lines_written", ...) after those already in `m`.
void appendRecorderCounters(status_t& m, const RecorderCounters& recorder);

class RecorderOutput final : public EstimateSink {
 public:
  // Both borrowed: `estimator_stream` is the recorder's estimator stream.
  RecorderOutput(recording::LineSink& estimator_stream, const Recorder& recorder)
      : stream_(estimator_stream), recorder_(recorder) {}

  void gpsEpoch(const GpsRingEntry& entry, std::uint64_t imu_samples_before, const std::string& /*source_name*/,
                std::int64_t /*utime_us*/) override {
    stream_.gpsPlaced(entry.observation.t_ns, imu_samples_before);
  }
  void calibrationReloaded(std::int64_t t_ns, std::uint64_t imu_samples_before) override {
    stream_.calibrationReloaded(t_ns, imu_samples_before);
  }
  void appendStatusCounters(status_t& m) const override;

 private:
  recording::EstimatorStreamRecorder stream_;
  const Recorder& recorder_;
};

}  // namespace headingd::daemon
