#pragma once
// Heading and its redefinition for lying-down poses (Henriksson §2.5.2, §3.3).
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// Definition 2.5.1: angle from north of the body x-axis projected on the horizontal plane.
double headingOf(const Quat& q_nb);

// Definition 3.3.1 via eqs. 3.9-3.11: the same for the body's -z axis (the head of a person
// wearing the IMU), computed as the heading of q_tot = q ⊗ q_y with q_y 90° about y.
double redefinedHeadingOf(const Quat& q_nb);

// Eq. 3.12: h(q) = (-z)ᵀ q (-z) q*, the height of the head of a unit-length person:
// 1 standing, 0 lying flat, -1 upside down. It is element (3,3) of R(q) = M(q)ᵀ. (Eq. 3.13
// prints it as -DCM(3,3), which would give -1 standing; eq. 3.12 and the text fix the sign.)
double headHeight(const Quat& q_nb);

// Chooses the definition with hysteresis (§6.2: enter below 0.6, leave above 0.7).
class HeadingDefinitionSelector {
 public:
  HeadingDefinitionSelector(double enter_below, double leave_above)
      : enter_below_(enter_below), leave_above_(leave_above) {}
  bool update(const Quat& q_nb);
  bool redefined() const { return redefined_; }

 private:
  double enter_below_;
  double leave_above_;
  bool redefined_ = false;
};

}  // namespace headingd::core
