#pragma once
// The estimator loop's outputs (LCM, NMEA out, the black box's estimator stream) behind one
// interface: the loop calls every sink at fixed points of its tick, in its order of steps, and
// does not know what a sink makes of them (the split of PX4-ECL: the filter does the math, the
// module publishes). Every call comes on the estimator thread and must not block; each default
// does nothing, so a sink overrides only what it uses.
#include <cstdint>
#include <optional>
#include <string>

#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/sample_gate.hpp"
#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/outputs/lcm_messages.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon {

// One estimate as the loop hands it out.
struct PublishedEstimate {
  const core::HeadingPipeline& pipeline;  // output() and the estimator's state (covariance)
  Validity validity;
  PublishTimes times;
  // The newest sample's arrival (CLOCK_MONOTONIC) when this estimate used a new sample, empty
  // when it did not: a sink that measures a sample's age measures it only once.
  std::optional<std::int64_t> fresh_arrival_ns;
};

class EstimateSink {
 public:
  virtual ~EstimateSink() = default;

  // An IMU sample as the estimator saw it (calibrated), with the sample gate's verdict.
  virtual void imuSample(const ImuRingEntry& /*entry*/, core::SampleVerdict /*verdict*/,
                         const std::string& /*source_name*/, std::int64_t /*utime_us*/) {}
  // A GPS epoch that went into the estimator after `imu_samples_before` IMU samples.
  virtual void gpsEpoch(const GpsRingEntry& /*entry*/, std::uint64_t /*imu_samples_before*/,
                        const std::string& /*source_name*/, std::int64_t /*utime_us*/) {}
  // The estimate of a tick (and of each arrival with [daemon] publish = "imu").
  virtual void estimate(const PublishedEstimate& /*estimate*/) {}
  // SIGHUP reloaded the calibration after `imu_samples_before` samples, the last one at `t_ns`.
  virtual void calibrationReloaded(std::int64_t /*t_ns*/, std::uint64_t /*imu_samples_before*/) {}
  // The sink's own counters, appended to those STATUS already holds.
  virtual void appendStatusCounters(status_t& /*m*/) const {}
};

}  // namespace headingd::daemon
