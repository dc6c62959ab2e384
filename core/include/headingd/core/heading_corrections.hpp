#pragma once
// The background gyro-only headings ψ_g1, ψ_g2 of Henriksson eq. 4.4, kept as what the
// magnetometer has done since: two sums of the heading observer's corrections, each restarted
// every reset period, staggered by half a period. Undoing the older sum gives the heading the
// estimate would have had, had the field not been used since that sum restarted, with the
// estimate's own tilt: a separate gyro-only attitude would also drift in tilt, and under fast
// turns its tilt error leaks into its heading (BROAD at 50 Hz: restores made the attached-magnet
// trial worse, not better).
//
// Why this equals eq. 4.4's integrator: the observer turns the attitude about NED down
// (left multiplication), the gyro about body axes (right multiplication), and the two commute;
// the gravity update turns it about NED north and east by small angles, which moves a heading
// turn's axis by second-order amounts only.
namespace headingd::core {

class HeadingCorrectionLog {
 public:
  explicit HeadingCorrectionLog(double reset_period_s) : reset_period_s_(reset_period_s) { restart(); }

  // A correction of the heading by angle_rad (about NED down).
  void add(double angle_rad) {
    sum_rad_[0] += angle_rad;
    sum_rad_[1] += angle_rad;
  }
  // The observer's integral term turned the heading by rate_rad_s · dt_s (about NED down).
  // Had the field not been used since a sum restarted, the term would have kept the value
  // it had then: each sum counts only what it has moved since.
  void addRateTurn(double rate_rad_s, double dt_s) {
    for (int i = 0; i < 2; ++i) sum_rad_[i] += (rate_rad_s - rate_at_restart_rad_s_[i]) * dt_s;
  }
  // Time passes; each sum restarts once it is a reset period old, keeping the integral
  // term's value `rate_rad_s` of that moment.
  void advance(double dt_s, double rate_rad_s = 0.0) {
    for (int i = 0; i < 2; ++i) {
      age_s_[i] += dt_s;
      if (age_s_[i] >= reset_period_s_) {
        age_s_[i] = 0.0;
        sum_rad_[i] = 0.0;
        rate_at_restart_rad_s_[i] = rate_rad_s;
      }
    }
  }
  // The older sum and its age.
  double oldestSumRad() const { return age_s_[0] >= age_s_[1] ? sum_rad_[0] : sum_rad_[1]; }
  double oldestAgeS() const { return age_s_[0] >= age_s_[1] ? age_s_[0] : age_s_[1]; }
  // The integral term's value when the older sum restarted.
  double oldestRateRadS() const {
    return age_s_[0] >= age_s_[1] ? rate_at_restart_rad_s_[0] : rate_at_restart_rad_s_[1];
  }
  // Both restart (start-up, gap), staggered by half a period (eq. 4.4b's n + N/2).
  void restart(double rate_rad_s = 0.0) {
    sum_rad_[0] = sum_rad_[1] = 0.0;
    rate_at_restart_rad_s_[0] = rate_at_restart_rad_s_[1] = rate_rad_s;
    age_s_[0] = 0.0;
    age_s_[1] = 0.5 * reset_period_s_;
  }

 private:
  double reset_period_s_;
  double sum_rad_[2] = {0.0, 0.0};
  double age_s_[2] = {0.0, 0.0};
  double rate_at_restart_rad_s_[2] = {0.0, 0.0};
};

}  // namespace headingd::core
