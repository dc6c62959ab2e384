#pragma once
// Offline smoothing for recordings analysed afterwards: the estimator run forward over the
// samples and, as a second filter, over the same samples reversed in time; each sample's two
// attitudes fused by their covariances (the two-filter smoother of Fraser & Potter 1969; for an
// EKF the same result as Rauch-Tung-Striebel to first order). Each filter is the causal
// estimator. The backward one carries on from the forward one's end (Estimator::reverseTime):
// it starts with the gyro bias, the heading and the field's references the whole recording
// taught. A fresh backward filter starts in whatever field the recording ends in, with nothing
// before it to show a magnet's field as a disturbance: its heading, fused, made the shared phone
// recordings with magnets on the path worse (iphone_magnets 3.40 -> 4.68 deg fitted;
// docs/smoother.md).
//
// Both filters have then seen the forward pass: their estimates are correlated by an amount
// nobody knows, and the fused covariance would count that pass twice. The tilt is fused by the
// two covariances as they are (the tilt forgets its past within its time constant); the
// backward heading counts with its variance inflated (kBackwardHeadingVarianceFactor, chosen
// for the worst recording, two_filter_smoother.cpp), and the heading variance stated is the
// smaller of the two, not the fused one.
//
// Time reversal (timeReversedSample): the reversed sample k stands for the original i = n-1-k at
// time t_last - t_i + t_first; a gyro sample is the mean rate over the interval that ends at
// its time, and the accelerometer's and magnetometer's are means over the same interval, so
// the interval (k-1, k] of the reversed recording is the original (i, i+1], whose rate is
// -gyro_{i+1} and whose vectors are accel_{i+1}, mag_{i+1}. That holds for vectors whose lag
// is the interval fraction f = 1/2 the estimator assumes; a sensor that is Δ later still (a
// phone's magnetometer, tens of ms) would be Δ early in reversed time, which no delay estimate
// can learn. So each vector is taken at the original time t_i + 2 f dt + Δ (interpolated),
// which the reversed recording's own lag f dt brings back to the body's t_i + f dt, with Δ the
// forward filter's learned lag less f dt (VectorShifts).
//
// The covariance of each attitude is taken about the NED axes: the EKF's tilt block about
// north and east (AttitudeEkf::tiltCovariance) and the heading sigma's square about down
// (heading_uncertainty.hpp); the two are independent by construction (the heading is the
// observer's, the tilt the EKF's). fuseAttitudes fuses all three.
#include <vector>

#include "headingd/core/estimator.hpp"

namespace headingd::core {

struct AttitudeEstimate {
  bool valid = false;
  Quat q_nb = Quat::Identity();
  Mat3 covariance_ned = Mat3::Identity();  // rad², about NED north, east, down
};

// The estimator's current attitude and its covariance: the EKF's tilt covariance, plus what a
// start in motion may leave (decaying with the tilt's time constant from the estimator's start
// or last gap), and the heading sigma's square.
AttitudeEstimate attitudeEstimate(const Estimator& estimator);

// Fuses two estimates of the same attitude: the difference as a turn about the NED axes,
// q_b = exp(δ) ⊗ q_a, weighed by K = P_a (P_a + P_b)⁻¹; P = P_a - K P_a. Either alone if the
// other is invalid.
AttitudeEstimate fuseAttitudes(const AttitudeEstimate& a, const AttitudeEstimate& b);

// The vectors' lags the reversal turns round (see the top): the estimator's interval fraction f
// and each sensor's lag beyond f dt.
struct VectorShifts {
  double lag_fraction = 0.5;
  double accel_extra_s = 0.0;
  double mag_extra_s = 0.0;
};

// Sample k of the recording reversed in time (see the top).
ImuSample timeReversedSample(const std::vector<ImuSample>& samples, std::size_t k, const VectorShifts& shifts = {});

// One estimate per sample (invalid where neither filter had one yet): the fused tilt and
// heading, the heading's variance the smaller of the two filters' (see the top). Memory: the samples and one estimate
// per sample (its quaternion and covariance, 112 bytes), nothing else. forward_counters, if given, gets the forward
// filter's counters (the samples it accepted, its still blocks, ...: what a replay of the same samples reports). start:
// the estimator both filters begin from, before any sample (with its parameters, and the reference field where one is
// known: Estimator::setReferenceField).
std::vector<AttitudeEstimate> smoothAttitudes(const std::vector<ImuSample>& samples, const Estimator& start,
                                              EstimatorCounters* forward_counters = nullptr);
inline std::vector<AttitudeEstimate> smoothAttitudes(const std::vector<ImuSample>& samples,
                                                     const EstimatorParams& params,
                                                     EstimatorCounters* forward_counters = nullptr) {
  return smoothAttitudes(samples, Estimator(params), forward_counters);
}

}  // namespace headingd::core
