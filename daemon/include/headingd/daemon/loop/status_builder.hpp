#pragma once
// What STATUS (daemon/lcm/status_t.lcm) says, built from the estimator loop's parts: the
// health state, every source's report, the rings, the tick timing and message rates of the
// last status period, the counters; and the one line for people (systemctl status, the
// console) that sums it up. The estimator loop decides when STATUS goes out; this decides what
// is in it. Filling reuses the message's strings and arrays, so a STATUS allocates nothing
// once names and counters have been set the first time.
#include <cstdint>
#include <string>
#include <vector>

#include "headingd/core/estimator.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/daemon/config/config.hpp"
#include "headingd/daemon/loop/latency_histogram.hpp"
#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/outputs/lcm_messages.hpp"
#include "headingd/daemon/outputs/lcm_output.hpp"
#include "headingd/daemon/sources/source.hpp"
#include "headingd/daemon/system/realtime.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon {

// How fresh the IMU data is: HEADING's validity and the health state are judged by it.
struct ImuFreshness {
  bool any_used = false;
  std::int64_t last_used_arrival_ns = 0;  // arrival of the newest IMU sample the gate used
  std::int64_t last_used_t_ns = 0;        // its sensor time
  std::int64_t last_any_arrival_ns = 0;   // of any IMU sample, used or rejected
};

// The estimator loop's timing: per run (the summary at exit) and per status period.
struct TickTiming {
  LatencyHistogram jitter;      // actual wake-up minus deadline
  LatencyHistogram processing;  // wake-up to the tick's messages queued for the LCM sender
  LatencyHistogram sample_age;  // newest sample's age when its HEADING was sent

  void clear() {
    jitter.clear();
    processing.clear();
    sample_age.clear();
  }
};

// A TickTiming's figures, in microseconds.
struct TickTimingFigures {
  double jitter_p50_us = 0, jitter_p99_us = 0, jitter_max_us = 0;
  double processing_p50_us = 0, processing_p99_us = 0, processing_max_us = 0;
  double sample_age_p50_us = 0, sample_age_p99_us = 0, sample_age_max_us = 0;
};
TickTimingFigures tickTimingFigures(const TickTiming& t);

// The loop's own counters, which STATUS lists beside the estimator's.
struct LoopCounters {
  std::uint64_t imu_rejected = 0;               // IMU samples the sample gate did not use
  std::uint64_t mag_calibration_set_aside = 0;  // mag_calibration_fit.hpp
  std::uint64_t mag_calibration_taken_back = 0;
  std::uint64_t gps_epochs = 0;  // GPS epochs that went into the estimator
  std::uint64_t gps_epochs_used_for_declination = 0;
  std::uint64_t gps_epochs_forced_out = 0;  // went in early: too many held (never expected)
  std::uint64_t gps_dates_not_believed = 0;
  // 1 when the first seconds' samples do not look like SI units (core/sensor_units_check.hpp).
  std::uint64_t units_suspect_accel = 0, units_suspect_gyro = 0,
                units_suspect_mag = 0;   // of those, dates (core/gps_date_check.hpp)
  std::uint64_t gps_values_ignored = 0;  // unusable GPS values left out (HeadingPipeline::processGps)
  std::uint64_t log_write_errors = 0;    // the log file could not be written (logging.hpp)
};

// "ok", "degraded" (see `reason`) or "starting" (no estimate yet); `reason` is empty unless
// degraded.
const char* healthState(const ImuFreshness& imu, bool estimate_valid, std::int64_t start_ns, std::int64_t now_ns,
                        const DaemonConfig& config, std::string* reason);

// Each source's state, last error and counters, refreshed through `reports` (one per source).
void fillSourceStatus(status_t& m, const std::vector<Source*>& sources, std::vector<SourceReport>& reports);
// Capacity, high-water marks (since start, and since the last STATUS: read and reset here, so
// the rings' consumer thread only), pushes and drops of each ring, the IMU rings first.
void fillRingStatus(status_t& m, const std::vector<SampleRing<ImuRingEntry>*>& imu_rings,
                    const std::vector<SampleRing<GpsRingEntry>*>& gps_rings);
// The scheduling policies the estimator and driver threads got and whether memory is locked.
void fillRealtimeStatus(status_t& m, const RealtimeReport& realtime);
// Percentiles of the status period's tick timing, in microseconds.
void fillTickTiming(status_t& m, const TickTiming& window);
// Messages per second over the status period.
void fillRates(status_t& m, const PublishedCounts& now, const PublishedCounts& at_last_status, double window_s);
// The estimator's counters (core::forEachCounter) with the loop's own in their places.
void fillCounters(status_t& m, const core::EstimatorCounters& estimator, const LoopCounters& loop);

// The one line for people, from a filled message and the estimate it describes.
void formatStatusLine(const status_t& m, const core::HeadingOutput& h, Validity v, std::string& out);

}  // namespace headingd::daemon
