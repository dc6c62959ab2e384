#pragma once
// How far the published magnetic heading may be off: the variance of the heading observer's
// error (Henriksson eq. 4.2), carried through what the estimator actually does to it rather
// than through an optimal filter's formula, so that it stays honest while the observer runs
// on its fixed gain, on the gyro alone (disturbed field, eq. 4.3) or at its start.
//
// Four errors are carried jointly (a 4×4 covariance, a few dozen flops per sample):
//   e  the heading error (estimate - truth, about NED down, rad);
//   b  the error of the rate the heading integrates about the vertical (rad/s): what the gyro
//      bias estimate gets wrong about the vertical. Between samples e grows by b·dt;
//   u  the error of the heading the field shows (rad): what the disturbance tests do not see.
//      Two first-order Gauss-Markov processes, u = a + p, because its two sources change for
//      different reasons:
//   a  what a calibration leaves (a residual hard iron, the magnetometer's misalignment): in
//      the sensor's axes, so its heading error changes only as the attitude does. Its
//      variance is a floor (field_sigma_rad); it decorrelates as the attitude's mean turns
//      (net_turn.hpp), over field_turn_rad: a sensor that keeps its attitude, shaken in place
//      or carried straight on, keeps its error for as long as it does.
//   p  what the place adds (a building's field) and the tilt error through the dip, with the
//      time-correlation field_correlation_s (the person moves on). Its variance is what the
//      innovations show of it (observeInnovation): a field that disagrees with the gyro from
//      place to place says that its errors are larger here. Plus a share of what the samples
//      the disturbance tests set aside show (observeSetAside): the tests flag a wrong field
//      only part of the time it is wrong (a building's steel: 20-60 % of it in the
//      simulator), and the samples they let through there carry part of the same error,
//      which their innovations do not show once the heading has followed them.
// A field sample used with gain K (eq. 4.2) makes e ← (1 - K) e + K u; the observer's
// integral term, when on, makes b ← b + g (u - e) with its own gain g. Before the first field
// sample the heading is unknown: σ is that of an angle uniform on the circle (π/√3).
//
// That covariance says what the estimator's errors may be before anyone looks at the
// innovations. But the innovations (ν = u - e) show the errors: a rate error b makes them
// drift to b τ and stay there, so a minute of small innovations says b is small. Beside it a
// Kalman filter over the same (e, b, a, p), with the same steps, takes each used sample's
// innovation as a measurement of u - e (its white noise learned from the innovations' spread
// about their one-second mean, from the first second of them on) and estimates the
// estimator's own errors. The published σ is that filter's expected squared error
// √(P_ee + ê²): on a phone carried from the start (no rest, the bias filter's prior of tens
// of mrad/s, 30-100° of heading σ before the innovations) it falls once the field has shown
// the rate error small, and a steadier gyro than the bias filter assumes shows its rate error
// as small too. Neither changes the estimate; rateSigmaRadS() stays the first's (the restore
// of eq. 4.4 is gated on it).
#include <Eigen/Core>

#include "headingd/core/low_pass.hpp"

namespace headingd::core {

// The estimator's values and how they were chosen: estimator_params.hpp (heading_field_*).
struct HeadingUncertaintyParams {
  double field_sigma_rad = 0.0;             // σ of a (steady state)
  double field_correlation_s = 1.0;         // p's correlation time, and the innovations' average
  double rate_walk_rad_s_per_sqrt_s = 0.0;  // b wanders as the gyro bias does
  // Share of the set-aside samples' mean squared innovation (times their share of the field
  // samples, both over field_correlation_s) added to p's steady-state variance.
  double set_aside_share = 0.0;
  // The attitude's net turn (rad) over which a decorrelates; 0: a decorrelates with time as p
  // does (one process).
  double field_turn_rad = 0.0;
};

class HeadingUncertainty {
 public:
  explicit HeadingUncertainty(const HeadingUncertaintyParams& params);

  // The heading is unknown again (start, a gap in the samples): the next field sample sets it.
  void forget();

  // One sample of dt_s: e integrates b, b is at most as uncertain as the gyro bias filter says
  // about the vertical (rate_variance, (rad/s)²), p decorrelates with time and a with the
  // attitude's net turn this sample (attitude_turn_rad, NetTurn), each towards its steady
  // state.
  void predict(double dt_s, double rate_variance, double attitude_turn_rad = 0.0);

  // The innovation ψ_mm - ψ of a field sample that was used, dt_s after the previous field
  // sample (a magnetometer may be slower than the IMU): what of p the field shows. Its
  // mean over a second (the magnetometer's white noise averaged away) is squared and
  // averaged over field_correlation_s; that variance is p's steady state.
  void observeInnovation(double innovation_rad, double dt_s);
  // A field sample the disturbance tests set aside, with its innovation (capped at 90°): how
  // wrong the field is where the tests fire. Averaged with the used samples (which count as
  // zero) over field_correlation_s.
  void observeSetAside(double innovation_rad, double dt_s);

  // A field sample corrected the heading by `gain` × innovation (eq. 4.2; gain 1 sets it),
  // and the integral term moved the vertical rate by `rate_gain` × innovation (0: off).
  void correct(double gain, double rate_gain);

  bool known() const { return known_; }
  // The published 1-sigma: √(P_ee + ê²) of the filter that has seen the innovations (above).
  double sigmaRad() const;
  // The same before the innovations: what the estimator's steps alone imply.
  double priorSigmaRad() const;
  // Standard deviation of b, the rate error about the vertical (rad/s).
  double rateSigmaRadS() const;
  // What the filter that has seen the innovations makes of b (rad/s) and its standard
  // deviation: a diagnosis (headingd-study --trace); the estimate does not use it.
  double shownRateRadS() const;
  double shownRateSigmaRadS() const;

 private:
  // The Kalman update of the filter that has seen the innovations.
  void showInnovation(double innovation_rad, double dt_s);

  HeadingUncertaintyParams p_;
  ExpDecay field_decay_;                         // p's, per IMU sample
  ExpDecay field_sample_decay_;                  // the innovations' spread's average, per field sample
  ExpDecay innovation_mean_decay_;               // the innovations' one-second mean
  Eigen::Matrix4d P_ = Eigen::Matrix4d::Zero();  // over (e, b, a, p)
  // The filter that has seen the innovations: its estimate of (e, b, a, p) and covariance.
  Eigen::Vector4d shown_x_ = Eigen::Vector4d::Zero();
  Eigen::Matrix4d shown_P_ = Eigen::Matrix4d::Zero();
  double innovation_noise_variance_ = 0.0;  // per sample, about the one-second mean
  bool known_ = false;
  bool rate_started_ = false;         // P_(1, 1) has been set from the bias filter
  bool field_started_ = false;        // a's and p's variances have been set
  double innovation_seen_s_ = 0.0;    // of innovations observed
  double innovation_mean_rad_ = 0.0;  // over about a second
  double innovation_variance_ = 0.0;  // of that mean, over field_correlation_s
  double set_aside_variance_ = 0.0;   // set-aside innovations², used samples as 0, over it too
};

}  // namespace headingd::core
