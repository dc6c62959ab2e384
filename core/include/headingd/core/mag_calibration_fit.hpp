#pragma once
// Whether a magnetometer calibration still describes the sensor (calibrated_imu_stream.hpp
// applies a calibration sample by sample with this check).
//
// A calibration made with a magnet, a battery or a bracket next to the sensor is wrong once
// that is taken away (BROAD trials 32-36: the magnet is on for part of the recording). The
// test needs no reference: a good calibration makes the field's strength independent of
// the orientation, so as the sensor turns its strength stays steady while the raw one
// swings; with the distortion gone it is the other way round. Both strengths are compared
// by their relative fluctuation about a low-pass (a magnitude-only version of the norm
// test of Kok & Schön 2016 §6.1 and Henriksson 2013 eq. 4.5). At rest nothing fluctuates,
// so the low-passed strengths are also compared with the field strength the calibration
// was scaled to: a calibration that puts a still sensor's field 15 % off while the raw
// reading is close is set aside too. A field that disturbs both alike (steel nearby)
// leaves the choice alone.
#include <cstdint>

#include "headingd/core/imu_calibration.hpp"
#include "headingd/core/imu_sample.hpp"
#include "headingd/core/low_pass.hpp"

namespace headingd::core {

struct MagCalibrationFitParams {
  // Low-pass of the strength and of its squared relative deviation from that low-pass.
  double time_constant_s = 3.0;
  // One reading fits "clearly better" when its fluctuation variance is this many times
  // smaller than the other's ...
  double variance_ratio = 4.0;
  // ... and the other fluctuates by more than this (relative RMS, 0.08 = 8 %): sensor noise
  // and slow turns never switch.
  double min_relative_fluctuation = 0.08;
  // Strength test (only when the calibration states its field strength): the reading in
  // use is this far off (relative) ...
  double max_relative_strength_error = 0.15;
  // ... and the other at most this fraction of that.
  double strength_error_ratio = 0.33;
  // The better fit must hold this long before the choice changes.
  double confirm_s = 2.0;
};

class MagCalibrationFit {
 public:
  // expected_norm_uT: the field strength the calibration was scaled to (MagCalibration::
  // field_norm_uT); 0 = not stated, then only the fluctuation test is made.
  explicit MagCalibrationFit(const MagCalibrationFitParams& p = {}, double expected_norm_uT = 0.0)
      : p_(p), expected_norm_uT_(expected_norm_uT), raw_(p.time_constant_s), calibrated_(p.time_constant_s) {}

  // Feeds one pair of readings (µT) dt_s after the previous one; returns whether the
  // calibrated reading is the one to use.
  bool update(const Vec3& raw_uT, const Vec3& calibrated_uT, double dt_s);

  bool calibrationInUse() const { return calibrated_in_use_; }
  std::uint64_t setAside() const { return set_aside_; }    // calibrated → raw switches
  std::uint64_t takenBack() const { return taken_back_; }  // raw → calibrated switches
  // For diagnostics: the low-passed strengths (µT) and their relative RMS fluctuation.
  double rawStrength() const { return raw_.mean.value(); }
  double calibratedStrength() const { return calibrated_.mean.value(); }
  double rawFluctuation() const;
  double calibratedFluctuation() const;

 private:
  // A strength's low-pass and the low-pass of its squared relative deviation from it.
  struct Strength {
    explicit Strength(double time_constant_s) : mean(time_constant_s), variance(time_constant_s) {}
    LowPass<double> mean;
    LowPass<double> variance;
    void update(double norm, double dt_s);
  };
  bool fitsBetter(const Strength& other, const Strength& in_use) const;
  MagCalibrationFitParams p_;
  double expected_norm_uT_;
  Strength raw_, calibrated_;
  bool calibrated_in_use_ = true;
  double other_better_s_ = 0.0;  // how long the reading not in use has fitted clearly better
  std::uint64_t set_aside_ = 0;
  std::uint64_t taken_back_ = 0;
};

}  // namespace headingd::core
