#include "headingd/daemon/estimator_loop.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <spdlog/spdlog.h>
#include <time.h>
#include <tuple>

#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/daemon/clocks.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "headingd/daemon/realtime.hpp"

namespace headingd::daemon {
namespace {

// [daemon] calibration: none when none is configured; a bad file throws (start-up stops).
core::CalibratedImuStream loadCalibration(const std::string& path) {
  if (path.empty()) return core::CalibratedImuStream{};
  return core::CalibratedImuStream(core::parseImuCalibration(files::readMaybeGzipFile(path), path));
}


constexpr double kDeg = 180.0 / std::numbers::pi;

bool gateUsed(core::SampleVerdict v) {
  switch (v) {
    case core::SampleVerdict::kAccepted:
    case core::SampleVerdict::kFirst:
    case core::SampleVerdict::kGap:
    case core::SampleVerdict::kClockJump:
      return true;
    default:
      return false;
  }
}

double us(double ns) { return ns * 1e-3; }

void setCounter(std::vector<headingd::counter_t>& counters, std::size_t i, const char* name, std::uint64_t value) {
  if (i >= counters.size()) counters.resize(i + 1);
  if (counters[i].name != name) counters[i].name = name;
  counters[i].value = static_cast<std::int64_t>(value);
}

}  // namespace

EstimatorLoop::EstimatorLoop(const DaemonConfig& config, const core::WorldMagneticModel* wmm,
                             std::vector<SampleRing<ImuRingEntry>*> imu_rings,
                             std::vector<SampleRing<GpsRingEntry>*> gps_rings, std::vector<Source*> sources,
                             LcmPublisher& publisher, SystemdNotifier& notifier)
    : config_(config),
      pipeline_(config.estimator, wmm),
      correction_(loadCalibration(config.calibration_path)),
      imu_rings_(std::move(imu_rings)),
      gps_rings_(std::move(gps_rings)),
      sources_(std::move(sources)),
      publisher_(publisher),
      notifier_(notifier),
      period_ns_(static_cast<std::int64_t>(std::llround(1e9 / config.rate_hz))),
      imu_timeout_ns_(static_cast<std::int64_t>(config.imu_timeout_s * 1e9)),
      status_period_ns_(static_cast<std::int64_t>(config.status_period_s * 1e9)),
      rejected_log_(config.log.repeat_burst, config.log.repeat_interval_s),
      drop_log_(config.log.repeat_burst, config.log.repeat_interval_s),
      miss_log_(config.log.repeat_burst, config.log.repeat_interval_s) {
  std::size_t imu_capacity = 0, gps_capacity = 0;
  for (const auto* r : imu_rings_) imu_capacity += r->capacity();
  for (const auto* r : gps_rings_) gps_capacity += r->capacity();
  imu_batch_.reserve(imu_capacity);
  gps_pending_.reserve(2 * gps_capacity + 1);
  for (const Source* s : sources_) source_names_.push_back(s->name());
  source_reports_.resize(sources_.size());
  ring_drops_seen_.assign(imu_rings_.size() + gps_rings_.size(), 0);
  status_msg_.sources.resize(sources_.size());
  status_msg_.num_sources = static_cast<std::int32_t>(sources_.size());
  status_msg_.rings.resize(imu_rings_.size() + gps_rings_.size());
  status_msg_.num_rings = static_cast<std::int32_t>(status_msg_.rings.size());
}

void EstimatorLoop::run() {
  applyThreadRealtime(config_.realtime);
  start_ns_ = monotonicNs();
  last_status_ns_ = start_ns_;
  std::int64_t deadline = start_ns_ + period_ns_;
  bool ready_sent = false;
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    const timespec ts = toTimespec(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
    const std::int64_t wake = monotonicNs();
    const bool exit_after_this_tick = sourcesWantExit();  // seen before draining: their data is all in
    tick(wake, exit_after_this_tick);
    const std::int64_t done = monotonicNs();
    ++ticks_;
    jitter_total_.record(wake - deadline);
    jitter_window_.record(wake - deadline);
    processing_total_.record(done - wake);
    processing_window_.record(done - wake);
    deadline += period_ns_;
    if (done > deadline) {
      // Missed one or more deadlines: skip them rather than run a burst of late ticks.
      const std::int64_t missed = (done - deadline) / period_ns_ + 1;
      deadline_misses_ += static_cast<std::uint64_t>(missed);
      deadline += missed * period_ns_;
      std::uint64_t suppressed = 0;
      if (miss_log_.allow(done, &suppressed)) {
        spdlog::warn("estimator tick took {:.3f} ms, {} deadline(s) missed ({} such messages suppressed)",
                     (done - wake) * 1e-6, missed, suppressed);
      }
    }
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

  imu_batch_.clear();
  for (auto* ring : imu_rings_) ring->drain([this](const ImuRingEntry& e) { imu_batch_.push_back(e); });
  for (auto* ring : gps_rings_) {
    ring->drain([this](const GpsRingEntry& e) {
      if (gps_pending_.size() == gps_pending_.capacity()) {  // never expected: GPS is slow
        processGps(gps_pending_.front(), realtimeNs() / 1000);
        ++gps_epochs_forced_;
        gps_pending_.erase(gps_pending_.begin());
      }
      gps_pending_.push_back(e);
    });
  }
  // One source's samples come in order; several sources are merged by sensor time, ties
  // by arrival (std::sort: no temporary buffer, unlike stable_sort).
  auto by_time = [](const ImuRingEntry& a, const ImuRingEntry& b) {
    return std::tie(a.sample.t_ns, a.arrival_mono_ns, a.source_index) <
           std::tie(b.sample.t_ns, b.arrival_mono_ns, b.source_index);
  };
  if (!std::is_sorted(imu_batch_.begin(), imu_batch_.end(), by_time)) {
    std::sort(imu_batch_.begin(), imu_batch_.end(), by_time);
  }
  auto gps_by_time = [](const GpsRingEntry& a, const GpsRingEntry& b) {
    return std::tie(a.observation.t_ns, a.arrival_mono_ns, a.source_index) <
           std::tie(b.observation.t_ns, b.arrival_mono_ns, b.source_index);
  };
  if (!std::is_sorted(gps_pending_.begin(), gps_pending_.end(), gps_by_time)) {
    std::sort(gps_pending_.begin(), gps_pending_.end(), gps_by_time);
  }

  consumed_this_tick_ = false;
  std::size_t next_gps = 0;
  for (const ImuRingEntry& e : imu_batch_) {
    processImu(e, utime_us);
    // GPS epochs go in after the IMU sample of the same or a later time (headingd-replay's order).
    while (next_gps < gps_pending_.size() && gps_pending_[next_gps].observation.t_ns <= e.sample.t_ns) {
      processGps(gps_pending_[next_gps++], utime_us);
    }
  }
  // Without IMU data an epoch would wait for ever: then it goes in as it is (also on the
  // last tick, when a file's last epoch is later than its last IMU sample).
  const bool imu_stale = !any_imu_used_ || wake_ns - last_used_arrival_ns_ > imu_timeout_ns_;
  if (imu_stale || last_tick) {
    while (next_gps < gps_pending_.size()) processGps(gps_pending_[next_gps++], utime_us);
  }
  gps_pending_.erase(gps_pending_.begin(), gps_pending_.begin() + static_cast<std::ptrdiff_t>(next_gps));

  // Ring drops happen on the producer side, which must not log; they are logged here.
  for (std::size_t i = 0; i < imu_rings_.size() + gps_rings_.size(); ++i) {
    const RingStats s = i < imu_rings_.size() ? imu_rings_[i]->stats() : gps_rings_[i - imu_rings_.size()]->stats();
    if (s.dropped != ring_drops_seen_[i]) {
      std::uint64_t suppressed = 0;
      if (drop_log_.allow(wake_ns, &suppressed)) {
        const std::string& name = i < imu_rings_.size() ? imu_rings_[i]->name() : gps_rings_[i - imu_rings_.size()]->name();
        spdlog::warn("ring {} full: {} sample(s) dropped ({} in total; {} such messages suppressed)", name,
                     s.dropped - ring_drops_seen_[i], s.dropped, suppressed);
      }
      ring_drops_seen_[i] = s.dropped;
    }
  }

  const std::int64_t now = monotonicNs();
  publishEstimate(now, utime_us);
  // The last tick too, so that STATUS shows the sources finished and their final counters.
  if (now - last_status_ns_ >= status_period_ns_ || last_tick) publishStatus(now, utime_us);
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
      spdlog::warn("magnetometer calibration no longer fits the readings (field strength raw {:.1f} uT varying "
                   "{:.1f} %, calibrated {:.1f} uT varying {:.1f} %): set aside, raw magnetometer used",
                   fit.rawStrength(), 100.0 * fit.rawFluctuation(), fit.calibratedStrength(),
                   100.0 * fit.calibratedFluctuation());
    }
  }
  const core::SampleVerdict verdict = pipeline_.process(e.sample);
  last_any_imu_arrival_ns_ = std::max(last_any_imu_arrival_ns_, e.arrival_mono_ns);
  if (gateUsed(verdict)) {
    any_imu_used_ = true;
    consumed_this_tick_ = true;
    last_used_arrival_ns_ = e.arrival_mono_ns;
    last_used_t_ns_ = e.sample.t_ns;
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
    if (publisher_.publish(config_.lcm.imu_channel, imu_msg_)) ++imu_published_;
  }
}

void EstimatorLoop::processGps(const GpsRingEntry& e, std::int64_t utime_us) {
  pipeline_.processGps(e.observation);
  ++gps_epochs_processed_;
  if (config_.lcm.publish_gps) {
    fillGps(gps_msg_, e.observation, source_names_[e.source_index], utime_us);
    if (publisher_.publish(config_.lcm.gps_channel, gps_msg_)) ++gps_published_;
  }
}

Validity EstimatorLoop::validity(std::int64_t now_ns) const {
  if (!pipeline_.output().attitude.valid) return Validity::kNone;
  return now_ns - last_used_arrival_ns_ <= imu_timeout_ns_ ? Validity::kFresh : Validity::kStale;
}

void EstimatorLoop::publishEstimate(std::int64_t now_ns, std::int64_t utime_us) {
  const Validity v = validity(now_ns);
  PublishTimes t;
  t.utime_us = utime_us;
  t.sample_utime_us = last_used_t_ns_ / 1000;
  t.sample_age_us = any_imu_used_ ? (now_ns - last_used_arrival_ns_) / 1000 : 0;
  const core::HeadingOutput& out = pipeline_.output();
  fillHeading(heading_msg_, out, v, t);
  fillAttitude(attitude_msg_, out, pipeline_.estimator().ekf().covariance(), v, t);
  const bool heading_ok = publisher_.publish(config_.lcm.heading_channel, heading_msg_);
  const bool attitude_ok = publisher_.publish(config_.lcm.attitude_channel, attitude_msg_);
  if (heading_ok && attitude_ok) ++heading_published_;
  if (consumed_this_tick_) {
    const std::int64_t age = monotonicNs() - last_used_arrival_ns_;
    age_total_.record(age);
    age_window_.record(age);
  }
}

const char* EstimatorLoop::healthState(std::int64_t now_ns, std::string* reason) const {
  reason->clear();
  const double uptime_s = static_cast<double>(now_ns - start_ns_) * 1e-9;
  if (!any_imu_used_) {
    if (uptime_s <= config_.imu_timeout_s) return "starting";
    *reason = last_any_imu_arrival_ns_ != 0 ? "every IMU sample so far was rejected (see the estimator counters)"
                                            : "no IMU data since start";
    return "degraded";
  }
  const double silent_s = static_cast<double>(now_ns - last_used_arrival_ns_) * 1e-9;
  if (silent_s > config_.imu_timeout_s) {
    char text[128];
    const bool arriving = now_ns - last_any_imu_arrival_ns_ <= imu_timeout_ns_;
    std::snprintf(text, sizeof text, arriving ? "IMU samples rejected for %.1f s" : "no IMU data for %.1f s", silent_s);
    *reason = text;
    return "degraded";
  }
  if (!pipeline_.output().attitude.valid) return "starting";
  return "ok";
}

void EstimatorLoop::publishStatus(std::int64_t now_ns, std::int64_t utime_us) {
  const double window_s = static_cast<double>(now_ns - last_status_ns_) * 1e-9;
  last_status_ns_ = now_ns;
  status_t& m = status_msg_;
  m.utime = utime_us;
  m.state = healthState(now_ns, &m.reason);
  m.uptime_us = (now_ns - start_ns_) / 1000;

  for (std::size_t i = 0; i < sources_.size(); ++i) {
    SourceReport& r = source_reports_[i];
    sources_[i]->report(r);
    source_status_t& s = m.sources[i];
    if (s.name != sources_[i]->name()) s.name = sources_[i]->name();
    s.kind = sources_[i]->kind();
    s.state = sourceStateName(r.state);
    s.last_error = r.last_error;
    s.counters.resize(r.counters.size());
    s.num_counters = static_cast<std::int32_t>(r.counters.size());
    for (std::size_t c = 0; c < r.counters.size(); ++c) {
      if (s.counters[c].name != r.counters[c].name) s.counters[c].name = r.counters[c].name;
      s.counters[c].value = static_cast<std::int64_t>(r.counters[c].value);
    }
  }
  for (std::size_t i = 0; i < imu_rings_.size() + gps_rings_.size(); ++i) {
    const bool imu = i < imu_rings_.size();
    const RingStats st = imu ? imu_rings_[i]->stats() : gps_rings_[i - imu_rings_.size()]->stats();
    ring_status_t& r = m.rings[i];
    const std::string& name = imu ? imu_rings_[i]->name() : gps_rings_[i - imu_rings_.size()]->name();
    if (r.name != name) r.name = name;
    r.capacity = static_cast<std::int32_t>(st.capacity);
    r.high_water = static_cast<std::int32_t>(st.high_water);
    r.pushed = static_cast<std::int64_t>(st.pushed);
    r.dropped = static_cast<std::int64_t>(st.dropped);
  }

  m.rate_hz = config_.rate_hz;
  m.ticks = static_cast<std::int64_t>(ticks_);
  m.deadline_misses = static_cast<std::int64_t>(deadline_misses_);
  m.tick_jitter_p50_us = us(jitter_window_.percentile(0.5));
  m.tick_jitter_p99_us = us(jitter_window_.percentile(0.99));
  m.tick_jitter_max_us = us(static_cast<double>(jitter_window_.max()));
  m.processing_p50_us = us(processing_window_.percentile(0.5));
  m.processing_p99_us = us(processing_window_.percentile(0.99));
  m.processing_max_us = us(static_cast<double>(processing_window_.max()));
  m.sample_age_p50_us = us(age_window_.percentile(0.5));
  m.sample_age_p99_us = us(age_window_.percentile(0.99));
  jitter_window_.clear();
  processing_window_.clear();
  age_window_.clear();
  m.heading_rate_hz = static_cast<double>(heading_published_ - heading_at_last_status_) / window_s;
  m.imu_rate_hz = static_cast<double>(imu_published_ - imu_at_last_status_) / window_s;
  m.gps_rate_hz = static_cast<double>(gps_published_ - gps_at_last_status_) / window_s;
  heading_at_last_status_ = heading_published_;
  imu_at_last_status_ = imu_published_;
  gps_at_last_status_ = gps_published_;
  m.publish_errors = static_cast<std::int64_t>(publisher_.errors());

  const core::EstimatorCounters c = pipeline_.estimator().counters();
  std::size_t i = 0;
  setCounter(m.counters, i++, "samples_accepted", c.samples.accepted);
  setCounter(m.counters, i++, "gaps", c.samples.gaps);
  setCounter(m.counters, i++, "clock_jumps", c.samples.clock_jumps);
  setCounter(m.counters, i++, "duplicate_time", c.samples.duplicate_time);
  setCounter(m.counters, i++, "backwards_time", c.samples.backwards_time);
  setCounter(m.counters, i++, "non_finite", c.samples.non_finite);
  setCounter(m.counters, i++, "non_finite_mag", c.samples.non_finite_mag);
  setCounter(m.counters, i++, "out_of_range", c.samples.out_of_range);
  setCounter(m.counters, i++, "out_of_range_mag", c.samples.out_of_range_mag);
  setCounter(m.counters, i++, "imu_rejected", imu_rejected_);
  setCounter(m.counters, i++, "bias_still_blocks", c.bias_still_blocks);
  setCounter(m.counters, i++, "mag_no_heading", c.mag_no_heading);
  setCounter(m.counters, i++, "mag_disturbed", c.mag_disturbed);
  setCounter(m.counters, i++, "mag_heading_restores", c.mag_heading_restores);
  setCounter(m.counters, i++, "mag_calibration_set_aside", correction_.magFit().setAside());
  setCounter(m.counters, i++, "mag_calibration_taken_back", correction_.magFit().takenBack());
  setCounter(m.counters, i++, "state_recoveries", c.state_recoveries);
  setCounter(m.counters, i++, "gps_epochs", gps_epochs_processed_);
  setCounter(m.counters, i++, "gps_epochs_used_for_declination", pipeline_.gpsEpochsUsedForDeclination());
  setCounter(m.counters, i++, "gps_epochs_forced_out", gps_epochs_forced_);
  m.num_counters = static_cast<std::int32_t>(i);

  if (publisher_.publish(config_.lcm.status_channel, m)) ++status_published_;

  // One line for people: systemctl status (STATUS=) and, if asked, stdout.
  const core::HeadingOutput& h = pipeline_.output();
  const Validity v = validity(now_ns);
  char line[400];
  std::snprintf(line, sizeof line,
                "%s%s%s | heading %s%.1f deg true, %.1f deg magnetic | declination %.2f deg (%s) | disturbed %s | "
                "HEADING %.1f Hz, IMU %.1f Hz, GPS %.1f Hz | jitter p99 %.0f us, tick p99 %.0f us",
                m.state.c_str(), m.reason.empty() ? "" : ": ", m.reason.c_str(),
                v == Validity::kFresh ? "" : v == Validity::kStale ? "(stale) " : "(none) ", h.heading_true_rad * kDeg,
                h.heading_mag_rad * kDeg, h.declination_rad * kDeg, core::declinationSourceName(h.declination_sources),
                h.attitude.mag_disturbed ? "yes" : "no", m.heading_rate_hz, m.imu_rate_hz, m.gps_rate_hz,
                m.tick_jitter_p99_us, m.processing_p99_us);
  status_text_ = line;
  notifier_.status(status_text_);
  if (config_.console_status) {
    std::fputs(line, stdout);
    std::fputc('\n', stdout);
    std::fflush(stdout);
  }
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
    spdlog::info("SIGHUP: calibration reloaded from {}", config_.calibration_path);
  } catch (const std::exception& e) {
    spdlog::error("SIGHUP: calibration not reloaded, keeping the one in use: {}", e.what());
  }
}

LoopSummary EstimatorLoop::summary() const {
  LoopSummary s;
  s.ticks = ticks_;
  s.deadline_misses = deadline_misses_;
  s.jitter_p50_us = us(jitter_total_.percentile(0.5));
  s.jitter_p99_us = us(jitter_total_.percentile(0.99));
  s.jitter_max_us = us(static_cast<double>(jitter_total_.max()));
  s.processing_p50_us = us(processing_total_.percentile(0.5));
  s.processing_p99_us = us(processing_total_.percentile(0.99));
  s.processing_max_us = us(static_cast<double>(processing_total_.max()));
  s.sample_age_p50_us = us(age_total_.percentile(0.5));
  s.sample_age_p99_us = us(age_total_.percentile(0.99));
  s.sample_age_max_us = us(static_cast<double>(age_total_.max()));
  s.heading_published = heading_published_;
  s.imu_published = imu_published_;
  s.gps_published = gps_published_;
  s.status_published = status_published_;
  s.publish_errors = publisher_.errors();
  return s;
}

}  // namespace headingd::daemon
