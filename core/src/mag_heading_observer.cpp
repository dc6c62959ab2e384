#include "headingd/core/mag_heading_observer.hpp"

#include <cmath>

#include "headingd/core/heading_definition.hpp"

namespace headingd::core {

MagHeadingMeasurement measureMagHeading(const Quat& q_nb, const Vec3& mag_uT, double min_horizontal_fraction) {
  MagHeadingMeasurement m;
  const Vec3 field_n = q_nb * mag_uT;
  const double total = field_n.norm();
  m.horizontal_uT = field_n.head<2>().norm();
  if (!(total > 0.0) || m.horizontal_uT < min_horizontal_fraction * total) return m;
  m.dip_rad = std::atan2(field_n.z(), m.horizontal_uT);
  m.innovation_rad = -std::atan2(field_n.y(), field_n.x());
  m.measured_heading_rad = wrapAngle(headingOf(q_nb) + m.innovation_rad);
  m.valid = true;
  return m;
}

double magObserverGain(double dt_s, double time_constant_s) { return 1.0 - std::exp(-dt_s / time_constant_s); }

Quat applyHeadingCorrection(const Quat& q_nb, double innovation_rad, double gain) {
  return (headingRotation(gain * innovation_rad) * q_nb).normalized();
}

}  // namespace headingd::core
