#include "headingd/core/heading_definition.hpp"

#include <cmath>

namespace headingd::core {

double headingOf(const Quat& q_nb) { return yawZyx(q_nb); }

double headingOfAxis(const Quat& q_nb, const Vec3& head_axis_s) {
  const Vec3 head_n = q_nb * head_axis_s;     // eq. 3.11's q ⊗ q_y applied to x
  return std::atan2(head_n.y(), head_n.x());  // definition 3.3.1
}

double headHeight(const Quat& q_nb, const Vec3& head_axis_s) {
  return -(q_nb * head_axis_s).z();  // eq. 3.12: NED up is -z_n
}

bool HeadingDefinitionSelector::update(double head_height, double dt_s) {
  below_s_ = head_height < enter_below_ ? below_s_ + dt_s : 0.0;
  if (!redefined_ && head_height < enter_below_ && below_s_ >= enter_after_s_) {
    redefined_ = true;
  } else if (redefined_ && head_height > leave_above_) {
    redefined_ = false;
  }
  return redefined_;
}

}  // namespace headingd::core
