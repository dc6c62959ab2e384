#pragma once
// The two background gyro-only attitudes at the end of Henriksson §3.1 (and their heading
// counterparts ψ_g1, ψ_g2 of eq. 4.4): each is reset from the estimate every period, the two
// staggered by half a period, and integrated with the gyroscope alone in between. When the
// accelerometer turns out to have been disturbed (R steps up), the older one, which has
// seen none of the recent accelerometer updates, replaces the estimate.
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class BackgroundAttitudes {
 public:
  explicit BackgroundAttitudes(double reset_period_s) : reset_period_s_(reset_period_s) {}

  // Integrates both with the (bias-corrected) gyro, then resets whichever is due from
  // the current estimate.
  void update(const Vec3& gyro_rad_s, double dt_s, const Quat& estimate_nb) {
    update(gyroIncrement(gyro_rad_s, dt_s), dt_s, estimate_nb);
  }
  // The same with the sample's rotation already computed (gyroIncrement).
  void update(const Quat& increment, double dt_s, const Quat& estimate_nb);

  // The attitude that has integrated the gyro alone for longest since its reset.
  const Quat& oldest() const;
  // How long that one has run on the gyro alone.
  double oldestAge() const;

  // Restart both from the given attitude (start-up, or after a gap).
  void restart(const Quat& estimate_nb);

 private:
  double reset_period_s_;
  Quat q_[2] = {Quat::Identity(), Quat::Identity()};
  double age_s_[2] = {0.0, 0.0};
  bool started_ = false;
};

}  // namespace headingd::core
