#pragma once
// [daemon] calibration as the estimator loop applies it: read at start-up (so that
// --check-config sees a bad file), applied to every sample, its magnetometer part set aside
// while it no longer fits the readings (core/mag_calibration_fit.hpp; logged when that
// changes), and read again on SIGHUP, between two ticks so that no sample sees half of each.
#include <cstdint>
#include <string>

#include "headingd/core/calibrated_imu_stream.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::daemon {

// The calibration in `path`; none when `path` is empty. Throws naming the file when it cannot
// be read or parsed.
core::CalibratedImuStream loadCalibration(const std::string& path);

class CalibrationInUse {
 public:
  // `loaded`: loadCalibration(path), read before (at start-up, with the other checks).
  CalibrationInUse(std::string path, core::CalibratedImuStream loaded)
      : path_(std::move(path)), correction_(std::move(loaded)) {}

  // The calibrated sample: what the estimator sees and IMU publishes.
  core::ImuSample apply(const core::ImuSample& raw);
  // SIGHUP: reads the file again; true when the new calibration is in use. A file that no
  // longer reads keeps the calibration in use (a typo must not turn it off in the field).
  bool reload();

  std::uint64_t magSetAside() const { return correction_.magFit().setAside(); }
  std::uint64_t magTakenBack() const { return correction_.magFit().takenBack(); }

 private:
  void logMagFitChange();

  std::string path_;
  core::CalibratedImuStream correction_;
  bool mag_in_use_ = true;  // last state logged
};

}  // namespace headingd::daemon
