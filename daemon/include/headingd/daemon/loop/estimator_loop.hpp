#pragma once
// The fixed-rate estimator thread. Each tick, at an absolute CLOCK_MONOTONIC deadline
// (clock_nanosleep TIMER_ABSTIME, so late ticks do not push later ones back):
//   drain every ring → order the samples by time → HeadingPipeline (each IMU sample, then the
//   GPS epochs at or before it: core::ImuThenGpsOrder, as headingd-replay does) → publish
//   IMU and GPS as used, then HEADING and ATTITUDE once → STATUS every status period
//   (status_builder.hpp says what is in it). What goes out goes to the estimate sinks
//   (estimate_sink.hpp): LCM always, NMEA out and the black box's estimator stream where they
//   are on. Publishing encodes and queues; the LCM sender thread sends (lcm_publisher.hpp),
//   so a slow network stack does not hold the tick.
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

#include "headingd/core/calibrated_imu_stream.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/daemon/config/config.hpp"
#include "headingd/daemon/loop/calibration_in_use.hpp"
#include "headingd/daemon/loop/gps_feed.hpp"
#include "headingd/daemon/loop/input_rings.hpp"
#include "headingd/daemon/loop/latency_histogram.hpp"
#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/loop/status_builder.hpp"
#include "headingd/daemon/outputs/estimate_sink.hpp"
#include "headingd/daemon/outputs/lcm_output.hpp"
#include "headingd/daemon/outputs/lcm_publisher.hpp"
#include "headingd/daemon/sources/source.hpp"
#include "headingd/daemon/system/realtime.hpp"
#include "headingd/daemon/system/repeat_limiter.hpp"
#include "headingd/daemon/system/systemd_notify.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon {

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
  // SIGHUP: reload the calibration at the start of the next tick (calibration_in_use.hpp).
  void requestCalibrationReload() { reload_requested_.store(true); }

  LoopSummary summary() const;

  // An output besides LCM (borrowed; NMEA out, the black box), called after LCM and after the
  // sinks added before it; STATUS lists its counters in that order too. Add before run().
  void addSink(EstimateSink* sink) { sinks_.push_back(sink); }
  // [daemon] publish = "imu": the doorbell the rings ring on each push. Set before run().
  void setDoorbell(Doorbell* doorbell) { doorbell_ = doorbell; }

 private:
  // The steps of one tick, in order.
  void tick(std::int64_t wake_ns, bool last_tick);
  // [daemon] publish = "imu": until `deadline`, estimates and publishes what arrives as it
  // arrives (woken by the rings' doorbell).
  void publishArrivalsUntil(std::int64_t deadline);
  void drainRings();
  void feedPipeline(std::int64_t wake_ns, bool last_tick, std::int64_t utime_us);
  void processImu(const ImuRingEntry& e, std::int64_t utime_us);
  void processGps(const GpsRingEntry& e, std::int64_t utime_us);
  void publishEstimate(std::int64_t now_ns, std::int64_t utime_us);
  void publishStatus(std::int64_t now_ns, std::int64_t utime_us);
  LoopCounters loopCounters() const;
  bool sourcesWantExit() const;
  Validity validity(std::int64_t now_ns) const;
  // Scheduling: timing of the tick just run, and the deadline of the next one.
  void recordTickTiming(std::int64_t jitter_ns, std::int64_t processing_ns);
  std::int64_t nextDeadline(std::int64_t deadline, std::int64_t wake_ns, std::int64_t done_ns);

  const DaemonConfig& config_;
  core::HeadingPipeline pipeline_;
  CalibrationInUse calibration_;  // [daemon] calibration, applied to every sample
  InputRings rings_;
  std::vector<Source*> sources_;
  std::vector<std::string> source_names_;  // by source_index, for the IMU/GPS messages
  LcmPublisher& publisher_;                // the schedule: when the sender flushes, the samples' ages, errors
  LcmOutput lcm_;
  std::vector<EstimateSink*> sinks_;  // after LCM, in the order added
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
  GpsFeed gps_feed_;                 // GPS epochs held until they are due
  std::uint64_t imu_processed_ = 0;  // every IMU sample given to the pipeline, used or not

  // Freshness.
  std::int64_t start_ns_ = 0;
  ImuFreshness imu_;
  bool consumed_this_tick_ = false;
  bool units_told_ = false;  // the sensor units check's verdict logged

  // Timing.
  std::uint64_t ticks_ = 0;
  std::uint64_t deadline_misses_ = 0;
  TickTiming timing_total_, timing_window_;  // the whole run; the status period
  std::int64_t last_status_ns_ = 0;
  PublishedCounts published_at_last_status_;
  std::uint64_t gps_epochs_processed_ = 0;
  std::uint64_t imu_rejected_ = 0;

  // Logging limits for per-sample problems.
  RepeatLimiter rejected_log_;
  RepeatLimiter gps_rejected_log_;  // GPS values the pipeline left out
  RepeatLimiter miss_log_;

  headingd::status_t status_msg_{};  // reused
  std::vector<SourceReport> source_reports_;
  std::string status_text_;
};

}  // namespace headingd::daemon
