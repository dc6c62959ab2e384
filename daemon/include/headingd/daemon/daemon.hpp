#pragma once
// The daemon put together: the configuration → the World Magnetic Model, one ring per source
// and sample kind, the sources, the LCM publisher, the estimator thread. The main thread
// only waits for signals (main.cpp).
#include <memory>
#include <thread>
#include <vector>

#include "headingd/core/wmm.hpp"
#include "headingd/daemon/config/config.hpp"
#include "headingd/daemon/loop/doorbell.hpp"
#include "headingd/daemon/loop/estimator_loop.hpp"
#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/outputs/lcm_publisher.hpp"
#include "headingd/daemon/outputs/nmea_out_server.hpp"
#include "headingd/daemon/outputs/nmea_output.hpp"
#include "headingd/daemon/recorder/recorder.hpp"
#include "headingd/daemon/recorder/recorder_output.hpp"
#include "headingd/daemon/recorder/recording_files.hpp"
#include "headingd/daemon/sources/playback_clock.hpp"
#include "headingd/daemon/sources/source.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/daemon/system/realtime.hpp"
#include "headingd/daemon/system/systemd_notify.hpp"

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
  void seedGpsDate();  // [daemon] gps_date_seed from the system clock when it is absent
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
  SourceRings rings_;
  PlaybackClock playback_clock_;  // shared by the log sources; before them, so it outlives them
  std::vector<std::unique_ptr<Source>> sources_;
  SystemdNotifier notifier_;
  std::unique_ptr<RealtimeSettings> realtime_;  // [realtime], for the process and each thread
  Doorbell doorbell_;                           // [daemon] publish = "imu": the IMU rings wake the estimator
  std::unique_ptr<LcmPublisher> publisher_;
  std::unique_ptr<NmeaOutServer> nmea_out_;  // [nmea_out] (null: off); stopped after the loop
  // The loop's outputs besides LCM (null: off); before the loop, so that they outlive it.
  std::unique_ptr<RecorderOutput> recorder_output_;
  std::unique_ptr<NmeaOutput> nmea_output_;
  std::unique_ptr<EstimatorLoop> loop_;
  std::thread loop_thread_;
  bool sources_started_ = false;
};

}  // namespace headingd::daemon
