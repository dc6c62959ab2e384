#include "headingd/core/background_attitudes.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {
namespace {

// The product of two unit quaternions has |q|² = 1 to a few ulps; there 1/|q| = 1.5 - 0.5|q|²
// to rounding, which saves a square root and a division per attitude and sample.
Quat renormalised(const Quat& q) {
  const double norm2 = q.squaredNorm();
  if (std::abs(norm2 - 1.0) >= 1e-8) return q.normalized();
  return Quat((1.5 - 0.5 * norm2) * q.coeffs());
}

}  // namespace

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
      q_[i] = renormalised(q_[i] * increment);  // q(k+1) = q(k) ⊗ Δr, Henriksson eq. 2.34
    }
  }
}

const Quat& BackgroundAttitudes::oldest() const { return age_s_[0] >= age_s_[1] ? q_[0] : q_[1]; }

double BackgroundAttitudes::oldestAge() const { return std::max(age_s_[0], age_s_[1]); }

}  // namespace headingd::core
