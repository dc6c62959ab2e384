#pragma once
// The daemon put together: the configuration → the World Magnetic Model, one ring per source
// and sample kind, the sources, the LCM publisher, the estimator thread. The main thread
// only waits for signals (main.cpp).
#include <memory>
#include <thread>
#include <vector>

#include "headingd/core/wmm.hpp"
#include "headingd/daemon/config.hpp"
#include "headingd/daemon/doorbell.hpp"
#include "headingd/daemon/estimator_loop.hpp"
#include "headingd/daemon/lcm_publisher.hpp"
#include "headingd/daemon/nmea_out_server.hpp"
#include "headingd/daemon/playback_clock.hpp"
#include "headingd/daemon/realtime.hpp"
#include "headingd/daemon/recorder.hpp"
#include "headingd/daemon/recording_files.hpp"
#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/sample_ring.hpp"
#include "headingd/daemon/source.hpp"
#include "headingd/daemon/source_registry.hpp"
#include "headingd/daemon/systemd_notify.hpp"

namespace headingd::daemon {

class Daemon {
 public:
  // Reads and checks every file the configuration names (calibration, WMM, DBC, logs,
  // recordings) and builds the sources, but starts nothing and opens no socket. This is the
  // whole validation of start-up: --check-config runs it and stops, start-up runs it and then
  // start(), so the two cannot disagree. Throws on any problem (main: exit status 2).
  explicit Daemon(DaemonConfig config);
  ~Daemon();

  // Opens LCM, starts the estimator thread and the sources.
  void start();
  // Stops the sources and the estimator thread (within one estimator period plus the
  // sources' own stop time). Idempotent.
  void stop();
  // True once the estimator loop ended on its own (a source asked to exit).
  bool finished() const { return loop_ != nullptr && loop_->finished(); }
  void requestCalibrationReload();

  const DaemonConfig& config() const { return config_; }
  std::size_t sourceCount() const { return sources_.size(); }
  LoopSummary summary() const;

 private:
  // [place]: its date chosen (the system's when the table gives none), what the WMM says
  // there logged.
  void usePlace();
  void makeRecorder();
  void startRecorder();

  DaemonConfig config_;
  core::CalibratedImuStream calibration_;  // handed to the loop by start()
  std::unique_ptr<core::WorldMagneticModel> wmm_;
  // The black box (null: off). Made before the sources (they hold its streams) and stopped
  // after them.
  std::unique_ptr<Recorder> recorder_;
  std::vector<std::unique_ptr<recording::LineSink>> recorder_sinks_;  // can, gps, estimator
  RecorderSinks source_sinks_;
  RecordingStart recording_start_;
  std::vector<std::unique_ptr<SampleRing<ImuRingEntry>>> imu_rings_;
  std::vector<std::unique_ptr<SampleRing<GpsRingEntry>>> gps_rings_;
  PlaybackClock playback_clock_;  // shared by the log sources; before them, so it outlives them
  std::vector<std::unique_ptr<Source>> sources_;
  SystemdNotifier notifier_;
  std::unique_ptr<RealtimeSettings> realtime_;
  Doorbell doorbell_;  // [daemon] publish = "imu": the IMU rings wake the estimator  // [realtime], for the process and
                       // each thread
  std::unique_ptr<LcmPublisher> publisher_;
  std::unique_ptr<NmeaOutServer> nmea_out_;  // [nmea_out] (null: off); stopped after the loop
  std::unique_ptr<EstimatorLoop> loop_;
  std::thread loop_thread_;
  bool sources_started_ = false;
};

}  // namespace headingd::daemon
