#include "headingd/core/sample_gate.hpp"

namespace headingd::core {

const char* sampleVerdictName(SampleVerdict v) {
  switch (v) {
    case SampleVerdict::kAccepted: return "accepted";
    case SampleVerdict::kFirst: return "first";
    case SampleVerdict::kGap: return "gap";
    case SampleVerdict::kClockJump: return "clock_jump";
    case SampleVerdict::kDuplicateTime: return "duplicate_time";
    case SampleVerdict::kBackwardsTime: return "backwards_time";
    case SampleVerdict::kNonFinite: return "non_finite";
    case SampleVerdict::kOutOfRange: return "out_of_range";
  }
  return "unknown";
}

SampleVerdict SampleGate::check(const ImuSample& s, double* dt_s, bool* mag_usable) {
  *dt_s = 0.0;
  *mag_usable = s.has_mag && s.mag_uT.allFinite();
  if (!s.gyro_rad_s.allFinite() || !s.accel_m_s2.allFinite()) {
    ++counters_.non_finite;
    return SampleVerdict::kNonFinite;
  }
  // Per-axis bounds (lpNorm<Infinity>) so that no square is taken of a corrupt value.
  if (s.gyro_rad_s.lpNorm<Eigen::Infinity>() > limits_.max_gyro_rad_s ||
      s.accel_m_s2.lpNorm<Eigen::Infinity>() > limits_.max_accel_m_s2) {
    ++counters_.out_of_range;
    return SampleVerdict::kOutOfRange;
  }
  if (s.has_mag && !*mag_usable) {
    ++counters_.non_finite_mag;
  } else if (*mag_usable && s.mag_uT.lpNorm<Eigen::Infinity>() > limits_.max_mag_uT) {
    *mag_usable = false;
    ++counters_.out_of_range_mag;
  }
  if (!started_) {
    started_ = true;
    last_t_ns_ = s.t_ns;
    return SampleVerdict::kFirst;
  }
  // A corrupt timestamp can be anywhere in the int64 range, and the difference of two such
  // must not wrap around into a plausible step: an overflow is a jump, whichever way.
  std::int64_t step_ns = 0;
  if (__builtin_sub_overflow(s.t_ns, last_t_ns_, &step_ns)) {
    const bool backwards = s.t_ns < last_t_ns_;
    last_t_ns_ = s.t_ns;
    ++(backwards ? counters_.clock_jumps : counters_.gaps);
    return backwards ? SampleVerdict::kClockJump : SampleVerdict::kGap;
  }
  if (step_ns == 0) {
    ++counters_.duplicate_time;
    return SampleVerdict::kDuplicateTime;
  }
  if (step_ns < 0 && -step_ns <= max_gap_ns_) {
    ++counters_.backwards_time;
    return SampleVerdict::kBackwardsTime;
  }
  last_t_ns_ = s.t_ns;
  if (step_ns < 0) {
    ++counters_.clock_jumps;
    return SampleVerdict::kClockJump;
  }
  if (step_ns > max_gap_ns_) {
    ++counters_.gaps;
    return SampleVerdict::kGap;
  }
  ++counters_.accepted;
  *dt_s = static_cast<double>(step_ns) * 1e-9;
  return SampleVerdict::kAccepted;
}

}  // namespace headingd::core
