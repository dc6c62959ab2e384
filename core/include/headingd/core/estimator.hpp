#pragma once
// The whole attitude and magnetic-heading estimator: pure and deterministic (same samples
// in, same estimates out), no I/O, no clocks. Per sample:
//   gate (timestamps, NaN) → gyro bias (still blocks) → EKF predict (Henriksson eq. 3.2-3.3)
//   → the specific force and the field turned by each sensor's learned delay
//     (vector_delay_estimator.hpp)
//   → accelerometer pre-filter (gyro_frame_low_pass.hpp) → quasi-static field and specific
//   force (MAGYQ §5, quasi_static_field.hpp) → d_k and R level
//   (eq. 3.1, 3.4, hysteresis) → EKF gravity update (eq. 3.5-3.8) → gyro bias (the update's
//   turn, in motion)
//   → magnetometer heading observer (eq. 4.2, with an integral term for the vertical rate
//   error) with the gyro-only heading restored at a
//   disturbance's onset (eq. 4.4, heading_corrections.hpp) → MAU against the WMM while the field
//   is clean, the QSF update while it is set aside but quasi-static (both off by default:
//   estimator_params.hpp) → the person's up axis learned
//   while walking (body_up_axis.hpp) → heading definition (§3.3) for that axis.
#include <cstdint>
#include <limits>

#include "headingd/core/accel_clipping.hpp"
#include "headingd/core/accel_disturbance.hpp"
#include "headingd/core/attitude_ekf.hpp"
#include "headingd/core/body_up_axis.hpp"
#include "headingd/core/estimator_params.hpp"
#include "headingd/core/gravity_residual.hpp"
#include "headingd/core/gyro_bias_estimator.hpp"
#include "headingd/core/gyro_frame_low_pass.hpp"
#include "headingd/core/heading_corrections.hpp"
#include "headingd/core/heading_definition.hpp"
#include "headingd/core/heading_uncertainty.hpp"
#include "headingd/core/imu_sample.hpp"
#include "headingd/core/mag_disturbance.hpp"
#include "headingd/core/magnetic_attitude_update.hpp"
#include "headingd/core/net_turn.hpp"
#include "headingd/core/quasi_static_field.hpp"
#include "headingd/core/quasi_static_field_update.hpp"
#include "headingd/core/rotated_field_update.hpp"
#include "headingd/core/sample_gate.hpp"
#include "headingd/core/turn_blended_low_pass.hpp"
#include "headingd/core/vector_delay_estimator.hpp"
#include "headingd/core/vertical_rate_error.hpp"

namespace headingd::core {

struct EstimatorOutput {
  bool valid = false;  // false until the first usable sample
  std::int64_t t_ns = 0;
  double dt_s = 0.0;  // period this sample was integrated over (0: not integrated)
  Quat q_nb = Quat::Identity();
  // zyx yaw: heading of the body x-axis from magnetic north. Roll and pitch are not computed
  // per sample (two more libm calls that most samples' readers never look at): eulerZyx(q_nb).
  double yaw_rad = 0.0;
  // Heading by the definition in use: ψ (x-axis) or, lying down, ψ_rd (§3.3: the heading of
  // the person's head, body_up_axis_s).
  double heading_rad = 0.0;
  bool heading_redefined = false;
  double head_height = 1.0;  // h(q) of eq. 3.12 for body_up_axis_s: 1 upright, 0 lying
  // The person's up axis in sensor axes (unit): sensor -z, the documented mounting, until it
  // has been learned while walking (body_up_learned; body_up_axis.hpp).
  Vec3 body_up_axis_s = kDocumentedHeadAxis;
  bool body_up_learned = false;
  MotionLevel motion_level = MotionLevel::kStanding;  // activity (§3.1's levels), reported only
  double accel_disturbance = 0.0;                     // d_k, (m/s²)²
  double gravity_noise_m_s2 = 0.0;  // σ of R_k in this sample's gravity update (gravity_residual.hpp)
  // An axis of this sample read the accelerometer's learned limit (accel_clipping.hpp).
  bool accel_clipped = false;
  Vec3 gyro_bias_rad_s = Vec3::Zero();
  // Added to the heading rate about NED down: the heading observer's integral term, the
  // vertical rate error the field has shown (rad/s; mag_rate_error_time_constant_s).
  double vertical_rate_correction_rad_s = 0.0;
  bool at_rest = false;
  bool mag_used = false;
  bool mag_disturbed = false;
  MagDisturbance mag_disturbance;   // which tests fired
  double mag_gain = 0.0;            // K of eq. 4.2 this sample
  double mag_innovation_rad = 0.0;  // ψ_mm - ψ_pred
  // How much older than the gyro's end of interval the field sample was taken to be (s): the
  // sample-interval fraction, or the magnetometer's learned delay, plus how long it was held
  // (vector_delay_estimator.hpp).
  double mag_lag_s = 0.0;
  // The same for the accelerometer's sample (without holds: the fraction or its learned delay).
  double accel_lag_s = 0.0;
  // 1-sigma of yaw_rad's error (heading_uncertainty.hpp); π/√3 while the heading is unknown.
  double heading_sigma_rad = 0.0;
  // The field / the specific force constant in the navigation frame (quasi_static_field.hpp).
  bool mag_quasi_static = false;
  bool accel_quasi_static = false;
  // This sample's field corrected the attitude: MAU against the WMM (the tilt), the QSF update
  // (the heading, while the observer sets the field aside).
  bool mau_applied = false;
  bool qsf_mag_update_applied = false;
  // A quasi-static field's change corrected the gyro's bias: MARU (the magnetic field), AGU (the
  // specific force) (rotated_field_update.hpp).
  bool maru_applied = false;
  bool agu_applied = false;
};

struct EstimatorCounters {
  SampleCounters samples;
  std::uint64_t bias_still_blocks = 0;     // still blocks that measured the gyro bias
  std::uint64_t mag_no_heading = 0;        // field too close to vertical for a heading
  std::uint64_t mag_disturbed = 0;         // samples with K = 0 for a disturbed field
  std::uint64_t mag_heading_restores = 0;  // disturbance onsets that restored ψ_g (eq. 4.4)
  std::uint64_t state_recoveries = 0;      // a non-finite state was replaced (never expected)
  std::uint64_t accel_clipped = 0;         // samples with an axis at the accelerometer's learned limit
  std::uint64_t qsf_mag_periods = 0;       // quasi-static field periods (quasi_static_field.hpp)
  std::uint64_t qsf_mag_ms = 0;            // time in them, milliseconds
  std::uint64_t qsf_accel_periods = 0;     // the same for the specific force
  std::uint64_t qsf_accel_ms = 0;
  // Field updates applied and rejected (quasi_static_field_update.hpp, magnetic_attitude_update.hpp).
  std::uint64_t qsf_mag_updates = 0;
  std::uint64_t qsf_mag_updates_rejected = 0;  // by the innovation gate
  std::uint64_t mau_updates = 0;
  std::uint64_t mau_updates_rejected = 0;    // by the innovation gate
  std::uint64_t mau_updates_unverified = 0;  // by the magnetic frame's check
  std::uint64_t maru_updates = 0;            // of the gyro bias (rotated_field_update.hpp)
  std::uint64_t maru_updates_rejected = 0;   // by the innovation gate
  std::uint64_t agu_updates = 0;
  std::uint64_t agu_updates_rejected = 0;
};

// Calls fn(name, value) for every counter, in a fixed order, with stable snake_case names:
// the one list headingd-replay prints and the daemon's STATUS reports.
template <class Fn>
void forEachCounter(const EstimatorCounters& c, Fn&& fn) {
  const SampleCounters& s = c.samples;
  fn("accepted", s.accepted);
  fn("gaps", s.gaps);
  fn("clock_jumps", s.clock_jumps);
  fn("duplicate_time", s.duplicate_time);
  fn("backwards_time", s.backwards_time);
  fn("non_finite", s.non_finite);
  fn("non_finite_mag", s.non_finite_mag);
  fn("out_of_range", s.out_of_range);
  fn("out_of_range_mag", s.out_of_range_mag);
  fn("bias_still_blocks", c.bias_still_blocks);
  fn("mag_no_heading", c.mag_no_heading);
  fn("mag_disturbed", c.mag_disturbed);
  fn("mag_heading_restores", c.mag_heading_restores);
  fn("state_recoveries", c.state_recoveries);
  fn("accel_clipped", c.accel_clipped);
  fn("qsf_mag_periods", c.qsf_mag_periods);
  fn("qsf_mag_ms", c.qsf_mag_ms);
  fn("qsf_accel_periods", c.qsf_accel_periods);
  fn("qsf_accel_ms", c.qsf_accel_ms);
  fn("qsf_mag_updates", c.qsf_mag_updates);
  fn("qsf_mag_updates_rejected", c.qsf_mag_updates_rejected);
  fn("mau_updates", c.mau_updates);
  fn("mau_updates_rejected", c.mau_updates_rejected);
  fn("mau_updates_unverified", c.mau_updates_unverified);
  fn("maru_updates", c.maru_updates);
  fn("maru_updates_rejected", c.maru_updates_rejected);
  fn("agu_updates", c.agu_updates);
  fn("agu_updates_rejected", c.agu_updates_rejected);
}

// A value: a copy carries on independently from the same state (its parts hold their own
// copies of the parameters, never references into this object).
class Estimator {
 public:
  explicit Estimator(const EstimatorParams& params = {});

  // Processes one sample and returns what the gate decided. A skipped sample leaves the
  // output as it was.
  SampleVerdict process(const ImuSample& sample);

  const EstimatorOutput& output() const { return out_; }
  EstimatorCounters counters() const;
  const EstimatorParams& params() const { return p_; }
  const AttitudeEkf& ekf() const { return ekf_; }
  const HeadingUncertainty& headingUncertainty() const { return heading_uncertainty_; }
  const VectorDelayEstimator& magDelay() const { return mag_delay_; }
  const MagDisturbanceDetector& magDisturbance() const { return mag_disturbance_; }
  const VectorDelayEstimator& accelDelay() const { return accel_delay_; }
  const GyroBiasEstimator& gyroBias() const { return bias_; }
  // Time since the tilt started afresh (the first sample, or after a gap).
  double tiltSeconds() const { return tilt_seconds_; }
  const QuasiStaticFieldDetector& magQuasiStatic() const { return qsf_mag_; }
  const QuasiStaticFieldDetector& accelQuasiStatic() const { return qsf_accel_; }

  // Time runs backwards from the next sample on (the offline smoother's second filter carries on
  // from the first: two_filter_smoother.hpp). The next sample opens a new time axis without
  // starting afresh: the attitude, its covariance, the heading's sigma, what the field's
  // disturbance tests learned and the vectors' low-passes carry on; the gyro's bias and the
  // observer's vertical rate turn sign; the delays (which the smoother's reversed samples are
  // shifted by), the quasi-static periods and the observer's correction sums start afresh.
  void reverseTime();

  // The Earth's field where the device is (WMM at the GPS position): enables the absolute
  // strength and dip tests of the disturbance detection (Henriksson §4.2).
  void setReferenceField(double field_norm_uT, double inclination_rad) {
    mag_disturbance_.setReference(field_norm_uT, inclination_rad);
    mau_.setReference(field_norm_uT, inclination_rad);
    vertical_rate_error_.referenceUpdated();
  }

 private:
  void initialise(const ImuSample& s, bool mag_usable);
  void step(const ImuSample& s, double dt_s, bool mag_usable);
  // turn_rate_rad_s: |ω| of this sample, bias taken off (the integral term learns only below
  // mag_rate_error_max_turn_rad_s).
  void correctHeading(const Vec3& mag_uT, double field_period_s, double turn_rate_rad_s);
  void restoreGyroHeading();
  // MAU and the QSF update (magnetic_attitude_update.hpp, quasi_static_field_update.hpp) after
  // the observer has seen this field sample: filtered_uT what it saw, sample_uT the sample.
  void applyFieldUpdates(const Vec3& filtered_uT, const Vec3& sample_uT, double field_period_s, bool new_field_sample);
  // Whether the background gyro-only heading of eq. 4.4 is expected to be better than a clean
  // field's: a restore is worth it only then.
  bool gyroHeadingBeatsAField() const;
  // The accelerometer's clipped axes this sample (accel_clipping.hpp) through the same
  // gyro-frame low-pass as its readings (turning: its blend weight, SteadyTurnWeight): their
  // share in the gravity measurement, per axis (signed), in the current sensor axes. Zero
  // while clipping is not looked for.
  // A vector sample turned to the end of the interval by its lag (written to *lag_s): the
  // interval fraction plus its held time, or the delay learned for it where that is used.
  Vec3 turnedToNow(VectorDelayEstimator& delay, const Vec3& sample, const Vec3& gyro, const Vec3& down_s, bool clean,
                   double dt_s, double* lag_s);
  Vec3 trackClipping(const Vec3& accel_m_s2, const Quat& increment, double dt_s, double turning);
  void publish(std::int64_t t_ns);
  // The heading uncertainty's step: the rate error the bias filter allows about the vertical.
  void predictHeadingUncertainty(double dt_s);
  // The quasi-static field tests of this sample (a held field sample is not a new one). Returns
  // whether the field's sample was a new one.
  bool detectQuasiStaticFields(const ImuSample& s, const Quat& increment, const Vec3& accel_now, const Vec3& mag_now,
                               bool mag_usable, double dt_s);

  EstimatorParams p_;
  SampleGate gate_;
  GyroBiasEstimator bias_;
  AttitudeEkf ekf_;
  AccelDisturbanceLevel disturbance_;
  TurnBlendedLowPass accel_prefilter_;
  AccelClipDetector accel_clipping_;
  // The clipped axes (±1 per axis, accel_clipping.hpp) through the same low-pass as the
  // accelerometer: the direction along which its output is short, and the share of clipped
  // samples in it.
  TurnBlendedLowPass clipped_share_;
  bool clipped_share_started_ = false;
  SteadyTurnWeight steady_turn_;  // how far into a bend: the two low-passes' blend
  GravityResidual gravity_residual_;
  GyroFrameLowPass mag_prefilter_;
  double mag_sample_dt_s_ = 0.0;  // time since the last field sample (a slower magnetometer)
  MotionLevelSelector motion_;
  HeadingCorrectionLog heading_corrections_;
  BodyUpAxis body_up_;
  HeadingDefinitionSelector heading_definition_;
  MagDisturbanceDetector mag_disturbance_;
  HeadingUncertainty heading_uncertainty_;
  NetTurn attitude_net_turn_;              // how far the attitude has moved, for heading_uncertainty_
  VectorDelayEstimator mag_delay_;         // the magnetometer's delay against the gyro
  VectorDelayEstimator accel_delay_;       // the accelerometer's
  double mag_seconds_ = 0.0;               // time since the first usable field sample
  VerticalRateError vertical_rate_error_;  // the observer's integral term
  double tilt_seconds_ = 0.0;              // time since the tilt started afresh (start-up, gap)
  GyroFrame qsf_frame_;                    // the frame both detectors carry their samples into
  QuasiStaticFieldDetector qsf_mag_;
  QuasiStaticFieldDetector qsf_accel_;
  Vec3 qsf_last_mag_uT_ = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  // to tell a held sample
  double qsf_mag_dt_s_ = 0.0;                                                        // since the last new field sample
  double qsf_field_interval_s_ = 0.0;  // between the last two new field samples
  QuasiStaticFieldUpdate qsf_mag_update_;
  MagneticAttitudeUpdate mau_;
  RotatedFieldUpdate maru_;
  RotatedFieldUpdate agu_;
  bool initialised_ = false;
  bool heading_aligned_ = false;
  EstimatorOutput out_;
  std::uint64_t mag_no_heading_ = 0;
  std::uint64_t mag_disturbed_ = 0;
  std::uint64_t mag_heading_restores_ = 0;
  double mag_disturbed_seconds_ = 0.0;
  std::uint64_t state_recoveries_ = 0;
  std::uint64_t accel_clipped_ = 0;
};

// Attitude from one accelerometer (tilt) and, if given, magnetometer (heading) sample.
Quat attitudeFromGravityAndField(const Vec3& accel_m_s2, const Vec3* mag_uT);

}  // namespace headingd::core
