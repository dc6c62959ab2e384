#pragma once
// The fixed-rate estimator thread. Each tick, at an absolute CLOCK_MONOTONIC deadline
// (clock_nanosleep TIMER_ABSTIME, so late ticks do not push later ones back):
//   drain every ring → order the samples by time → HeadingPipeline (each IMU sample, then the
//   GPS epochs at or before it: core::ImuThenGpsOrder, as headingd-replay does) → publish
//   IMU and GPS as used, then HEADING and ATTITUDE once → STATUS every status period
//   (status_builder.hpp says what is in it). Publishing encodes and queues; the LCM sender
//   thread sends (lcm_publisher.hpp), so a slow network stack does not hold the tick.
// It measures its wake-up jitter, processing time, missed deadlines and the age of the
// newest sample at publish, in fixed histograms (no allocation after start-up).
//
// Freshness: HEADING and ATTITUDE are published every tick; when no IMU sample has been
// used for [daemon] imu_timeout_s their `validity` is STALE (and STATUS says "degraded"),
// VALIDITY_NONE before the first estimate.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "headingd/attitude_t.hpp"
#include "headingd/core/calibrated_imu_stream.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/imu_then_gps_order.hpp"
#include "headingd/daemon/config.hpp"
#include "headingd/daemon/latency_histogram.hpp"
#include "headingd/daemon/lcm_messages.hpp"
#include "headingd/daemon/lcm_publisher.hpp"
#include "headingd/daemon/nmea_out_sentences.hpp"
#include "headingd/daemon/nmea_out_server.hpp"
#include "headingd/daemon/realtime.hpp"
#include "headingd/daemon/recorder.hpp"
#include "headingd/daemon/repeat_limiter.hpp"
#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/sample_ring.hpp"
#include "headingd/daemon/source.hpp"
#include "headingd/daemon/status_builder.hpp"
#include "headingd/daemon/systemd_notify.hpp"
#include "headingd/gps_t.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/imu_t.hpp"
#include "headingd/recording/stream_recorders.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon {

// [daemon] calibration: none when `path` is empty; throws naming the file when it cannot be
// read or parsed. Run at start-up (so --check-config sees it) and on SIGHUP.
core::CalibratedImuStream loadCalibration(const std::string& path);

// Whole-run figures, for the summary printed at exit and for measure.sh.
struct LoopSummary {
  std::uint64_t ticks = 0;
  std::uint64_t deadline_misses = 0;
  TickTimingFigures timing;
  std::uint64_t heading_published = 0, imu_published = 0, gps_published = 0, status_published = 0;
  std::uint64_t publish_errors = 0;
};

class EstimatorLoop {
 public:
  // Everything is borrowed and must outlive the loop. `wmm` may be null. `calibration`: read
  // from [daemon] calibration by loadCalibration() before (at start-up, with the other checks).
  EstimatorLoop(const DaemonConfig& config, const core::WorldMagneticModel* wmm,
                std::vector<SampleRing<ImuRingEntry>*> imu_rings, std::vector<SampleRing<GpsRingEntry>*> gps_rings,
                std::vector<Source*> sources, LcmPublisher& publisher, SystemdNotifier& notifier,
                RealtimeSettings& realtime, core::CalibratedImuStream calibration);

  // Runs ticks on the calling thread until stop() or until a source asked for it (at_end =
  // "exit"), no file source is playing any more and their data is processed.
  void run();
  void stop() { stop_requested_.store(true); }
  bool finished() const { return finished_.load(); }
  // SIGHUP: reload the calibration at the next tick (see reloadCalibration).
  void requestCalibrationReload() { reload_requested_.store(true); }

  LoopSummary summary() const;

  // The black box (null: not recording): its estimator stream gets where each GPS epoch went
  // in, and STATUS its counters. Set before run().
  void setRecorder(recording::LineSink* sink, const Recorder* recorder);
  // [daemon] publish = "imu": the doorbell the rings ring on each push. Set before run().
  void setDoorbell(Doorbell* doorbell) { doorbell_ = doorbell; }

  // [nmea_out] (null: off): every round(rate_hz / [nmea_out] rate_hz) ticks the estimate just
  // published as HEADING goes out as NMEA sentences; THS says S when `from_files`. Set before run().
  void setNmeaOut(NmeaOutServer* server, bool from_files);

 private:
  // The steps of one tick, in order.
  void tick(std::int64_t wake_ns, bool last_tick);
  // [daemon] publish = "imu": until `deadline`, estimates and publishes what arrives as it
  // arrives (woken by the rings' doorbell).
  void publishArrivalsUntil(std::int64_t deadline);
  void drainRings();
  void putInTimeOrder();
  void feedPipeline(std::int64_t wake_ns, bool last_tick, std::int64_t utime_us);
  void logRingDrops(std::int64_t wake_ns);
  void processImu(const ImuRingEntry& e, std::int64_t utime_us);
  void processGps(const GpsRingEntry& e, std::int64_t utime_us);
  void releasePlacedEpochs(std::int64_t utime_us);
  void publishEstimate(std::int64_t now_ns, std::int64_t utime_us);
  void publishStatus(std::int64_t now_ns, std::int64_t utime_us);
  void sendNmea(Validity v);
  LoopCounters loopCounters() const;
  void reloadCalibration();
  bool sourcesWantExit() const;
  Validity validity(std::int64_t now_ns) const;
  // Scheduling: timing of the tick just run, and the deadline of the next one.
  void recordTickTiming(std::int64_t jitter_ns, std::int64_t processing_ns);
  std::int64_t nextDeadline(std::int64_t deadline, std::int64_t wake_ns, std::int64_t done_ns);

  const DaemonConfig& config_;
  core::HeadingPipeline pipeline_;
  // [daemon] calibration, applied to every sample; its magnetometer part is set aside while
  // it no longer fits (mag_calibration_fit.hpp).
  core::CalibratedImuStream correction_;
  bool mag_calibration_in_use_ = true;  // last state logged
  std::vector<SampleRing<ImuRingEntry>*> imu_rings_;
  std::vector<SampleRing<GpsRingEntry>*> gps_rings_;
  std::vector<Source*> sources_;
  std::vector<std::string> source_names_;  // by source_index, for the IMU/GPS messages
  LcmPublisher& publisher_;
  SystemdNotifier& notifier_;
  RealtimeSettings& realtime_;  // applied by run() to its thread; STATUS reports what it got

  std::int64_t period_ns_;
  std::int64_t imu_timeout_ns_;
  std::int64_t status_period_ns_;
  std::atomic<bool> stop_requested_{false};
  Doorbell* doorbell_ = nullptr;  // null: publish once a tick only
  std::atomic<bool> finished_{false};
  std::atomic<bool> reload_requested_{false};

  // Per-tick buffers, reserved once.
  std::vector<ImuRingEntry> imu_batch_;
  core::ImuThenGpsOrder<GpsRingEntry> gps_order_;  // GPS epochs held until an IMU sample at or after them
  // Epochs a recording places by sample count (GpsRingEntry::after_imu_samples), held until
  // that many IMU samples went in; [placed_next_, end) are held.
  std::vector<GpsRingEntry> placed_gps_;
  std::size_t placed_next_ = 0;
  std::uint64_t imu_processed_ = 0;  // every IMU sample given to the pipeline, used or not
  std::unique_ptr<recording::EstimatorStreamRecorder> recorder_;
  const Recorder* recorder_status_ = nullptr;
  NmeaOutServer* nmea_out_ = nullptr;
  bool nmea_from_files_ = false;
  std::uint64_t nmea_every_ticks_ = 1;
  std::uint64_t ticks_to_nmea_ = 0;
  NmeaOutBatch nmea_batch_;

  // Freshness.
  std::int64_t start_ns_ = 0;
  ImuFreshness imu_;
  bool consumed_this_tick_ = false;

  // Timing.
  std::uint64_t ticks_ = 0;
  std::uint64_t deadline_misses_ = 0;
  TickTiming timing_total_, timing_window_;  // the whole run; the status period
  std::int64_t last_status_ns_ = 0;
  PublishedCounts published_, published_at_last_status_;
  std::uint64_t gps_epochs_processed_ = 0, gps_epochs_forced_ = 0;
  std::uint64_t imu_rejected_ = 0;
  std::vector<std::uint64_t> ring_drops_seen_;

  // Logging limits for per-sample problems.
  RepeatLimiter rejected_log_;
  RepeatLimiter gps_rejected_log_;  // GPS values the pipeline left out
  RepeatLimiter drop_log_;
  RepeatLimiter miss_log_;

  // Reused messages.
  headingd::heading_t heading_msg_{};
  headingd::attitude_t attitude_msg_{};
  headingd::imu_t imu_msg_{};
  headingd::gps_t gps_msg_{};
  headingd::status_t status_msg_{};
  std::vector<SourceReport> source_reports_;
  std::string status_text_;
};

}  // namespace headingd::daemon
