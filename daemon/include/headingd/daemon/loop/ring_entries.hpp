#pragma once
// What sources push into their rings. Plain values: a push copies them and allocates nothing.
//
// Two clocks meet here. `sample.t_ns` / `observation.t_ns` is the sensor time axis the
// estimator integrates on (CLOCK_MONOTONIC for live sources; a file's own time column for
// file sources; the GPS epochs of one run must be on the IMU's axis). `arrival_mono_ns` is
// CLOCK_MONOTONIC when the data reached this machine (a CAN frame's kernel timestamp mapped
// to the monotonic clock, a serial line's read time, a file sample's scheduled play time): the
// estimator measures the age of what it publishes from it.
#include <cstdint>

#include "headingd/core/gps_observation.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::daemon {

struct ImuRingEntry {
  core::ImuSample sample;
  std::int64_t arrival_mono_ns = 0;
  std::uint16_t source_index = 0;  // which source (for the IMU message's `source` field)
};

struct GpsRingEntry {
  core::GpsObservation observation;
  std::int64_t arrival_mono_ns = 0;
  std::uint16_t source_index = 0;
  // -1: the estimator takes the epoch after the first IMU sample at or after its time (live
  // sources, logs). >= 0: after exactly this many IMU samples (a black-box recording replayed:
  // where the live estimator took it).
  std::int64_t after_imu_samples = -1;
};

// The time the estimator orders an epoch by (core::ImuThenGpsOrder).
inline std::int64_t sensorTimeNs(const GpsRingEntry& e) { return e.observation.t_ns; }

}  // namespace headingd::daemon
