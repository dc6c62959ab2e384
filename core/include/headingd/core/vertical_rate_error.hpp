#pragma once
// The heading observer's integral term (Henriksson eq. 4.2 made a PI observer): a lasting
// innovation ψ_mm - ψ is a rate error of the gyro about the vertical (a bias no rest has
// shown), and the heading rate is corrected by ∫ innovation dt / (τ τ_i), τ the observer's
// time constant and τ_i mag_rate_error_time_constant_s.
//
// A field that is wrong but looks clean makes lasting innovations too, and the rate learned
// from them outlasts the field. So the term learns only where the innovation is most likely
// a rate error (estimator_params.hpp has the figures):
//  - where the field is known to be clean: the World Magnetic Model's field has been set from
//    a GPS fix recently (mag_rate_error_max_reference_age_s: a receiver with a fix sees the
//    sky, away from the steel of buildings, and the disturbance tests compare the field with
//    the model's there), or, without a fix, the disturbance tests have set aside less than
//    mag_rate_error_max_set_aside_share of the field samples over about
//    mag_rate_error_settle_s (they flag a building's field only part of the time it is
//    wrong, so a stretch where they never fire is one where the field is most likely clean);
//  - once the heading has stayed within mag_rate_error_steady_heading_rad for
//    mag_rate_error_settle_s: after a change of heading the innovations show how the field's
//    error differs between the two headings (a calibration's residual hard iron), which the
//    observer takes out with time constant τ; a rate error keeps them where they are;
//  - while the sensor turns slower than mag_rate_error_max_turn_rad_s.
#include <limits>

#include "headingd/core/estimator_params.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class VerticalRateError {
 public:
  explicit VerticalRateError(const EstimatorParams& p);

  // Per sample: time passes; q_nb is the attitude after the gyro's prediction (its x-axis
  // heading is what has to stay steady).
  // Inline: when only a fix can show a clean field and there has been none yet, this is all
  // there is per sample.
  void advance(double dt_s, const Quat& q_nb) {
    if (time_constant_s_ <= 0.0) return;
    reference_age_s_ += dt_s;
    if (max_set_aside_share_ <= 0.0 && max_reference_age_s_ > 0.0 &&
        reference_age_s_ == std::numeric_limits<double>::infinity()) {
      return;
    }
    trackSteadyHeading(dt_s, q_nb);
  }
  // The World Magnetic Model's field was set from a fix just now.
  void referenceUpdated() { reference_age_s_ = 0.0; }
  // A field sample `period_s` after the previous one, used or set aside by the disturbance
  // tests: the share of set-aside samples, weighted by their periods (a magnetometer slower
  // than the IMU counts by its own rate), averaged over about mag_rate_error_settle_s.
  void fieldSample(bool set_aside, double period_s);

  // After a clean field sample with innovation innovation_rad, once the observer has left its
  // start: learns when every condition above holds. Returns the gain the rate took
  // (dt / (τ τ_i)), 0 when it did not learn.
  double learn(double innovation_rad, double dt_s, double turn_rate_rad_s);

  // The correction added to the gyro's vertical rate (rad/s).
  double rateRadS() const { return rate_rad_s_; }
  // Back to an earlier value (the restore of eq. 4.4 undoes what a bad field taught).
  void restore(double rate_rad_s) { rate_rad_s_ = rate_rad_s; }

 private:
  bool referenceIsRecent() const;
  bool fieldIsClean() const;
  void trackSteadyHeading(double dt_s, const Quat& q_nb);

  double time_constant_s_;           // τ_i; 0: off
  double observer_time_constant_s_;  // τ
  double max_turn_rad_s_;
  double max_reference_age_s_;  // 0: no fix needed
  double max_set_aside_share_;  // 0: a fix needed
  double settle_s_;
  double steady_cos_;  // cos of mag_rate_error_steady_heading_rad
  double max_rate_rad_s_;
  double rate_rad_s_ = 0.0;
  double reference_age_s_;
  double steady_s_ = 0.0;
  Eigen::Vector2d steady_anchor_ = Eigen::Vector2d::Zero();  // unit heading direction
  bool steady_anchored_ = false;
  LowPassAlpha set_aside_alpha_;
  double set_aside_share_ = 1.0;  // no field sample yet: not known to be clean
  double field_seen_s_ = 0.0;
};

}  // namespace headingd::core
