#pragma once
// Heading and its redefinition for lying-down poses (Henriksson §2.5.2, §3.3), for a head
// axis given in sensor axes: the documented mounting's -z (the thesis), or the person's up
// axis learned while walking (body_up_axis.hpp).
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// The head of a person wearing a sensor mounted as documented (x forward, z down): its -z
// axis (§3.3, eq. 3.12).
inline const Vec3 kDocumentedHeadAxis{0.0, 0.0, -1.0};

// Definition 2.5.1: angle from north of the body x-axis projected on the horizontal plane.
double headingOf(const Quat& q_nb);

// Definition 3.3.1 for any head axis (unit, sensor axes): the angle from north of the head
// axis projected on the horizontal plane. Eqs. 3.9-3.11 turn the attitude by q_y (90° about
// y, which takes x onto -z) so that x stands where the head is and take the heading of
// q ⊗ q_y; for a general axis that is the heading of the axis itself, computed directly.
// Undefined (any value) while the axis is vertical: use it lying down only.
double headingOfAxis(const Quat& q_nb, const Vec3& head_axis_s);

// Eq. 3.12 for any head axis: h(q) = (up_n)ᵀ q a q*, the height of the head of a unit-length
// person: 1 standing, 0 lying flat, -1 upside down. For a = -z it is element (3,3) of
// R(q) = M(q)ᵀ. (Eq. 3.13 prints it as -DCM(3,3), which would give -1 standing; eq. 3.12
// and the text fix the sign.)
double headHeight(const Quat& q_nb, const Vec3& head_axis_s);

// Chooses the definition with hysteresis (§6.2: enter below 0.6, leave above 0.7), entering
// only once h has stayed below enter_below for enter_after_s: lying down is a pose that
// lasts, and a swung or running phone dips below it for a second at a time (the heading of
// the head axis, near vertical then, is no heading). Leaving is at once.
class HeadingDefinitionSelector {
 public:
  HeadingDefinitionSelector(double enter_below, double leave_above, double enter_after_s = 0.0)
      : enter_below_(enter_below), leave_above_(leave_above), enter_after_s_(enter_after_s) {}
  // head_height: h of eq. 3.12 this sample; dt_s: the time since the previous sample.
  bool update(double head_height, double dt_s);
  bool redefined() const { return redefined_; }

 private:
  double enter_below_;
  double leave_above_;
  double enter_after_s_;
  double below_s_ = 0.0;  // how long h has been below enter_below
  bool redefined_ = false;
};

}  // namespace headingd::core
