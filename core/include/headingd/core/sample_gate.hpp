#pragma once
// Decides whether a sample can be used and over which period. The sample
// period always comes from the timestamps, never from a nominal rate.
#include <cstdint>

#include "headingd/core/imu_sample.hpp"

namespace headingd::core {

enum class SampleVerdict {
  kAccepted,       // use it, integrating the gyro over the returned period
  kFirst,          // first usable sample: starts the time base, nothing to integrate yet
  kGap,            // time jumped forward by more than the gap limit: restart the time base
  kClockJump,      // time jumped backwards by more than the gap limit: restart the time base
  kDuplicateTime,  // same timestamp as the last sample: skipped
  kBackwardsTime,  // slightly older than the last sample: skipped
  kNonFinite,      // NaN/Inf in gyro or accelerometer: skipped
  kOutOfRange,     // a gyro or accelerometer reading no sensor of this kind can give: skipped
};

const char* sampleVerdictName(SampleVerdict v);

// True for the verdicts under which the estimator used the sample (it moved the estimate's
// time on); false for those it skipped.
constexpr bool sampleUsed(SampleVerdict v) {
  return v == SampleVerdict::kAccepted || v == SampleVerdict::kFirst || v == SampleVerdict::kGap ||
         v == SampleVerdict::kClockJump;
}

struct SampleCounters {
  std::uint64_t accepted = 0;
  std::uint64_t gaps = 0;
  std::uint64_t clock_jumps = 0;
  std::uint64_t duplicate_time = 0;
  std::uint64_t backwards_time = 0;
  std::uint64_t non_finite = 0;
  std::uint64_t non_finite_mag = 0;  // magnetometer dropped, gyro and accelerometer used
  std::uint64_t out_of_range = 0;
  std::uint64_t out_of_range_mag = 0;  // magnetometer dropped, gyro and accelerometer used
};

// Largest readings a sample may hold. Beyond them a value is corrupt, not a measurement
// (and squares of values near 1e154 would overflow to infinity in the filters).
struct SampleLimits {
  double max_gyro_rad_s;
  double max_accel_m_s2;
  double max_mag_uT;
};

class SampleGate {
 public:
  SampleGate(double max_gap_s, const SampleLimits& limits)
      : max_gap_ns_(static_cast<std::int64_t>(max_gap_s * 1e9)), limits_(limits) {}
  explicit SampleGate(double max_gap_s) : SampleGate(max_gap_s, SampleLimits{1e3, 1e4, 1e5}) {}

  // Returns the verdict; for kAccepted, *dt_s is the period since the last used sample.
  // A sample whose magnetometer alone is non-finite is accepted with *mag_usable = false.
  SampleVerdict check(const ImuSample& s, double* dt_s, bool* mag_usable);
  const SampleCounters& counters() const { return counters_; }

 private:
  std::int64_t max_gap_ns_;
  SampleLimits limits_;
  std::int64_t last_t_ns_ = 0;
  bool started_ = false;
  SampleCounters counters_;
};

}  // namespace headingd::core
