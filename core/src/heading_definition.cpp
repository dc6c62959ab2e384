#include "headingd/core/heading_definition.hpp"

#include <cmath>

namespace headingd::core {

double headingOf(const Quat& q_nb) { return yawZyx(q_nb); }

double redefinedHeadingOf(const Quat& q_nb) {
  const double h = std::sqrt(0.5);
  const Quat q_y(h, 0.0, h, 0.0);  // eq. 3.10
  return headingOf(q_nb * q_y);    // eq. 3.11
}

double headHeight(const Quat& q_nb) {
  const double q0 = q_nb.w(), q1 = q_nb.x(), q2 = q_nb.y(), q3 = q_nb.z();
  return q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3;
}

bool HeadingDefinitionSelector::update(const Quat& q_nb) {
  const double height = headHeight(q_nb);
  if (!redefined_ && height < enter_below_) {
    redefined_ = true;
  } else if (redefined_ && height > leave_above_) {
    redefined_ = false;
  }
  return redefined_;
}

}  // namespace headingd::core
