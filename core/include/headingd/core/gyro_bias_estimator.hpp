#pragma once
// Gyroscope bias: a Kalman filter of the bias in sensor axes (a walk plus an instability, six
// states: drifting_bias.hpp) with two kinds of measurement, so that every source of
// information about the bias counts and none can lock a wrong estimate in.
//
//  - At rest (rest_detector.hpp) the mean rate ω̄ is the bias (Earth's 15°/h is far below
//    the noise of body-worn MEMS gyros): measurement y = ω̄, H = I. A block far outside the
//    joint covariance (NIS above χ²(3)'s 99 % point) counts with the spread it shows, not
//    with its own covariance: a hand's slow drift can fool a block's turn measurement. A
//    second such block that agrees with the first says the bias changed: then it is learned
//    at once. When a motion is found just after a block, the rest detector cuts the block
//    back (or withdraws it): the estimate is then taken back to what it was before the block
//    and the cut block counted in its place.
//  - In motion the accelerometer says what the gyro got wrong about tilt: a bias error
//    β = b - b̂ turns the predicted attitude by R β per second (R: sensor to NED), and the
//    EKF's gravity update turns it back. Over the time the gravity filters average (their lag
//    is taken into R by low-passing it), the update's turn about NED north and east per
//    second is -(R β)_h: measurement y = -turn/dt, H = R̄_h (the horizontal rows of the
//    low-passed R). The vertical part of the bias is not seen this way; the heading observer's
//    integral term (estimator.hpp) takes the rate error it causes out while the field is clean.
//    How much a window of turns says comes from the data, not from an assumption: the turns
//    carry everything the motion does to the tilt, correlated over the tilt's time constant
//    τ_c. Their spread is measured on the turns low-passed with τ_c (variance V), and a
//    window of length T counts as W = V · 2τ_c / T (the variance of a long mean of a process
//    of that correlation time, spread over its windows), never less than the windows' own
//    spread; nothing is measured until the spread has been seen for 3 τ_c. Violent motion
//    then says less about the bias.
//    And only while the attitude stays near its low-passed value
//    (bias_motion_max_attitude_change): while the sensor turns on, the low-passed R is not the
//    turns' real lag, the turns' mean is not the bias, and on the phone recordings (no rest,
//    the phone always turning) the update learned 20-100 mrad/s that were not there;
//    estimator_params.hpp gives the figures.
//    The turns answer a changed estimate only through the tilt's lag τ_c, so the update is a
//    feedback loop; its gain is bounded so that it follows no faster than with time constant
//    bias_motion_min_tilt_lags × τ_c (damping ratio 1/√2 at 2), also in the first windows,
//    when the uncertainty of knowing nothing would let them set the bias at once.
// The same structure carries VQF's motion bias estimation (Laidig & Seel 2023); MAGYQ
// (Renaudin & Combettes 2014, §3) keeps the gyro bias as filter states for the same reason.
//
// The bias drifts as drifting_bias.hpp says: a random walk of bias_walk_rad_s_per_sqrt_s plus
// the gyro's bias instability (bias_instability_rad_s over bias_instability_time_s).
// Every coefficient comes from a time: with the walk, a measurement process of noise
// density N gives, in steady state, a filter that follows with time constant τ = √(N / walk²).
// So N = τ² walk² for the rest (bias_time_constant_s) and for the motion measurement
// (bias_motion_time_constant_s), and a sample of period dt is a measurement of variance N / dt:
// the filter behaves the same at any sample rate.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "headingd/core/drifting_bias.hpp"
#include "headingd/core/estimator_params.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/measurement_model.hpp"
#include "headingd/core/quaternion.hpp"
#include "headingd/core/rest_detector.hpp"

namespace headingd::core {

class GyroBiasEstimator {
 public:
  explicit GyroBiasEstimator(const EstimatorParams& p);

  // Per sample, before the attitude filter: the bias wanders, and at rest ω̄ measures it.
  // mag_uT: the field sample, or nullptr when there is none or it is disturbed (rest test).
  // Returns the bias to take off this sample's rate.
  const Vec3& update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* mag_uT, double dt_s);

  // After the gravity update of each sample: that update turned the attitude q_nb by turn_rad
  // about NED north and east. `measures_bias`: the turn is a measurement of the bias (the
  // tilt has settled from its start, the sensor is not at rest). The turns are summed over
  // windows of 0.1 s, and a window whose every sample measures makes one update: the same
  // information as per sample, a tenth of the cost or less. (The same weight whatever the
  // accelerometer's disturbance: a more disturbed accelerometer gets a smaller gain in the
  // EKF, so the turns it causes are no noisier.)
  void addTiltCorrection(const Eigen::Vector2d& turn_rad, const Quat& q_nb, double dt_s, bool measures_bias);

  // A measurement model's linearisation (measurement_model.hpp) whose prediction depends on the
  // gyro's bias, as MARU's and AGU's (rotated_field_update.hpp): its gyro-bias columns are H, its
  // residual the innovation. One whose normalised innovation squared exceeds max_nis changes
  // nothing. Returns whether it was applied.
  bool addMeasurement(const Linearised<3>& measurement, double max_nis);

  // Time runs backwards from here on (the offline smoother's second filter, carrying on from the
  // first): the gyro reads -ω, so the bias turns sign; a still block in progress and the last
  // block's undo are dropped, and the in-motion windows start afresh.
  void reverseTime();

  const Vec3& bias() const { return bias_; }
  bool atRest() const { return rest_.atRest(); }
  // Seconds of still blocks the estimate has seen (0 until the first), and how many.
  double restSeconds() const { return rest_seconds_; }
  std::uint64_t stillBlocks() const { return still_blocks_; }
  // Standard deviation of each component (rad/s), from the filter's covariance.
  Vec3 sigma() const { return P_.diagonal().cwiseSqrt(); }
  const Mat3& covariance() const { return P_; }

 private:
  // After every change of state_: its bias and covariance (what bias() and covariance() give),
  // kept at most bias_max_rad_s.
  void settle();

  // The spread of one component of the turns per second (see the top): low-passed with the
  // correlation time τ_c, then their variance about their own mean over 10 τ_c (running
  // means until then), and the variance of the turns themselves.
  struct TurnSpread {
    explicit TurnSpread(double correlation_time_s);
    void add(double turn_rate_rad_s, double window_s);
    // W of a window of length window_s; +∞ until the spread has been seen for 3 τ_c.
    double windowVariance(double window_s) const;
    double correlation_time_s;
    LowPass<double> correlated;
    double elapsed_s = 0.0;
    double mean = 0.0, variance = 0.0;          // of the low-passed turns
    double raw_mean = 0.0, raw_variance = 0.0;  // of the turns themselves
  };

  // A copy, not a reference to the owner's parameters: the Estimator that holds this one
  // stays an ordinary value (copied or moved, it carries on from the same state), where a
  // reference would keep pointing into the object it was copied from. A few hundred bytes.
  EstimatorParams p_;
  RestDetector rest_;
  DriftingBias state_;
  Vec3 bias_ = Vec3::Zero();  // of state_
  Mat3 P_;                    // of state_
  void updateFromWindow();

  LowPass<Eigen::Matrix<double, 2, 3>> horizontal_rows_;  // R̄_h, updated once a window
  std::array<TurnSpread, 2> spread_;                      // about north, about east
  double window_s_ = 0.0;
  double measuring_s_ = 0.0;     // of the window, the time whose turns measure the bias
  double since_update_s_ = 0.0;  // since the last in-motion update (see updateFromWindow)
  Eigen::Vector2d window_turn_rad_ = Eigen::Vector2d::Zero();
  double rest_seconds_ = 0.0;
  std::uint64_t still_blocks_ = 0;
  // The last still block, when it was an outlier (its covariance: the W it was weighed with).
  RestBlock previous_outlier_;
  bool has_previous_outlier_ = false;
  // The rest part of the state before the last still block, for when the rest detector
  // revises or withdraws that block (a motion found just after it: rest_detector.hpp).
  struct StateBeforeBlock {
    DriftingBias state;
    double rest_seconds = 0.0;
    std::uint64_t still_blocks = 0;
    RestBlock previous_outlier;
    bool has_previous_outlier = false;
  };
  StateBeforeBlock before_last_block_;
  void restoreBeforeLastBlock();
};

}  // namespace headingd::core
