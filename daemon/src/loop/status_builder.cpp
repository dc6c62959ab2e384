#include "headingd/daemon/loop/status_builder.hpp"

#include <cstdio>
#include <numbers>
#include <string_view>

#include "headingd/core/angles.hpp"

namespace headingd::daemon {
namespace {

using core::kDegPerRad;

double us(double ns) { return ns * 1e-3; }

template <class Ring>
void fillRing(ring_status_t& r, Ring& ring) {
  const RingStats st = ring.stats();
  if (r.name != ring.name()) r.name = ring.name();
  r.capacity = static_cast<std::int32_t>(st.capacity);
  r.high_water = static_cast<std::int32_t>(st.high_water);
  r.window_high_water = static_cast<std::int32_t>(ring.takeWindowHighWater());
  r.pushed = static_cast<std::int64_t>(st.pushed);
  r.dropped = static_cast<std::int64_t>(st.dropped);
}

}  // namespace

const char* healthState(const ImuFreshness& imu, bool estimate_valid, std::int64_t start_ns, std::int64_t now_ns,
                        const DaemonConfig& config, std::string* reason) {
  reason->clear();
  const double uptime_s = static_cast<double>(now_ns - start_ns) * 1e-9;
  if (!imu.any_used) {
    if (uptime_s <= config.imu_timeout_s) return "starting";
    *reason = imu.last_any_arrival_ns != 0 ? "every IMU sample so far was rejected (see the estimator counters)"
                                           : "no IMU data since start";
    return "degraded";
  }
  const double silent_s = static_cast<double>(now_ns - imu.last_used_arrival_ns) * 1e-9;
  if (silent_s > config.imu_timeout_s) {
    char text[128];
    const auto imu_timeout_ns = static_cast<std::int64_t>(config.imu_timeout_s * 1e9);
    const bool arriving = now_ns - imu.last_any_arrival_ns <= imu_timeout_ns;
    std::snprintf(text, sizeof text, arriving ? "IMU samples rejected for %.1f s" : "no IMU data for %.1f s", silent_s);
    *reason = text;
    return "degraded";
  }
  if (!estimate_valid) return "starting";
  return "ok";
}

void fillSourceStatus(status_t& m, const std::vector<Source*>& sources, std::vector<SourceReport>& reports) {
  for (std::size_t i = 0; i < sources.size(); ++i) {
    SourceReport& r = reports[i];
    sources[i]->report(r);
    source_status_t& s = m.sources[i];
    if (s.name != sources[i]->name()) s.name = sources[i]->name();
    s.kind = sources[i]->kind();
    s.state = sourceStateName(r.state);
    s.last_error = r.last_error;
    s.counters.resize(r.counters.size());
    s.num_counters = static_cast<std::int32_t>(r.counters.size());
    for (std::size_t c = 0; c < r.counters.size(); ++c) {
      setStatusCounter(s.counters, c, r.counters[c].name, r.counters[c].value);
    }
  }
}

void fillRingStatus(status_t& m, const std::vector<SampleRing<ImuRingEntry>*>& imu_rings,
                    const std::vector<SampleRing<GpsRingEntry>*>& gps_rings) {
  std::size_t i = 0;
  for (auto* ring : imu_rings) fillRing(m.rings[i++], *ring);
  for (auto* ring : gps_rings) fillRing(m.rings[i++], *ring);
}

TickTimingFigures tickTimingFigures(const TickTiming& t) {
  TickTimingFigures f;
  f.jitter_p50_us = us(t.jitter.percentile(0.5));
  f.jitter_p99_us = us(t.jitter.percentile(0.99));
  f.jitter_max_us = us(static_cast<double>(t.jitter.max()));
  f.processing_p50_us = us(t.processing.percentile(0.5));
  f.processing_p99_us = us(t.processing.percentile(0.99));
  f.processing_max_us = us(static_cast<double>(t.processing.max()));
  f.sample_age_p50_us = us(t.sample_age.percentile(0.5));
  f.sample_age_p99_us = us(t.sample_age.percentile(0.99));
  f.sample_age_max_us = us(static_cast<double>(t.sample_age.max()));
  return f;
}

void fillTickTiming(status_t& m, const TickTiming& window) {
  const TickTimingFigures f = tickTimingFigures(window);
  m.tick_jitter_p50_us = f.jitter_p50_us;
  m.tick_jitter_p99_us = f.jitter_p99_us;
  m.tick_jitter_max_us = f.jitter_max_us;
  m.processing_p50_us = f.processing_p50_us;
  m.processing_p99_us = f.processing_p99_us;
  m.processing_max_us = f.processing_max_us;
  m.sample_age_p50_us = f.sample_age_p50_us;
  m.sample_age_p99_us = f.sample_age_p99_us;
}

void fillRealtimeStatus(status_t& m, const RealtimeReport& realtime) {
  if (m.estimator_policy != realtime.estimator.policy) m.estimator_policy = realtime.estimator.policy;
  m.estimator_priority = realtime.estimator.priority;
  if (m.driver_policy != realtime.drivers.policy) m.driver_policy = realtime.drivers.policy;
  m.driver_priority = realtime.drivers.priority;
  m.memory_locked = realtime.memory_locked;
}

void fillRates(status_t& m, const PublishedCounts& now, const PublishedCounts& at_last_status, double window_s) {
  m.heading_rate_hz = static_cast<double>(now.heading - at_last_status.heading) / window_s;
  m.imu_rate_hz = static_cast<double>(now.imu - at_last_status.imu) / window_s;
  m.gps_rate_hz = static_cast<double>(now.gps - at_last_status.gps) / window_s;
}

void fillCounters(status_t& m, const core::EstimatorCounters& estimator, const LoopCounters& loop) {
  std::size_t i = 0;
  const auto add = [&](std::string_view name, std::uint64_t value) { setStatusCounter(m.counters, i++, name, value); };
  // STATUS's published names and order: the estimator's "accepted" is "samples_accepted"
  // here, and each of the loop's counters stands beside the estimator counters it explains.
  core::forEachCounter(estimator, [&](std::string_view name, std::uint64_t value) {
    if (name == "state_recoveries") {
      add("mag_calibration_set_aside", loop.mag_calibration_set_aside);
      add("mag_calibration_taken_back", loop.mag_calibration_taken_back);
    }
    add(name == "accepted" ? "samples_accepted" : name, value);
    if (name == "out_of_range_mag") add("imu_rejected", loop.imu_rejected);  // after the gate's own
  });
  add("gps_epochs", loop.gps_epochs);
  add("gps_epochs_used_for_declination", loop.gps_epochs_used_for_declination);
  add("gps_epochs_forced_out", loop.gps_epochs_forced_out);
  add("gps_values_ignored", loop.gps_values_ignored);
  add("gps_dates_not_believed", loop.gps_dates_not_believed);
  add("units_suspect_accel", loop.units_suspect_accel);
  add("units_suspect_gyro", loop.units_suspect_gyro);
  add("units_suspect_mag", loop.units_suspect_mag);
  add("log_write_errors", loop.log_write_errors);
  m.num_counters = static_cast<std::int32_t>(i);
}

void formatStatusLine(const status_t& m, const core::HeadingOutput& h, Validity v, std::string& out) {
  char line[400];
  std::snprintf(line, sizeof line,
                "%s%s%s | heading %s%.1f deg true, %.1f deg magnetic | declination %.2f deg (%s) | disturbed %s | "
                "HEADING %.1f Hz, IMU %.1f Hz, GPS %.1f Hz | jitter p99 %.0f us, tick p99 %.0f us",
                m.state.c_str(), m.reason.empty() ? "" : ": ", m.reason.c_str(),
                v == Validity::kFresh   ? ""
                : v == Validity::kStale ? "(stale) "
                                        : "(none) ",
                h.heading_true_rad * kDegPerRad, h.heading_mag_rad * kDegPerRad, h.declination_rad * kDegPerRad,
                core::declinationSourceName(h.declination_sources), h.attitude.mag_disturbed ? "yes" : "no",
                m.heading_rate_hz, m.imu_rate_hz, m.gps_rate_hz, m.tick_jitter_p99_us, m.processing_p99_us);
  out = line;
}

}  // namespace headingd::daemon
