#include "headingd/daemon/estimator_loop.hpp"

#include <pthread.h>
#include <spdlog/spdlog.h>
#include <time.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/daemon/clocks.hpp"
#include "headingd/daemon/logging.hpp"
#include "headingd/daemon/realtime.hpp"
#include "headingd/files/gzip_file.hpp"

namespace headingd::daemon {

core::CalibratedImuStream loadCalibration(const std::string& path) {
  if (path.empty()) return core::CalibratedImuStream{};
  return core::CalibratedImuStream(
      core::parseImuCalibration(files::readMaybeGzipFile(path, files::kConfigFileLimit), path));
}

namespace {

// One source's samples come in order; several sources are merged by sensor time, ties by
// arrival (std::sort: no temporary buffer, unlike stable_sort).
bool imuByTime(const ImuRingEntry& a, const ImuRingEntry& b) {
  return std::tie(a.sample.t_ns, a.arrival_mono_ns, a.source_index) <
         std::tie(b.sample.t_ns, b.arrival_mono_ns, b.source_index);
}
bool gpsByTime(const GpsRingEntry& a, const GpsRingEntry& b) {
  return std::tie(a.observation.t_ns, a.arrival_mono_ns, a.source_index) <
         std::tie(b.observation.t_ns, b.arrival_mono_ns, b.source_index);
}

}  // namespace

EstimatorLoop::EstimatorLoop(const DaemonConfig& config, const core::WorldMagneticModel* wmm,
                             std::vector<SampleRing<ImuRingEntry>*> imu_rings,
                             std::vector<SampleRing<GpsRingEntry>*> gps_rings, std::vector<Source*> sources,
                             LcmPublisher& publisher, SystemdNotifier& notifier, RealtimeSettings& realtime,
                             core::CalibratedImuStream calibration)
    : config_(config),
      pipeline_(config.estimator, wmm),
      correction_(std::move(calibration)),
      imu_rings_(std::move(imu_rings)),
      gps_rings_(std::move(gps_rings)),
      sources_(std::move(sources)),
      publisher_(publisher),
      notifier_(notifier),
      realtime_(realtime),
      period_ns_(static_cast<std::int64_t>(std::llround(1e9 / config.rate_hz))),
      imu_timeout_ns_(static_cast<std::int64_t>(config.imu_timeout_s * 1e9)),
      status_period_ns_(static_cast<std::int64_t>(config.status_period_s * 1e9)),
      rejected_log_(config.log.repeat_burst, config.log.repeat_interval_s),
      gps_rejected_log_(config.log.repeat_burst, config.log.repeat_interval_s),
      drop_log_(config.log.repeat_burst, config.log.repeat_interval_s),
      miss_log_(config.log.repeat_burst, config.log.repeat_interval_s) {
  std::size_t imu_capacity = 0, gps_capacity = 0;
  for (const auto* r : imu_rings_) imu_capacity += r->capacity();
  for (const auto* r : gps_rings_) gps_capacity += r->capacity();
  imu_batch_.reserve(imu_capacity);
  gps_order_.reserve(2 * gps_capacity + 1);
  placed_gps_.reserve(2 * gps_capacity + 1);
  if (config.place && config.place->decimal_year) {
    pipeline_.setPlace(config.place->position, *config.place->decimal_year);
  }
  for (const Source* s : sources_) source_names_.push_back(s->name());
  source_reports_.resize(sources_.size());
  ring_drops_seen_.assign(imu_rings_.size() + gps_rings_.size(), 0);
  status_msg_.sources.resize(sources_.size());
  status_msg_.num_sources = static_cast<std::int32_t>(sources_.size());
  status_msg_.rings.resize(imu_rings_.size() + gps_rings_.size());
  status_msg_.num_rings = static_cast<std::int32_t>(status_msg_.rings.size());
}

void EstimatorLoop::run() {
  pthread_setname_np(pthread_self(), "estimator");
  realtime_.applyToEstimatorThread();
  start_ns_ = monotonicNs();
  last_status_ns_ = start_ns_;
  std::int64_t deadline = start_ns_ + period_ns_;
  publisher_.expectFlushAt(deadline);
  bool ready_sent = false;
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    if (doorbell_ != nullptr) publishArrivalsUntil(deadline);
    const timespec ts = toTimespec(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
    const std::int64_t wake = monotonicNs();
    const bool exit_after_this_tick = sourcesWantExit();  // seen before draining: their data is all in
    tick(wake, exit_after_this_tick);
    const std::int64_t done = monotonicNs();
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
  const timespec ts = toTimespec(deadline);
  std::uint32_t handled = doorbell_->count();
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    const std::uint32_t seen = doorbell_->count();
    if (monotonicNs() >= deadline) return;
    if (seen == handled) {
      doorbell_->waitWhile(seen, ts);
      continue;
    }
    handled = seen;
    const std::int64_t utime_us = realtimeNs() / 1000;
    drainRings();
    putInTimeOrder();
    feedPipeline(monotonicNs(), false, utime_us);
    if (consumed_this_tick_) publishEstimate(monotonicNs(), utime_us);
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
  if (reload_requested_.exchange(false)) reloadCalibration();
  const std::int64_t utime_us = realtimeNs() / 1000;
  drainRings();
  putInTimeOrder();
  feedPipeline(wake_ns, last_tick, utime_us);
  logRingDrops(wake_ns);
  const std::int64_t now = monotonicNs();
  publishEstimate(now, utime_us);
  publisher_.flush();  // the estimate goes out while STATUS is put together
  // The last tick too, so that STATUS shows the sources finished and their final counters.
  if (now - last_status_ns_ >= status_period_ns_ || last_tick) {
    publishStatus(now, utime_us);
    publisher_.flush();
  }
}

void EstimatorLoop::drainRings() {
  imu_batch_.clear();
  for (auto* ring : imu_rings_) ring->drain([this](const ImuRingEntry& e) { imu_batch_.push_back(e); });
  for (auto* ring : gps_rings_) {
    ring->drain([this](const GpsRingEntry& e) {
      if (e.after_imu_samples >= 0) {
        placed_gps_.push_back(e);  // in the recording's order, which is the live order
        return;
      }
      if (gps_order_.held() == gps_order_.capacity()) {  // never expected: GPS is slow
        gps_order_.releaseOldest([this](const GpsRingEntry& oldest) { processGps(oldest, realtimeNs() / 1000); });
        ++gps_epochs_forced_;
      }
      gps_order_.pushGps(e);
    });
  }
}

void EstimatorLoop::putInTimeOrder() {
  // One source's samples stay in the order it pushed them (the sample gate judges a time that
  // goes back), so the order never depends on where a tick cut the stream: a recording of
  // one IMU replays in the same order whatever the ticks.
  if (imu_rings_.size() > 1 && !std::is_sorted(imu_batch_.begin(), imu_batch_.end(), imuByTime)) {
    std::sort(imu_batch_.begin(), imu_batch_.end(), imuByTime);
  }
  gps_order_.sortHeld(gpsByTime);
}

void EstimatorLoop::feedPipeline(std::int64_t wake_ns, bool last_tick, std::int64_t utime_us) {
  consumed_this_tick_ = false;
  const auto processGpsNow = [this, utime_us](const GpsRingEntry& e) { processGps(e, utime_us); };
  releasePlacedEpochs(utime_us);
  for (const ImuRingEntry& e : imu_batch_) {
    processImu(e, utime_us);
    gps_order_.afterImu(e.sample.t_ns, processGpsNow);
    releasePlacedEpochs(utime_us);
  }
  // Without IMU data an epoch would wait for ever: then it goes in as it is (also on the
  // last tick, when a file's last epoch is later than its last IMU sample).
  const bool imu_stale = !imu_.any_used || wake_ns - imu_.last_used_arrival_ns > imu_timeout_ns_;
  if (imu_stale || last_tick) gps_order_.releaseAll(processGpsNow);
  if (last_tick) {
    while (placed_next_ < placed_gps_.size()) processGps(placed_gps_[placed_next_++], utime_us);
  }
}

void EstimatorLoop::releasePlacedEpochs(std::int64_t utime_us) {
  while (placed_next_ < placed_gps_.size() &&
         static_cast<std::uint64_t>(placed_gps_[placed_next_].after_imu_samples) <= imu_processed_) {
    processGps(placed_gps_[placed_next_++], utime_us);
  }
  if (placed_next_ == placed_gps_.size()) {
    placed_gps_.clear();
    placed_next_ = 0;
  }
}

void EstimatorLoop::setRecorder(recording::LineSink* sink, const Recorder* recorder) {
  recorder_ = sink != nullptr ? std::make_unique<recording::EstimatorStreamRecorder>(*sink) : nullptr;
  recorder_status_ = recorder;
}

void EstimatorLoop::setNmeaOut(NmeaOutServer* server, bool from_files) {
  nmea_out_ = server;
  nmea_from_files_ = from_files;
  nmea_every_ticks_ =
      static_cast<std::uint64_t>(std::max(1LL, std::llround(config_.rate_hz / config_.nmea_out.rate_hz)));
}

void EstimatorLoop::sendNmea(Validity v) {
  if (nmea_out_ == nullptr) return;
  if (ticks_to_nmea_ > 0) {
    --ticks_to_nmea_;
    return;
  }
  ticks_to_nmea_ = nmea_every_ticks_ - 1;
  formatNmeaOut(config_.nmea_out, pipeline_.output(), v, nmea_from_files_, nmea_batch_);
  nmea_out_->offer(nmea_batch_);
}

void EstimatorLoop::logRingDrops(std::int64_t wake_ns) {
  // Ring drops happen on the producer side, which must not log; they are logged here.
  std::size_t i = 0;
  const auto check = [&](const auto& ring) {
    const RingStats s = ring.stats();
    if (s.dropped != ring_drops_seen_[i]) {
      std::uint64_t suppressed = 0;
      if (drop_log_.allow(wake_ns, &suppressed)) {
        spdlog::warn("ring {} full: {} sample(s) dropped ({} in total; {} such messages suppressed)", ring.name(),
                     s.dropped - ring_drops_seen_[i], s.dropped, suppressed);
      }
      ring_drops_seen_[i] = s.dropped;
    }
    ++i;
  };
  for (const auto* ring : imu_rings_) check(*ring);
  for (const auto* ring : gps_rings_) check(*ring);
}

void EstimatorLoop::processImu(const ImuRingEntry& raw, std::int64_t utime_us) {
  // The calibrated sample is what the estimator sees and what IMU publishes.
  ImuRingEntry e = raw;
  e.sample = correction_.apply(raw.sample);
  if (correction_.magFit().calibrationInUse() != mag_calibration_in_use_) {
    mag_calibration_in_use_ = correction_.magFit().calibrationInUse();
    if (mag_calibration_in_use_) {
      spdlog::info("magnetometer calibration fits again: applied");
    } else {
      const core::MagCalibrationFit& fit = correction_.magFit();
      spdlog::warn(
          "magnetometer calibration no longer fits the readings (field strength raw {:.1f} uT varying "
          "{:.1f} %, calibrated {:.1f} uT varying {:.1f} %): set aside, raw magnetometer used",
          fit.rawStrength(), 100.0 * fit.rawFluctuation(), fit.calibratedStrength(),
          100.0 * fit.calibratedFluctuation());
    }
  }
  const core::SampleVerdict verdict = pipeline_.process(e.sample);
  ++imu_processed_;
  imu_.last_any_arrival_ns = std::max(imu_.last_any_arrival_ns, e.arrival_mono_ns);
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
  if (config_.lcm.publish_imu) {
    fillImu(imu_msg_, e.sample, verdict, source_names_[e.source_index], utime_us);
    if (publisher_.publish(config_.lcm.imu_channel, imu_msg_)) ++published_.imu;
  }
}

void EstimatorLoop::processGps(const GpsRingEntry& e, std::int64_t utime_us) {
  if (recorder_ != nullptr) recorder_->gpsPlaced(e.observation.t_ns, imu_processed_);
  std::uint64_t suppressed = 0;
  const char* problem = pipeline_.processGps(e.observation);
  if (problem != nullptr && gps_rejected_log_.allow(e.arrival_mono_ns, &suppressed)) {
    spdlog::warn("GPS epoch from {}: value left out: {} ({} values left out so far, {} lines not logged)",
                 source_names_[e.source_index], problem, pipeline_.gpsValuesIgnored(), suppressed);
  }
  ++gps_epochs_processed_;
  if (config_.lcm.publish_gps) {
    fillGps(gps_msg_, e.observation, source_names_[e.source_index], utime_us);
    if (publisher_.publish(config_.lcm.gps_channel, gps_msg_)) ++published_.gps;
  }
}

Validity EstimatorLoop::validity(std::int64_t now_ns) const {
  if (!pipeline_.output().attitude.valid) return Validity::kNone;
  return now_ns - imu_.last_used_arrival_ns <= imu_timeout_ns_ ? Validity::kFresh : Validity::kStale;
}

void EstimatorLoop::publishEstimate(std::int64_t now_ns, std::int64_t utime_us) {
  const Validity v = validity(now_ns);
  PublishTimes t;
  t.utime_us = utime_us;
  t.sample_utime_us = imu_.last_used_t_ns / 1000;
  t.sample_age_us = imu_.any_used ? (now_ns - imu_.last_used_arrival_ns) / 1000 : 0;
  const core::HeadingOutput& out = pipeline_.output();
  fillHeading(heading_msg_, out, v, t);
  fillAttitude(attitude_msg_, out, pipeline_.estimator().ekf().covariance(), v, t);
  // The sample's age is measured when HEADING has been sent, by the sender thread.
  const std::int64_t fresh_arrival = consumed_this_tick_ ? imu_.last_used_arrival_ns : LcmPublisher::kNoSample;
  const bool heading_ok = publisher_.publish(config_.lcm.heading_channel, heading_msg_, fresh_arrival);
  const bool attitude_ok = publisher_.publish(config_.lcm.attitude_channel, attitude_msg_);
  if (heading_ok && attitude_ok) ++published_.heading;
  sendNmea(v);
}

void EstimatorLoop::publishStatus(std::int64_t now_ns, std::int64_t utime_us) {
  const double window_s = static_cast<double>(now_ns - last_status_ns_) * 1e-9;
  last_status_ns_ = now_ns;
  status_t& m = status_msg_;
  m.utime = utime_us;
  m.state = healthState(imu_, pipeline_.output().attitude.valid, start_ns_, now_ns, config_, &m.reason);
  m.uptime_us = (now_ns - start_ns_) / 1000;
  fillSourceStatus(m, sources_, source_reports_);
  fillRingStatus(m, imu_rings_, gps_rings_);
  m.rate_hz = config_.rate_hz;
  m.ticks = static_cast<std::int64_t>(ticks_);
  m.deadline_misses = static_cast<std::int64_t>(deadline_misses_);
  fillTickTiming(m, timing_window_);
  timing_window_.clear();
  fillRates(m, published_, published_at_last_status_, window_s);
  published_at_last_status_ = published_;
  m.publish_errors = static_cast<std::int64_t>(publisher_.errors());
  fillCounters(m, pipeline_.estimator().counters(), loopCounters());
  fillRealtimeStatus(m, realtime_.report());
  if (recorder_status_ != nullptr) appendRecorderCounters(m, recorder_status_->counters());
  if (nmea_out_ != nullptr) appendNmeaOutCounters(m, nmea_out_->counters());
  if (publisher_.publish(config_.lcm.status_channel, m)) ++published_.status;

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
  c.mag_calibration_set_aside = correction_.magFit().setAside();
  c.mag_calibration_taken_back = correction_.magFit().takenBack();
  c.gps_epochs = gps_epochs_processed_;
  c.gps_epochs_used_for_declination = pipeline_.gpsEpochsUsedForDeclination();
  c.gps_epochs_forced_out = gps_epochs_forced_;
  c.gps_values_ignored = pipeline_.gpsValuesIgnored();
  c.log_write_errors = logWriteErrors();
  return c;
}

void EstimatorLoop::reloadCalibration() {
  // Between two ticks, so no sample sees half of each calibration. A file that no longer
  // reads keeps the calibration in use: a typo must not turn it off in the field.
  if (config_.calibration_path.empty()) {
    spdlog::info("SIGHUP: no [daemon] calibration configured, nothing to reload");
    return;
  }
  try {
    correction_ = loadCalibration(config_.calibration_path);
    mag_calibration_in_use_ = true;
    if (recorder_ != nullptr) recorder_->calibrationReloaded(imu_.last_used_t_ns, imu_processed_);
    spdlog::info("SIGHUP: calibration reloaded from {}", config_.calibration_path);
  } catch (const std::exception& e) {
    spdlog::error("SIGHUP: calibration not reloaded, keeping the one in use: {}", e.what());
  }
}

LoopSummary EstimatorLoop::summary() const {
  LoopSummary s;
  s.ticks = ticks_;
  s.deadline_misses = deadline_misses_;
  s.timing = tickTimingFigures(timing_total_);
  s.heading_published = published_.heading;
  s.imu_published = published_.imu;
  s.gps_published = published_.gps;
  s.status_published = published_.status;
  s.publish_errors = publisher_.errors();
  return s;
}

}  // namespace headingd::daemon
