#include "headingd/core/two_filter_smoother.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace headingd::core {
namespace {

// The turn δ (rotation vector, NED axes) with q_to = exp(δ) ⊗ q_from, the shorter way round.
Vec3 turnBetween(const Quat& q_from, const Quat& q_to) {
  Quat d = q_to * q_from.conjugate();
  if (d.w() < 0.0) d.coeffs() = -d.coeffs();
  const Eigen::AngleAxisd angle_axis(d);
  return angle_axis.angle() * angle_axis.axis();
}

Quat turnedBy(const Vec3& turn_ned, const Quat& q) {
  const double angle = turn_ned.norm();
  if (angle == 0.0) return q;
  return (Quat(Eigen::AngleAxisd(angle, turn_ned / angle)) * q).normalized();
}

// What a tilt started from one sample in motion may be off by (estimator.hpp: tens of degrees
// at the level of running), decaying with the tilt's time constant (tiltTimeConstantS): the
// EKF's covariance does not hold it (its start-up value is 6 deg, and the running-mean start
// of the first time constant moves the tilt without it). A simulated phone swung in the hand
// and smoothed had its last 3 s off by 10 deg without this: the backward filter's start.
constexpr double kStartTiltSigmaRad = 0.5;

// The backward filter's heading counts with its variance times this (header): it has seen the
// forward pass (the two are correlated by an unknown amount), and where it meets a disturbance
// without the history the forward filter had, its sigma is the less honest. Chosen on the 53
// shared recordings and the simulator's 51 classes at 100 Hz (docs/smoother.md): 1, 2, 4, 8 and
// 16 lose at most 3.87, 2.24, 0.94 and 0.23° on one recording against the causal filter (the
// texting Nexus 5 walking past magnets; 1 even more), 16 no more than the tilt alone (0.23°, a
// phoning iPhone 5), and in the simulator +0.05° at worst against the tilt alone's +0.06°.
constexpr double kBackwardHeadingVarianceFactor = 16.0;

// The vector `member` at the original time t_i + after_s, linear between the samples around it
// (the first or last sample beyond the recording's ends).
Vec3 vectorAt(const std::vector<ImuSample>& samples, std::size_t i, double after_s, Vec3 ImuSample::*member) {
  const double t_s = 1e-9 * static_cast<double>(samples[i].t_ns) + after_s;
  const auto seconds = [&](std::size_t j) { return 1e-9 * static_cast<double>(samples[j].t_ns); };
  std::size_t j = i;
  while (j + 1 < samples.size() && seconds(j + 1) <= t_s) ++j;
  while (j > 0 && seconds(j) > t_s) --j;
  if (j + 1 >= samples.size() || seconds(j) > t_s) return samples[j].*member;
  const double w = (t_s - seconds(j)) / (seconds(j + 1) - seconds(j));
  return (1.0 - w) * samples[j].*member + w * samples[j + 1].*member;
}

}  // namespace

AttitudeEstimate attitudeEstimate(const Estimator& estimator) {
  AttitudeEstimate e;
  const EstimatorOutput& o = estimator.output();
  e.valid = o.valid;
  if (!o.valid) return e;
  e.q_nb = o.q_nb;
  e.covariance_ned.setZero();
  e.covariance_ned.topLeftCorner<2, 2>() = estimator.ekf().tiltCovariance();
  const double start_sigma =
      kStartTiltSigmaRad * std::exp(-estimator.tiltSeconds() / tiltTimeConstantS(estimator.params()));
  e.covariance_ned.topLeftCorner<2, 2>().diagonal().array() += start_sigma * start_sigma;
  e.covariance_ned(2, 2) = o.heading_sigma_rad * o.heading_sigma_rad;
  return e;
}

AttitudeEstimate fuseAttitudes(const AttitudeEstimate& a, const AttitudeEstimate& b) {
  if (!a.valid) return b;
  if (!b.valid) return a;
  const Mat3 gain = a.covariance_ned * (a.covariance_ned + b.covariance_ned).inverse();
  AttitudeEstimate fused;
  fused.valid = true;
  fused.q_nb = turnedBy(gain * turnBetween(a.q_nb, b.q_nb), a.q_nb);
  const Mat3 P = a.covariance_ned - gain * a.covariance_ned;
  fused.covariance_ned = 0.5 * (P + P.transpose());
  return fused;
}

ImuSample timeReversedSample(const std::vector<ImuSample>& samples, std::size_t k, const VectorShifts& shifts) {
  const std::size_t n = samples.size();
  const std::size_t i = n - 1 - k;
  // The interval (i, i+1]; the reversed recording's first sample (i = n-1) only starts it, and
  // the original's last readings stand in for the interval after it that there is none of.
  const std::size_t next = i + 1 < n ? i + 1 : i;
  ImuSample s = samples[next];
  s.t_ns = samples.back().t_ns - samples[i].t_ns + samples.front().t_ns;
  s.gyro_rad_s = -s.gyro_rad_s;
  const double dt_s = 1e-9 * static_cast<double>(samples[next].t_ns - samples[i].t_ns);
  const double base_s = 2.0 * shifts.lag_fraction * dt_s;
  if (shifts.accel_extra_s != 0.0 || base_s != dt_s) {
    s.accel_m_s2 = vectorAt(samples, i, base_s + shifts.accel_extra_s, &ImuSample::accel_m_s2);
  }
  if (shifts.mag_extra_s != 0.0 || base_s != dt_s) {
    s.mag_uT = vectorAt(samples, i, base_s + shifts.mag_extra_s, &ImuSample::mag_uT);
  }
  return s;
}

std::vector<AttitudeEstimate> smoothAttitudes(const std::vector<ImuSample>& samples, const Estimator& start,
                                              EstimatorCounters* forward_counters) {
  const EstimatorParams& params = start.params();
  std::vector<AttitudeEstimate> forward;
  forward.reserve(samples.size());
  Estimator estimator = start;
  for (const ImuSample& s : samples) {
    estimator.process(s);
    forward.push_back(attitudeEstimate(estimator));
  }
  if (forward_counters != nullptr) *forward_counters = estimator.counters();
  // The lags the forward filter found, beyond the interval fraction (see the header).
  const EstimatorOutput& end = estimator.output();
  VectorShifts shifts;
  shifts.lag_fraction = params.vector_sample_lag_fraction;
  if (samples.size() > 1) {
    const double fraction_s = params.vector_sample_lag_fraction * 1e-9 *
                              static_cast<double>(samples.back().t_ns - samples[samples.size() - 2].t_ns);
    shifts.accel_extra_s = end.accel_lag_s - fraction_s;
    shifts.mag_extra_s = end.mag_lag_s - estimator.magDelay().heldS() - fraction_s;
  }
  // The backward filter carries on from the forward one's end with time reversed
  // (Estimator::reverseTime): it starts with everything the forward one learned (the gyro bias,
  // the field's references, the heading), where a fresh filter would start in whatever field the
  // recording ends in with nothing to show a magnet's field as a disturbance (see the header).
  // Its estimates are fused as they come, in place of the forward ones.
  Estimator backward = estimator;
  backward.reverseTime();
  for (std::size_t k = 0; k < samples.size(); ++k) {
    backward.process(timeReversedSample(samples, k, shifts));
    AttitudeEstimate& out = forward[samples.size() - 1 - k];
    const bool forward_valid = out.valid;
    const double forward_heading_variance = out.covariance_ned(2, 2);
    AttitudeEstimate from_the_end = attitudeEstimate(backward);
    from_the_end.covariance_ned(2, 2) *= kBackwardHeadingVarianceFactor;
    out = fuseAttitudes(out, from_the_end);
    // Both filters have seen the forward pass, so the fused heading variance would count it
    // twice: the smaller of the two is stated instead.
    if (forward_valid && from_the_end.valid) {
      out.covariance_ned(2, 2) = std::min(forward_heading_variance, from_the_end.covariance_ned(2, 2));
    }
  }
  return forward;
}

}  // namespace headingd::core
