#include "headingd/core/background_attitudes.hpp"

#include <algorithm>

namespace headingd::core {

void BackgroundAttitudes::restart(const Quat& estimate_nb) {
  q_[0] = q_[1] = estimate_nb;
  // Staggered by half a period (eq. 4.4b uses n + N/2) so that one is always at least half
  // a period old.
  age_s_[0] = 0.0;
  age_s_[1] = 0.5 * reset_period_s_;
  started_ = true;
}

void BackgroundAttitudes::update(const Quat& increment, double dt_s, const Quat& estimate_nb) {
  if (!started_) {
    restart(estimate_nb);
    return;
  }
  for (int i = 0; i < 2; ++i) {
    age_s_[i] += dt_s;
    if (age_s_[i] >= reset_period_s_) {
      q_[i] = estimate_nb;
      age_s_[i] = 0.0;
    } else {
      q_[i] = (q_[i] * increment).normalized();  // q(k+1) = q(k) ⊗ Δr, Henriksson eq. 2.34
    }
  }
}

const Quat& BackgroundAttitudes::oldest() const { return age_s_[0] >= age_s_[1] ? q_[0] : q_[1]; }

double BackgroundAttitudes::oldestAge() const { return std::max(age_s_[0], age_s_[1]); }

}  // namespace headingd::core
