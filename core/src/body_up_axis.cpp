#include "headingd/core/body_up_axis.hpp"

#include <algorithm>

namespace headingd::core {

void BodyUpAxis::update(const Quat& q_nb, bool walking, double dt_s) {
  if (!(p_.time_constant_s > 0.0) || !walking || !(dt_s > 0.0)) return;  // held while not walking
  // NED up (-z_n) seen in sensor axes: q_nb* ⊗ (0, 0, -1) ⊗ q_nb.
  const Vec3 up_s = q_nb.conjugate() * Vec3(0.0, 0.0, -1.0);
  if (acquiring_) {
    learn(up_s, dt_s);
    return;
  }
  const double h = up_s.dot(axis_s_);  // eq. 3.12 for the learned axis
  if (h > p_.upright_above) {
    contradicting_s_ = 0.0;
    learn(up_s, dt_s);
  } else if (h < p_.lying_below) {
    contradicting_s_ += dt_s;
    if (contradicting_s_ >= p_.relearn_after_s) {  // moved: learn afresh (the axis holds meanwhile)
      mean_up_s_ = Vec3::Zero();
      walking_s_ = 0.0;
      contradicting_s_ = 0.0;
      acquiring_ = true;
    }
  }
}

void BodyUpAxis::learn(const Vec3& up_s, double dt_s) {
  walking_s_ += dt_s;
  // An exponential mean with the time constant that starts as the plain running mean of what
  // it has seen (gain no smaller than dt / t): the first strides count as much as later ones.
  const double gain = std::max(1.0 - alpha_(dt_s), dt_s / walking_s_);
  mean_up_s_ += gain * (up_s - mean_up_s_);
  if (walking_s_ >= p_.min_walking_s && mean_up_s_.norm() > 0.0) {
    axis_s_ = mean_up_s_.normalized();
    learned_ = true;
    acquiring_ = false;
  }
}

}  // namespace headingd::core
