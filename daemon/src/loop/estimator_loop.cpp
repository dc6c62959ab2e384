#include "headingd/daemon/loop/estimator_loop.hpp"

#include <pthread.h>
#include <spdlog/spdlog.h>
#include <time.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "headingd/daemon/system/logging.hpp"
#include "headingd/daemon/system/realtime.hpp"
#include "headingd/live/clocks.hpp"

namespace headingd::daemon {

EstimatorLoop::EstimatorLoop(const DaemonConfig& config, const core::WorldMagneticModel* wmm,
                             std::vector<SampleRing<ImuRingEntry>*> imu_rings,
                             std::vector<SampleRing<GpsRingEntry>*> gps_rings, std::vector<Source*> sources,
                             LcmPublisher& publisher, SystemdNotifier& notifier, RealtimeSettings& realtime,
                             core::CalibratedImuStream calibration)
    : config_(config),
      pipeline_(config.estimator, wmm),
      calibration_(config.calibration_path, std::move(calibration)),
      rings_(std::move(imu_rings), std::move(gps_rings),
             RepeatLimiter(config.log.repeat_burst, config.log.repeat_interval_s)),
      sources_(std::move(sources)),
      publisher_(publisher),
      lcm_(config.lcm, publisher),
      notifier_(notifier),
      realtime_(realtime),
      period_ns_(static_cast<std::int64_t>(std::llround(1e9 / config.rate_hz))),
      imu_timeout_ns_(static_cast<std::int64_t>(config.imu_timeout_s * 1e9)),
      status_period_ns_(static_cast<std::int64_t>(config.status_period_s * 1e9)),
      gps_feed_(rings_.gpsCapacity()),
      rejected_log_(config.log.repeat_burst, config.log.repeat_interval_s),
      gps_rejected_log_(config.log.repeat_burst, config.log.repeat_interval_s),
      miss_log_(config.log.repeat_burst, config.log.repeat_interval_s) {
  imu_batch_.reserve(rings_.imuCapacity());
  if (config.place && config.place->decimal_year) {
    pipeline_.setPlace(config.place->position, *config.place->decimal_year);
  }
  if (config.gps_date_seed) pipeline_.seedGpsDate(*config.gps_date_seed);
  for (const Source* s : sources_) source_names_.push_back(s->name());
  source_reports_.resize(sources_.size());
  status_msg_.sources.resize(sources_.size());
  status_msg_.num_sources = static_cast<std::int32_t>(sources_.size());
  status_msg_.rings.resize(rings_.count());
  status_msg_.num_rings = static_cast<std::int32_t>(status_msg_.rings.size());
}

void EstimatorLoop::run() {
  pthread_setname_np(pthread_self(), "estimator");
  realtime_.applyToEstimatorThread();
  start_ns_ = live::monotonicNs();
  last_status_ns_ = start_ns_;
  std::int64_t deadline = start_ns_ + period_ns_;
  publisher_.expectFlushAt(deadline);
  bool ready_sent = false;
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    if (doorbell_ != nullptr) publishArrivalsUntil(deadline);
    const timespec ts = live::toTimespec(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
    const std::int64_t wake = live::monotonicNs();
    const bool exit_after_this_tick = sourcesWantExit();  // seen before draining: their data is all in
    tick(wake, exit_after_this_tick);
    const std::int64_t done = live::monotonicNs();
    recordTickTiming(wake - deadline, done - wake);
    deadline = nextDeadline(deadline, wake, done);
    publisher_.expectFlushAt(deadline);  // the LCM sender looks then
    if (!ready_sent) {
      notifier_.ready();  // the loop runs and publishes: what Type=notify waits for
      ready_sent = true;
    }
    notifier_.watchdogPing(done);
    if (exit_after_this_tick) {
      spdlog::info("a source finished and asked to stop the daemon (at_end = \"exit\")");
      break;
    }
  }
  finished_.store(true);
}

void EstimatorLoop::publishArrivalsUntil(std::int64_t deadline) {
  // The tick still runs at its deadline (STATUS, watchdog, stale data, GPS epochs without IMU
  // data) and publishes as always; between ticks each arrival is estimated and published
  // at once, so a heading is as old as the driver's and this work, not the tick's phase.
  const timespec ts = live::toTimespec(deadline);
  std::uint32_t handled = doorbell_->count();
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    const std::uint32_t seen = doorbell_->count();
    if (live::monotonicNs() >= deadline) return;
    if (seen == handled) {
      doorbell_->waitWhile(seen, ts);
      continue;
    }
    handled = seen;
    const std::int64_t utime_us = live::realtimeNs() / 1000;
    drainRings();
    feedPipeline(live::monotonicNs(), false, utime_us);
    if (consumed_this_tick_) publishEstimate(live::monotonicNs(), utime_us);
    publisher_.flush();
  }
}

void EstimatorLoop::recordTickTiming(std::int64_t jitter_ns, std::int64_t processing_ns) {
  ++ticks_;
  for (TickTiming* t : {&timing_total_, &timing_window_}) {
    t->jitter.record(jitter_ns);
    t->processing.record(processing_ns);
  }
  // Measured by the LCM sender thread as each estimate went out (lcm_publisher.hpp).
  publisher_.drainSampleAges([this](std::int64_t age_ns) {
    timing_total_.sample_age.record(age_ns);
    timing_window_.sample_age.record(age_ns);
  });
}

std::int64_t EstimatorLoop::nextDeadline(std::int64_t deadline, std::int64_t wake_ns, std::int64_t done_ns) {
  deadline += period_ns_;
  if (done_ns <= deadline) return deadline;
  // Missed one or more deadlines: skip them rather than run a burst of late ticks.
  const std::int64_t missed = (done_ns - deadline) / period_ns_ + 1;
  deadline_misses_ += static_cast<std::uint64_t>(missed);
  std::uint64_t suppressed = 0;
  if (miss_log_.allow(done_ns, &suppressed)) {
    spdlog::warn("estimator tick took {:.3f} ms, {} deadline(s) missed ({} such messages suppressed)",
                 (done_ns - wake_ns) * 1e-6, missed, suppressed);
  }
  return deadline + missed * period_ns_;
}

bool EstimatorLoop::sourcesWantExit() const {
  bool wanted = false;
  for (const Source* s : sources_) {
    if (s->playing()) return false;  // all file sources first play to their end
    wanted = wanted || s->wantsExit();
  }
  return wanted;
}

void EstimatorLoop::tick(std::int64_t wake_ns, bool last_tick) {
  if (reload_requested_.exchange(false) && calibration_.reload()) {
    for (EstimateSink* sink : sinks_) sink->calibrationReloaded(imu_.last_used_t_ns, imu_processed_);
  }
  const std::int64_t utime_us = live::realtimeNs() / 1000;
  drainRings();
  feedPipeline(wake_ns, last_tick, utime_us);
  rings_.logDrops(wake_ns);
  const std::int64_t now = live::monotonicNs();
  publishEstimate(now, utime_us);
  publisher_.flush();  // the estimate goes out while STATUS is put together
  // The last tick too, so that STATUS shows the sources finished and their final counters.
  if (now - last_status_ns_ >= status_period_ns_ || last_tick) {
    publishStatus(now, utime_us);
    publisher_.flush();
  }
}

void EstimatorLoop::drainRings() {
  const auto processForcedOut = [this](const GpsRingEntry& oldest) { processGps(oldest, live::realtimeNs() / 1000); };
  rings_.drain(imu_batch_, [&](const GpsRingEntry& e) { gps_feed_.add(e, processForcedOut); });
  gps_feed_.sortHeld();
}

void EstimatorLoop::feedPipeline(std::int64_t wake_ns, bool last_tick, std::int64_t utime_us) {
  consumed_this_tick_ = false;
  const auto processGpsNow = [this, utime_us](const GpsRingEntry& e) { processGps(e, utime_us); };
  gps_feed_.releasePlaced(imu_processed_, processGpsNow);
  for (const ImuRingEntry& e : imu_batch_) {
    processImu(e, utime_us);
    gps_feed_.afterImu(e.sample.t_ns, imu_processed_, processGpsNow);
  }
  // Without IMU data an epoch would wait for ever: then it goes in as it is (also on the
  // last tick, when a file's last epoch is later than its last IMU sample).
  const bool imu_stale = !imu_.any_used || wake_ns - imu_.last_used_arrival_ns > imu_timeout_ns_;
  if (imu_stale || last_tick) gps_feed_.releaseTimed(processGpsNow);
  if (last_tick) gps_feed_.releaseAllPlaced(processGpsNow);
}

void EstimatorLoop::processImu(const ImuRingEntry& raw, std::int64_t utime_us) {
  // The calibrated sample is what the estimator sees and what IMU publishes.
  ImuRingEntry e = raw;
  e.sample = calibration_.apply(raw.sample);
  const core::SampleVerdict verdict = pipeline_.process(e.sample);
  ++imu_processed_;
  imu_.last_any_arrival_ns = std::max(imu_.last_any_arrival_ns, e.arrival_mono_ns);
  if (!units_told_ && pipeline_.sensorUnits().decided()) {
    units_told_ = true;
    const std::string units = pipeline_.sensorUnits().describe();
    if (!units.empty()) spdlog::warn("IMU samples not in SI units? {}", units);
  }
  if (core::sampleUsed(verdict)) {
    imu_.any_used = true;
    consumed_this_tick_ = true;
    imu_.last_used_arrival_ns = e.arrival_mono_ns;
    imu_.last_used_t_ns = e.sample.t_ns;
  } else {
    ++imu_rejected_;
    std::uint64_t suppressed = 0;
    if (rejected_log_.allow(e.arrival_mono_ns, &suppressed)) {
      spdlog::warn("IMU sample at t={:.6f} s from {} rejected: {} ({} such messages suppressed)", e.sample.t_ns * 1e-9,
                   source_names_[e.source_index], core::sampleVerdictName(verdict), suppressed);
    }
  }
  lcm_.imuSample(e, verdict, source_names_[e.source_index], utime_us);
  for (EstimateSink* sink : sinks_) sink->imuSample(e, verdict, source_names_[e.source_index], utime_us);
}

void EstimatorLoop::processGps(const GpsRingEntry& e, std::int64_t utime_us) {
  std::uint64_t suppressed = 0;
  const char* problem = pipeline_.processGps(e.observation);
  if (problem != nullptr && gps_rejected_log_.allow(e.arrival_mono_ns, &suppressed)) {
    spdlog::warn("GPS epoch from {}: value left out: {} ({} values left out so far, {} lines not logged)",
                 source_names_[e.source_index], problem, pipeline_.gpsValuesIgnored(), suppressed);
  }
  ++gps_epochs_processed_;
  lcm_.gpsEpoch(e, imu_processed_, source_names_[e.source_index], utime_us);
  for (EstimateSink* sink : sinks_) sink->gpsEpoch(e, imu_processed_, source_names_[e.source_index], utime_us);
}

Validity EstimatorLoop::validity(std::int64_t now_ns) const {
  if (!pipeline_.output().attitude.valid) return Validity::kNone;
  return now_ns - imu_.last_used_arrival_ns <= imu_timeout_ns_ ? Validity::kFresh : Validity::kStale;
}

void EstimatorLoop::publishEstimate(std::int64_t now_ns, std::int64_t utime_us) {
  PublishTimes t;
  t.utime_us = utime_us;
  t.sample_utime_us = imu_.last_used_t_ns / 1000;
  t.sample_age_us = imu_.any_used ? (now_ns - imu_.last_used_arrival_ns) / 1000 : 0;
  const PublishedEstimate estimate{pipeline_, validity(now_ns), t,
                                   consumed_this_tick_ ? std::optional(imu_.last_used_arrival_ns) : std::nullopt};
  lcm_.estimate(estimate);
  for (EstimateSink* sink : sinks_) sink->estimate(estimate);
}

void EstimatorLoop::publishStatus(std::int64_t now_ns, std::int64_t utime_us) {
  const double window_s = static_cast<double>(now_ns - last_status_ns_) * 1e-9;
  last_status_ns_ = now_ns;
  status_t& m = status_msg_;
  m.utime = utime_us;
  m.state = healthState(imu_, pipeline_.output().attitude.valid, start_ns_, now_ns, config_, &m.reason);
  m.uptime_us = (now_ns - start_ns_) / 1000;
  fillSourceStatus(m, sources_, source_reports_);
  rings_.fillStatus(m);
  m.rate_hz = config_.rate_hz;
  m.ticks = static_cast<std::int64_t>(ticks_);
  m.deadline_misses = static_cast<std::int64_t>(deadline_misses_);
  fillTickTiming(m, timing_window_);
  timing_window_.clear();
  fillRates(m, lcm_.published(), published_at_last_status_, window_s);
  published_at_last_status_ = lcm_.published();
  m.publish_errors = static_cast<std::int64_t>(publisher_.errors());
  fillCounters(m, pipeline_.estimator().counters(), loopCounters());
  fillRealtimeStatus(m, realtime_.report());
  for (const EstimateSink* sink : sinks_) sink->appendStatusCounters(m);
  lcm_.publishStatus(m);

  // One line for people: systemctl status (STATUS=) and, if asked, stdout.
  formatStatusLine(m, pipeline_.output(), validity(now_ns), status_text_);
  notifier_.status(status_text_);
  if (config_.console_status) {
    std::fputs(status_text_.c_str(), stdout);
    std::fputc('\n', stdout);
    std::fflush(stdout);
  }
}

LoopCounters EstimatorLoop::loopCounters() const {
  LoopCounters c;
  c.imu_rejected = imu_rejected_;
  c.mag_calibration_set_aside = calibration_.magSetAside();
  c.mag_calibration_taken_back = calibration_.magTakenBack();
  c.gps_epochs = gps_epochs_processed_;
  c.gps_epochs_used_for_declination = pipeline_.gpsEpochsUsedForDeclination();
  c.gps_epochs_forced_out = gps_feed_.forcedOut();
  c.gps_values_ignored = pipeline_.gpsValuesIgnored();
  c.gps_dates_not_believed = pipeline_.gpsDatesNotBelieved();
  c.units_suspect_accel = pipeline_.sensorUnits().accelSuspect() ? 1 : 0;
  c.units_suspect_gyro = pipeline_.sensorUnits().gyroSuspect() ? 1 : 0;
  c.units_suspect_mag = pipeline_.sensorUnits().magSuspect() ? 1 : 0;
  c.log_write_errors = logWriteErrors();
  return c;
}

LoopSummary EstimatorLoop::summary() const {
  LoopSummary s;
  s.ticks = ticks_;
  s.deadline_misses = deadline_misses_;
  s.timing = tickTimingFigures(timing_total_);
  s.heading_published = lcm_.published().heading;
  s.imu_published = lcm_.published().imu;
  s.gps_published = lcm_.published().gps;
  s.status_published = lcm_.published().status;
  s.publish_errors = publisher_.errors();
  return s;
}

}  // namespace headingd::daemon
