#include "headingd/core/estimator.hpp"

#include <algorithm>
#include <cmath>

#include "headingd/core/mag_heading_observer.hpp"

namespace headingd::core {
namespace {

// The accelerometer's delay is regressed over chains at least this long: every row is a
// fresh sample, and over one row a noisy gyro's change is mostly noise, which pulls the
// estimate towards zero. Simulated slow rotation, accelerometer 30 ms late (35 ms with the
// interval mean), 3 seeds of phone / consumer / mems: 0.1 s learns 10-19 ms, 0.3 s 14-32,
// 0.5 s 22-34, 1 s 29-33 (and 31.8-36.5 once the rate at the chain's start is turned into
// its end's axes), 2 s 22-32 (with a larger σ).
constexpr double kAccelDelayMinSpanS = 1.0;
// ... and only from readings whose norm is within this share of gravity: a turned gravity.
// 2 / 5 / 10 / 20 %: with a 30 ms lag over the 84 classes -0.27 / -0.21 / -0.15 / -0.15°
// summed, none worse than +0.01; 5 % also learns on an accelerometer whose scale is a few
// per cent off, where 2 % would never learn.
constexpr double kAccelDelayMaxNormDeviation = 0.05;

// The attitude's mean for the heading sigma's calibration residual (net_turn.hpp): over 2 s a
// stride's sway and a swung phone's swing move the mean by a fraction of a degree (a swing of
// ±45° once a second by 3.6°), below the step; a turn moves it by its angle. Over seeds 1-30
// of the 84 simulator classes (below 90 / within / above 97 % of heading errors within 2
// sigma) 1 s and 0.05 rad give 4 / 18 / 62, 2 s and 0.1 rad 4 / 16 / 64, 4 s and 0.2 rad
// 4 / 16 / 64, the classes below 90 % within 0.2 points of each other.
constexpr double kAttitudeMeanS = 2.0;
constexpr double kAttitudeStepRad = 0.1;

// A start from a measured tilt is good to a few degrees: P ~ (0.05)² per component instead
// of Algorithm 2's 1000·I, which would let the first accelerometer samples throw it around.
const Mat4 kStartupCovariance = 0.05 * 0.05 * Mat4::Identity();

// MARU's and AGU's least noise per axis of a sample (rotated_field_update.hpp): a sensor's
// resolution leaves about a count/√12 even where a window's samples happen to repeat
// (magnetometers 0.06-0.3 µT per count, accelerometers 0.6-2.4 mg).
constexpr double kMinMagSampleNoiseUT = 0.05;
constexpr double kMinAccelSampleNoiseM_S2 = 0.005;

// The gravity update's turns measure a bias only after this many of the tilt's time constants
// since it started afresh: before, they correct the start.
constexpr double kBiasSettleTimeConstants = 5.0;

}  // namespace

Quat attitudeFromGravityAndField(const Vec3& accel_m_s2, const Vec3* mag_uT) {
  // At rest the accelerometer reads -g, i.e. "up"; body "down" is its opposite.
  const Vec3 down_b = -accel_m_s2.normalized();
  // The shortest rotation taking body down onto NED down gives roll and pitch, heading 0.
  Quat q_nb = Quat::FromTwoVectors(down_b, Vec3::UnitZ());
  if (mag_uT != nullptr) {
    const auto m = measureMagHeading(q_nb, *mag_uT, 0.0);
    if (m.valid) q_nb = applyHeadingCorrection(q_nb, m.innovation_rad, 1.0);
  }
  return q_nb;
}

Estimator::Estimator(const EstimatorParams& params)
    : p_(params),
      gate_(p_.max_sample_gap_s, {p_.max_gyro_rad_s, p_.max_accel_m_s2, p_.max_mag_uT}),
      bias_(p_),
      disturbance_(p_.gravity_m_s2, p_.accel_disturbance_time_constant_s),
      accel_prefilter_(p_.accel_prefilter_time_constant_s, p_.accel_prefilter_turning_time_constant_s),
      clipped_share_(p_.accel_prefilter_time_constant_s, p_.accel_prefilter_turning_time_constant_s),
      steady_turn_(p_.accel_prefilter_time_constant_s, p_.accel_prefilter_full_turn_rate_rad_s,
                   p_.accel_prefilter_turning_max_rate_rad_s),
      gravity_residual_(p_.accel_residual_time_constant_s, p_.accel_disturbance_time_constant_s),
      mag_prefilter_(p_.mag_prefilter_time_constant_s),
      motion_(p_),
      heading_corrections_(p_.backup_reset_period_s),
      body_up_({kDocumentedHeadAxis, p_.body_up_time_constant_s, p_.body_up_min_walking_s, p_.body_up_relearn_after_s,
                p_.redefine_heading_leave, p_.redefine_heading_enter}),
      heading_definition_(p_.redefine_heading_enter, p_.redefine_heading_leave, p_.redefine_heading_after_s),
      mag_disturbance_({p_.mag_disturbance_time_constant_s, p_.mag_max_norm_deviation_uT, p_.mag_max_dip_deviation_rad,
                        p_.mag_max_reference_norm_deviation_uT, p_.mag_max_reference_dip_deviation_rad,
                        p_.mag_back_to_before_s, p_.mag_residual_hard_iron_uT, p_.mag_learn_first_s,
                        p_.mag_learn_new_s}),
      heading_uncertainty_({p_.heading_field_sigma_rad, p_.heading_field_correlation_s, p_.bias_walk_rad_s_per_sqrt_s,
                            p_.heading_field_set_aside_share, p_.heading_field_turn_rad}),
      attitude_net_turn_(kAttitudeMeanS, kAttitudeStepRad),
      mag_delay_({p_.mag_delay_max_s, p_.mag_delay_time_constant_s, p_.mag_delay_apply_below_sigma_s}),
      accel_delay_({p_.accel_delay_max_s, p_.accel_delay_time_constant_s, p_.accel_delay_apply_below_sigma_s,
                    kAccelDelayMinSpanS, /*repeats_are_holds=*/false}),
      vertical_rate_error_(p_),
      qsf_mag_({p_.qsf_mag_window_s, p_.qsf_mag_reference_s, p_.qsf_mag_max_norm_rms_uT,
                p_.qsf_mag_max_norm_deviation_uT, p_.qsf_mag_max_direction_rms_uT}),
      qsf_accel_({p_.qsf_accel_window_s, p_.qsf_accel_reference_s, p_.qsf_accel_max_norm_rms_m_s2,
                  p_.qsf_accel_max_norm_deviation_m_s2, p_.qsf_accel_max_direction_rms_m_s2}),
      qsf_mag_update_({p_.qsf_mag_update_noise_uT, p_.mag_residual_hard_iron_uT, p_.field_update_max_nis}),
      mau_({p_.mau_noise_uT, p_.mau_interval_s, p_.mau_verify_max_rad, p_.field_update_max_nis}),
      maru_({p_.maru_baseline_s, p_.mag_residual_hard_iron_uT, kMinMagSampleNoiseUT, p_.field_update_max_nis}),
      agu_({p_.agu_baseline_s, p_.agu_residual_accel_bias_m_s2, kMinAccelSampleNoiseM_S2, p_.field_update_max_nis}) {}

SampleVerdict Estimator::process(const ImuSample& s) {
  out_.dt_s = 0.0;
  double dt_s = 0.0;
  bool mag_usable = false;
  const SampleVerdict verdict = gate_.check(s, &dt_s, &mag_usable);
  switch (verdict) {
    case SampleVerdict::kAccepted:
      if (initialised_) {
        step(s, dt_s, mag_usable);
      } else {
        initialise(s, mag_usable);
      }
      break;
    case SampleVerdict::kFirst:
      if (initialised_) {
        publish(s.t_ns);  // the first sample after reverseTime: it opens the new time axis
      } else {
        initialise(s, mag_usable);
      }
      break;
    case SampleVerdict::kGap:
    case SampleVerdict::kClockJump:
      // The gyro cannot be integrated across the hole, so the attitude may have turned by
      // any amount meanwhile: the tilt covariance goes back to its start-up value and the
      // next field sample sets the heading outright (then the observer's running mean).
      // The observer's correction sums restart so that no restore reaches across the hole.
      accel_prefilter_.restart();
      clipped_share_.restart();
      steady_turn_.restart();
      clipped_share_started_ = false;
      gravity_residual_.restart(p_.accel_residual_time_constant_s, p_.accel_disturbance_time_constant_s);
      mag_prefilter_.restart();
      mag_disturbance_.restart();
      mag_delay_.restartChain();  // the delays learned so far stay: they are the sensors'
      accel_delay_.restartChain();
      qsf_mag_.restart();
      qsf_accel_.restart();
      qsf_mag_dt_s_ = 0.0;
      qsf_mag_update_.restart();
      maru_.restart();
      agu_.restart();
      if (!initialised_) break;  // nothing estimated yet: the output stays invalid
      heading_corrections_.restart(vertical_rate_error_.rateRadS());
      ekf_.setCovariance(kStartupCovariance);
      heading_aligned_ = false;
      heading_uncertainty_.forget();
      mag_seconds_ = 0.0;
      tilt_seconds_ = 0.0;
      publish(s.t_ns);
      break;
    default: break;  // skipped and counted by the gate; the output stays as it was
  }
  return verdict;
}

void Estimator::reverseTime() {
  const Estimator fresh(p_);
  gate_ = fresh.gate_;
  bias_.reverseTime();
  vertical_rate_error_.restore(-vertical_rate_error_.rateRadS());
  heading_corrections_.restart(vertical_rate_error_.rateRadS());
  mag_delay_ = fresh.mag_delay_;
  accel_delay_ = fresh.accel_delay_;
  mag_sample_dt_s_ = 0.0;
  qsf_frame_ = fresh.qsf_frame_;
  qsf_mag_ = fresh.qsf_mag_;
  qsf_accel_ = fresh.qsf_accel_;
  qsf_last_mag_uT_ = fresh.qsf_last_mag_uT_;
  qsf_mag_dt_s_ = 0.0;
  qsf_field_interval_s_ = 0.0;
  qsf_mag_update_.restart();
  maru_.restart();
  agu_.restart();
}

void Estimator::initialise(const ImuSample& s, bool mag_usable) {
  if (s.accel_m_s2.norm() < 0.1 * p_.gravity_m_s2) return;  // no usable gravity direction yet
  ekf_.setAttitude(attitudeFromGravityAndField(s.accel_m_s2, mag_usable ? &s.mag_uT : nullptr));
  ekf_.setCovariance(kStartupCovariance);
  heading_corrections_.restart(vertical_rate_error_.rateRadS());
  heading_aligned_ = mag_usable;
  heading_uncertainty_.forget();
  predictHeadingUncertainty(0.0);
  if (mag_usable) heading_uncertainty_.correct(1.0, 0.0);
  tilt_seconds_ = 0.0;
  initialised_ = true;
  publish(s.t_ns);
}

void Estimator::step(const ImuSample& s, double dt_s, bool mag_usable) {
  out_.dt_s = dt_s;
  const AttitudeEkf previous_ekf = ekf_;

  // The rest test looks at the field too (a slow turn about the vertical), when it is clean:
  // the disturbance tests of the previous sample decide.
  const Vec3* field_for_rest = mag_usable && !out_.mag_disturbed ? &s.mag_uT : nullptr;
  const Vec3 gyro = s.gyro_rad_s - bias_.update(s.gyro_rad_s, s.accel_m_s2, field_for_rest, dt_s);
  const double turn_rate_rad_s = gyro.norm();
  const Quat increment = gyroIncrement(gyro, dt_s);  // shared by the EKF and the gyro-frame low-passes
  const double scale_noise = p_.gyro_scale_noise * turn_rate_rad_s;
  ekf_.predict(increment, dt_s, std::sqrt(p_.gyro_noise_rad_s * p_.gyro_noise_rad_s + scale_noise * scale_noise));
  // The heading observer's integral term: the vertical rate error it has learned comes off
  // the heading rate always, also while the field is disturbed (it is the gyro's error).
  // Zero until it has learned (vertical_rate_error.hpp): then nothing is turned.
  const double rate_correction = vertical_rate_error_.rateRadS();
  if (rate_correction != 0.0) {
    ekf_.turnHeading(rate_correction * dt_s);
    heading_corrections_.addRateTurn(rate_correction, dt_s);
  }
  vertical_rate_error_.advance(dt_s, ekf_.attitude());
  // Averaged longer while the body keeps turning: the centripetal acceleration of a bend
  // turns in the gyro frame and averages out there only over time (turn_blended_low_pass.hpp).
  const Vec3 down_s = ekf_.attitude().conjugate() * Vec3::UnitZ();
  const double turning = steady_turn_.update(gyro, down_s, motion_.level() != MotionLevel::kStanding, dt_s);
  const Vec3 clipped_share = trackClipping(s.accel_m_s2, increment, dt_s, turning);
  // The accelerometer and magnetometer samples are means over the interval, so they see the
  // body as it was part of the way through it, while the gyro's increment has brought the
  // attitude to its end: turn them by the rest of the interval's rotation. A sample repeated
  // by a sensor slower than the IMU is as much older again as it has been held, and each
  // sensor's own delay, once learned, replaces the fraction where it makes the vector's angle
  // to the down steadier (vector_delay_estimator.hpp). The specific force is a turned
  // gravity only while the body stands (a walker's accelerations keep step with their turns,
  // and would pass for a delay of a tenth of a second), and a clipped reading not at all.
  // (In this order, so that the norm is taken only where the rest holds.)
  const bool accel_clean =
      p_.accel_delay_max_s > 0.0 && !out_.accel_clipped && motion_.level() == MotionLevel::kStanding &&
      std::abs(s.accel_m_s2.norm() - p_.gravity_m_s2) < kAccelDelayMaxNormDeviation * p_.gravity_m_s2;
  accel_delay_.update(gyro, &s.accel_m_s2, accel_clean, dt_s);
  const Vec3 accel_now = turnedToNow(accel_delay_, s.accel_m_s2, gyro, down_s, accel_clean, dt_s, &out_.accel_lag_s);
  const bool mag_clean = field_for_rest != nullptr;
  mag_delay_.update(gyro, mag_usable ? &s.mag_uT : nullptr, mag_clean, dt_s);
  const Vec3 mag_now = turnedToNow(mag_delay_, s.mag_uT, gyro, down_s, mag_clean, dt_s, &out_.mag_lag_s);
  const Vec3 gravity_measurement = accel_prefilter_.update(increment, accel_now, dt_s, turning);
  const bool new_field_sample = detectQuasiStaticFields(s, increment, accel_now, mag_now, mag_usable, dt_s);

  // Henriksson §3.1 also goes back to a gyro-only background attitude whenever the level
  // steps up. headingd does not: that attitude has run on the gyro alone for 5-10 s, and
  // its errors over that time (bias, scale) cost more than the accelerations it undoes
  // (removing it took BROAD from 2.03 to 1.90 deg, at 50 Hz from 3.60 to 2.30 deg,
  // and halved the tilt peaks of simulated hand-held motion).
  // The activity level of §3.1 (d_k with hysteresis) is reported; R_k follows what the
  // low-pass left in the measurement instead (gravity_residual.hpp).
  motion_.update(disturbance_.update(s.accel_m_s2, dt_s));
  // R_k from the wander of the short average alone: the long one wanders less, but its error
  // is slower rather than smaller, and the EKF must not lean on it more (R_k from the blend:
  // the worst inclination of the shared phones' runs 2.48° instead of 2.20°).
  const double residual = gravity_residual_.update(increment, accel_prefilter_.shortAverage(), dt_s);
  out_.gravity_noise_m_s2 = gravityMeasurementNoise(p_.accel_noise_m_s2, p_.accel_residual_gain, residual);
  // A clipped reading is short of the body's specific force along its clipped axes, and the
  // low-pass keeps that for its time constant: along that direction the measurement counts
  // for less, by accel_clip_excess_m_s2 per unit of clipped share (estimator_params.hpp).
  const double share = clipped_share.norm();
  const double clip_sigma = p_.accel_clip_excess_m_s2 * share;
  const Eigen::Vector2d tilt_turn =
      share > 0.0 ? ekf_.updateGravity(gravity_measurement, out_.gravity_noise_m_s2, p_.gravity_m_s2,
                                       clipped_share / share, clip_sigma * clip_sigma)
                  : ekf_.updateGravity(gravity_measurement, out_.gravity_noise_m_s2, p_.gravity_m_s2);
  tilt_seconds_ += dt_s;
  // The start: the attitude came from one accelerometer sample, which in motion may be off by
  // tens of degrees, and the EKF would take its own time constant to leave it (at the level of
  // running, several). The prefilter starts as the running mean of gravity in the gyro frame,
  // better from its second sample on; for one EKF time constant the tilt is that mean.
  if (tilt_seconds_ < ekfTiltTimeConstantS(p_) && gravity_measurement.norm() > 0.1 * p_.gravity_m_s2) {
    ekf_.setAttitude(tiltedTo(ekf_.attitude(), -gravity_measurement));
  }
  // The turn measures the bias once the tilt has settled from its start (the first turns
  // correct the start, not a drift).
  bias_.addTiltCorrection(tilt_turn, ekf_.attitude(), dt_s,
                          !bias_.atRest() && tilt_seconds_ >= kBiasSettleTimeConstants * tiltTimeConstantS(p_));

  predictHeadingUncertainty(dt_s);
  out_.mag_used = false;
  out_.mag_disturbed = false;
  out_.mag_gain = 0.0;
  out_.mau_applied = false;
  out_.qsf_mag_update_applied = false;
  out_.maru_applied = false;
  mag_prefilter_.advance(increment);
  mag_disturbance_.advance(increment);
  mag_sample_dt_s_ += dt_s;
  if (mag_usable) {
    // The observer's time constants are in seconds: each field sample stands for the time since
    // the last one (a magnetometer slower than the IMU, in some epochs only), up to a gap.
    const double field_period_s = std::min(mag_sample_dt_s_, p_.max_sample_gap_s);
    const Vec3 field_uT = mag_prefilter_.add(mag_now, mag_sample_dt_s_);
    correctHeading(field_uT, field_period_s, turn_rate_rad_s);
    applyFieldUpdates(field_uT, mag_now, field_period_s, new_field_sample);
    if (out_.mag_used || out_.mag_disturbed) vertical_rate_error_.fieldSample(out_.mag_disturbed, field_period_s);
    mag_sample_dt_s_ = 0.0;
  }

  if (!ekf_.allFinite()) {
    // Never expected (every input is finite by now); if it happens, keep the last good state.
    ekf_ = previous_ekf;
    ++state_recoveries_;
  }
  heading_corrections_.advance(dt_s, vertical_rate_error_.rateRadS());
  publish(s.t_ns);
}

bool Estimator::gyroHeadingBeatsAField() const {
  // The background heading has run on the gyro alone for the older sum's age: its drift over
  // that time, at the rate error the heading sigma allows about the vertical, must be below the
  // heading error of a clean field (heading_field_sigma_rad). Where the bias about the vertical
  // is not known (a phone carried from the start, no rest: that sigma is the bias filter's
  // prior, tens of mrad/s) the gyro's seconds are worth less than the field's corrections, even
  // through a disturbance; on the shared phone recordings with magnets such restores cost as
  // often as they saved (estimator_params.hpp, mag_restore_max_age_s).
  const double drift_rad = heading_uncertainty_.rateSigmaRadS() * heading_corrections_.oldestAgeS();
  return drift_rad < p_.heading_field_sigma_rad;
}

void Estimator::restoreGyroHeading() {
  // Eq. 4.4: the detection lags the start of a disturbance (the field has to move beyond
  // the thresholds first), and the observer has been pulling the heading towards the bad
  // field meanwhile. Undo what it did since the older sum restarted, before the field went
  // wrong (heading_corrections.hpp): the heading the gyro alone would have kept.
  const double undo = -heading_corrections_.oldestSumRad();
  ekf_.turnHeading(undo);
  heading_corrections_.add(undo);
  // The integral term likewise goes back to what it was then.
  vertical_rate_error_.restore(heading_corrections_.oldestRateRadS());
  ++mag_heading_restores_;
}

void Estimator::correctHeading(const Vec3& mag_uT, double field_period_s, double turn_rate_rad_s) {
  const auto m = measureMagHeading(ekf_.attitude(), mag_uT, p_.mag_min_horizontal_fraction);
  if (!m.valid) {
    ++mag_no_heading_;
    return;
  }
  out_.mag_disturbance = mag_disturbance_.update(mag_uT, m.dip_rad, field_period_s);
  out_.mag_disturbed = out_.mag_disturbance.any();
  // A disturbance counts once it has lasted mag_restore_confirm_s: single noisy samples must
  // not swap in a heading with seconds of gyro drift.
  const double before = mag_disturbed_seconds_;
  mag_disturbed_seconds_ = out_.mag_disturbed ? mag_disturbed_seconds_ + field_period_s : 0.0;
  const bool onset = before < p_.mag_restore_confirm_s && mag_disturbed_seconds_ >= p_.mag_restore_confirm_s;
  if (out_.mag_disturbed) {
    ++mag_disturbed_;
    out_.mag_innovation_rad = m.innovation_rad;
    if (heading_aligned_) heading_uncertainty_.observeSetAside(m.innovation_rad, field_period_s);
    if (onset && heading_aligned_ && heading_corrections_.oldestAgeS() <= p_.mag_restore_max_age_s &&
        gyroHeadingBeatsAField()) {
      restoreGyroHeading();
    }
    return;  // K = 0: the heading runs on the gyro (eq. 4.3)
  }
  // The first usable field sets the heading outright. Then eq. 4.2, with K no smaller than
  // dt/t while t, the time since that first sample, is short: the observer starts as the
  // running mean of its measurements instead of leaning on the first, noisy one.
  double gain = 1.0;
  if (heading_aligned_) {
    mag_seconds_ += field_period_s;
    gain = std::max(magObserverGain(field_period_s, p_.mag_heading_time_constant_s), field_period_s / mag_seconds_);
  }
  // The integral term (PI observer, vertical_rate_error.hpp), once the observer has left its
  // running-mean start.
  const double rate_gain = heading_aligned_ && mag_seconds_ >= p_.mag_heading_time_constant_s
                               ? vertical_rate_error_.learn(m.innovation_rad, field_period_s, turn_rate_rad_s)
                               : 0.0;
  if (heading_aligned_) heading_uncertainty_.observeInnovation(m.innovation_rad, field_period_s);
  heading_uncertainty_.correct(gain, rate_gain);
  heading_aligned_ = true;
  ekf_.turnHeading(gain * m.innovation_rad);
  heading_corrections_.add(gain * m.innovation_rad);
  out_.mag_used = true;
  out_.mag_gain = gain;
  out_.mag_innovation_rad = m.innovation_rad;
}

void Estimator::applyFieldUpdates(const Vec3& filtered_uT, const Vec3& sample_uT, double field_period_s,
                                  bool new_field_sample) {
  // MAU on the low-passed field the observer used (its error is the calibration's, not the
  // sample's noise); the QSF update and MARU on each new sample (MAGYQ's white noise per sample).
  if (out_.mag_used) {
    out_.mau_applied = mau_.update(ekf_, filtered_uT, field_period_s, heading_uncertainty_.sigmaRad());
  }
  if (!new_field_sample) return;
  // Standing: the level, and a specific force that stands still too (quasi_static_field_update.hpp).
  const bool standing = motion_.level() == MotionLevel::kStanding && out_.accel_quasi_static;
  out_.maru_applied = maru_.update(bias_, sample_uT, qsf_frame_.frameFromSensor(),
                                   out_.mag_quasi_static && standing && !bias_.atRest(), qsf_mag_.sampleNoiseSigma());
  if (heading_aligned_) {
    out_.qsf_mag_update_applied =
        qsf_mag_update_.update(ekf_, sample_uT, qsf_frame_.frameFromSensor(), out_.mag_quasi_static && standing,
                               !out_.mag_used, qsf_field_interval_s_, heading_uncertainty_.rateSigmaRadS()) != 0.0;
  }
}

bool Estimator::detectQuasiStaticFields(const ImuSample& s, const Quat& increment, const Vec3& accel_now,
                                        const Vec3& mag_now, bool mag_usable, double dt_s) {
  qsf_frame_.advance(increment);
  maru_.advance(qsf_frame_.frameFromSensor(), dt_s);
  agu_.advance(qsf_frame_.frameFromSensor(), dt_s);
  out_.accel_quasi_static = qsf_accel_.add(accel_now, qsf_frame_.frameFromSensor(), dt_s);
  // AGU on every sample of the specific force (rotated_field_update.hpp): quasi-static while the
  // person stands, and not at rest (still blocks measure the bias there).
  out_.agu_applied =
      agu_.update(bias_, accel_now, qsf_frame_.frameFromSensor(),
                  out_.accel_quasi_static && motion_.level() == MotionLevel::kStanding && !bias_.atRest(),
                  qsf_accel_.sampleNoiseSigma());
  // A magnetometer slower than the IMU repeats its last sample: only a new one is a sample
  // of the field (a held one would count one reading's noise again).
  qsf_mag_dt_s_ += dt_s;
  if (mag_usable && s.mag_uT != qsf_last_mag_uT_) {
    out_.mag_quasi_static = qsf_mag_.add(mag_now, qsf_frame_.frameFromSensor(), qsf_mag_dt_s_);
    qsf_field_interval_s_ = qsf_mag_dt_s_;
    qsf_last_mag_uT_ = s.mag_uT;
    qsf_mag_dt_s_ = 0.0;
    return true;
  }
  if (!mag_usable) out_.mag_quasi_static = false;
  return false;
}

void Estimator::predictHeadingUncertainty(double dt_s) {
  const Quat q = ekf_.attitude();
  const Vec3 down_s = q.conjugate() * Vec3::UnitZ();  // NED down in sensor axes
  heading_uncertainty_.predict(dt_s, down_s.dot(bias_.covariance() * down_s), attitude_net_turn_.update(q, dt_s));
}

void Estimator::publish(std::int64_t t_ns) {
  const Quat q = ekf_.attitude();
  out_.valid = true;
  out_.t_ns = t_ns;
  out_.q_nb = q;
  out_.yaw_rad = yawZyx(q);
  // "Lying down" is the person's, not the sensor's: h and ψ_rd (§3.3) of the up axis learned
  // while walking (a walking person is upright), whatever the mounting. Only integrated
  // samples (dt > 0) teach it.
  body_up_.update(q, motion_.level() != MotionLevel::kStanding, out_.dt_s);
  out_.body_up_axis_s = body_up_.axis();
  out_.body_up_learned = body_up_.learned();
  out_.head_height = headHeight(q, body_up_.axis());
  // Until the up axis is known the mounting is unknown, and no sensor axis can say "lying
  // down": a phone held screen-up has its -z pointing down (h = -1), and the heading of that
  // near-vertical axis is no heading at all (107° RMS on the shared iPhone 4S texting trial,
  // which never walks hard enough to learn the axis). The selector sees the person upright
  // (h = 1) meanwhile, and the x-axis yaw is published.
  constexpr double kUpright = 1.0;
  out_.heading_redefined = heading_definition_.update(body_up_.known() ? out_.head_height : kUpright, out_.dt_s);
  out_.heading_rad = out_.heading_redefined ? headingOfAxis(q, body_up_.axis()) : out_.yaw_rad;
  out_.motion_level = motion_.level();
  out_.accel_disturbance = disturbance_.value();
  out_.gyro_bias_rad_s = bias_.bias();
  out_.vertical_rate_correction_rad_s = vertical_rate_error_.rateRadS();
  out_.at_rest = bias_.atRest();
  out_.heading_sigma_rad = heading_uncertainty_.sigmaRad();
}

Vec3 Estimator::turnedToNow(VectorDelayEstimator& delay, const Vec3& sample, const Vec3& gyro, const Vec3& down_s,
                            bool clean, double dt_s, double* lag_s) {
  *lag_s = p_.vector_sample_lag_fraction * dt_s + delay.heldS();
  Vec3 now = turnedBySmallAngle(sample, -*lag_s * gyro);
  if (delay.candidateS() != 0.0) {
    const double delayed_lag_s = delay.candidateS() + delay.heldS();
    const Vec3 delayed = turnedBySmallAngle(sample, -delayed_lag_s * gyro);
    delay.scoreDownAngle(down_s, now, delayed, clean, dt_s);
    if (delay.useCandidate()) {
      now = delayed;
      *lag_s = delayed_lag_s;
    }
  }
  return now;
}

Vec3 Estimator::trackClipping(const Vec3& accel_m_s2, const Quat& increment, double dt_s, double turning) {
  if (p_.accel_clip_excess_m_s2 <= 0.0) return Vec3::Zero();
  const Vec3 clipped = accel_clipping_.update(accel_m_s2, dt_s);
  out_.accel_clipped = !clipped.isZero();
  if (out_.accel_clipped) ++accel_clipped_;
  // Until the first clipped reading the share is zero and not worth a rotation per sample.
  if (out_.accel_clipped && !clipped_share_started_) {
    clipped_share_.add(Vec3::Zero(), dt_s, turning);  // the low-pass starts from no clipping
    clipped_share_started_ = true;
  }
  return clipped_share_started_ ? clipped_share_.update(increment, clipped, dt_s, turning) : Vec3::Zero();
}

EstimatorCounters Estimator::counters() const {
  EstimatorCounters c;
  c.samples = gate_.counters();
  c.bias_still_blocks = bias_.stillBlocks();
  c.mag_no_heading = mag_no_heading_;
  c.mag_disturbed = mag_disturbed_;
  c.mag_heading_restores = mag_heading_restores_;
  c.state_recoveries = state_recoveries_;
  c.accel_clipped = accel_clipped_;
  // Whole milliseconds of the seconds summed (a counter is an integer).
  c.qsf_mag_periods = qsf_mag_.periods();
  c.qsf_mag_ms = static_cast<std::uint64_t>(1000.0 * qsf_mag_.totalSeconds());
  c.qsf_accel_periods = qsf_accel_.periods();
  c.qsf_accel_ms = static_cast<std::uint64_t>(1000.0 * qsf_accel_.totalSeconds());
  c.qsf_mag_updates = qsf_mag_update_.counters().applied;
  c.qsf_mag_updates_rejected = qsf_mag_update_.counters().rejected_by_gate;
  c.mau_updates = mau_.counters().applied;
  c.mau_updates_rejected = mau_.counters().rejected_by_gate;
  c.mau_updates_unverified = mau_.counters().rejected_by_verification;
  c.maru_updates = maru_.counters().applied;
  c.maru_updates_rejected = maru_.counters().rejected_by_gate;
  c.agu_updates = agu_.counters().applied;
  c.agu_updates_rejected = agu_.counters().rejected_by_gate;
  return c;
}

}  // namespace headingd::core
